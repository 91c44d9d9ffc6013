// skyStartNdc: the sky strip starts just below the ground's far edge, never where the ground does
// not cover, and the renderer leaves no pixel unpainted.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/sky_extent.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

using test::viewFrom;

GroundFace groundTop(float half) {
  GroundFace g;  // y = 0, normal +y
  g.halfU = g.halfV = half;
  return g;
}

TEST(SkyExtent, StartsJustBelowTheFarEdgeOfTheGround) {
  // Looking level from 1.5 m: the far edge (z = -500, 508 m away) is 1.5 / 508 below the horizon.
  const ViewSetup v = viewFrom({0.f, 1.5f, 8.f}, {0.f, 1.5f, 0.f});
  const float y = skyStartNdc(v, 240, {groundTop(500.f)});
  const float edge = -(1.5f / 508.f) / v.tanHalfFovY;
  EXPECT_LT(y, edge);
  EXPECT_GT(y, edge - 0.05f) << "a few pixels of margin only";
}

TEST(SkyExtent, WholeImageOrNothing) {
  // Looking steeply down onto a large ground: no sky at all.
  EXPECT_EQ(skyStartNdc(viewFrom({0.f, 10.f, 0.5f}, {0.f, 0.f, 0.f}), 240, {groundTop(500.f)}), 1.f);
  // From below the ground, without any ground, or with a ground too small to reach the corners
  // of the image: the sky strip covers the whole image.
  const ViewSetup level = viewFrom({0.f, 1.5f, 8.f}, {0.f, 1.5f, 0.f});
  EXPECT_EQ(skyStartNdc(viewFrom({0.f, -3.f, 8.f}, {0.f, 1.f, 0.f}), 240, {groundTop(500.f)}), -1.f);
  EXPECT_EQ(skyStartNdc(level, 240, {}), -1.f);
  EXPECT_EQ(skyStartNdc(level, 240, {groundTop(2.f)}), -1.f);
}

TEST(SkyExtent, TheHigherOfTwoGroundsCounts) {
  const ViewSetup v = viewFrom({0.f, 1.5f, 8.f}, {0.f, 1.5f, 0.f});
  const float big = skyStartNdc(v, 240, {groundTop(500.f)});
  const float small = skyStartNdc(v, 240, {groundTop(60.f)});
  EXPECT_LT(small, big);
  EXPECT_EQ(skyStartNdc(v, 240, {groundTop(60.f), groundTop(500.f)}), big);
}

}  // namespace
}  // namespace haif::render
