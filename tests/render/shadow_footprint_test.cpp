// groundShadowRect: every point of a caster box's shadow on the ground projects inside the
// rectangle, which is much smaller than the image for a compact scene; unbounded cases give all.
#include <gtest/gtest.h>

#include <cmath>

#include "render/shadow_footprint.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

ViewSetup viewFrom(Vec3 eye, Vec3 target, int w, int h) { return test::viewFrom(eye, target, w, h, 2.f); }

const Vec3 kSun = normalize({-0.45f, 0.82f, -0.30f});

GroundFace ground() {
  GroundFace g;
  g.halfU = g.halfV = 500.f;
  return g;
}

TEST(ShadowFootprint, ContainsTheShadowOfEveryPointOfTheCasters) {
  const int w = 640, h = 360;
  const ViewSetup v = viewFrom({-8.f, 7.f, 12.f}, {0.f, 1.f, 0.f}, w, h);
  SceneBounds casters;
  casters.min = {-1.f, 0.f, -1.5f}, casters.max = {1.f, 3.f, 1.5f}, casters.valid = true;
  const PixelRect r = groundShadowRect(v, w, h, casters, kSun, ground(), 0.f);
  ASSERT_FALSE(r.empty());
  EXPECT_LT((r.x1 - r.x0) * (r.y1 - r.y0), w * h / 2) << "a compact scene leaves most of the ground out";
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 10; ++k) {
        const Vec3 p{-1.f + 0.2f * i, 0.3f * j, -1.5f + 0.3f * k};
        const Vec3 s = p - kSun * (p.y / kSun.y);  // its shadow on y = 0
        const float* m = v.viewProj.m;
        const float cw = m[3] * s.x + m[7] * s.y + m[11] * s.z + m[15];
        const float x = ((m[0] * s.x + m[4] * s.y + m[8] * s.z + m[12]) / cw * 0.5f + 0.5f) * w;
        const float y = ((m[1] * s.x + m[5] * s.y + m[9] * s.z + m[13]) / cw * 0.5f + 0.5f) * h;
        if (x < 0.f || y < 0.f || x >= w || y >= h) continue;  // off screen
        EXPECT_TRUE(x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) << "shadow of " << i << "," << j << "," << k;
      }
}

TEST(ShadowFootprint, WholeImageWhenItCannotBeBounded) {
  const int w = 320, h = 240;
  SceneBounds casters;
  casters.min = {-1.f, 0.f, -1.f}, casters.max = {1.f, 2.f, 1.f}, casters.valid = true;
  auto isWhole = [&](const PixelRect& r) { return r.x0 == 0 && r.y0 == 0 && r.x1 == w && r.y1 == h; };
  const ViewSetup v = viewFrom({-8.f, 7.f, 12.f}, {0.f, 1.f, 0.f}, w, h);
  EXPECT_TRUE(isWhole(groundShadowRect(v, w, h, casters, {0.f, -1.f, 0.f}, ground(), 0.f))) << "sun below";
  EXPECT_TRUE(isWhole(groundShadowRect(v, w, h, casters, normalize({1.f, 0.01f, 0.f}), ground(), 0.f)))
      << "grazing sun: the shadow runs off to the horizon";
  // Camera standing inside the shadow looking away from it: part of the shadow is behind.
  const ViewSetup inside = viewFrom({1.5f, 1.f, 1.f}, {8.f, 1.f, 8.f}, w, h);
  EXPECT_TRUE(isWhole(groundShadowRect(inside, w, h, casters, kSun, ground(), 0.f)));
}

}  // namespace
}  // namespace haif::render
