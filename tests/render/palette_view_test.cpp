// Body colours and automatic framing: deterministic, in range, whole scene inside the frustum.
#include <gtest/gtest.h>

#include "render/palette.h"
#include "render/view_setup.h"

namespace haif::render {
namespace {

TEST(Palette, ColourPerIdIsDeterministicAndVaried) {
  const LinearColor a = idColor(7), b = idColor(7);
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(a.b, b.b);
  int distinct = 0;
  for (uint32_t i = 0; i < 20; ++i) {
    const LinearColor c = idColor(i), d = idColor(i + 1);
    distinct += std::fabs(c.r - d.r) + std::fabs(c.g - d.g) + std::fabs(c.b - d.b) > 0.05f;
    EXPECT_GE(c.r, 0.f);
    EXPECT_LE(c.r, 1.f);
  }
  EXPECT_GE(distinct, 15) << "neighbouring ids should mostly differ";
}

TEST(Palette, HeatIsClampedAndMonotoneInBrightness) {
  const LinearColor lo = heatColor(-1.f), zero = heatColor(0.f), hi = heatColor(2.f), one = heatColor(1.f);
  EXPECT_EQ(lo.g, zero.g);
  EXPECT_EQ(hi.g, one.g);
  EXPECT_LT(zero.r + zero.g + zero.b, one.r + one.g + one.b);
  const LinearColor nan = heatColor(NAN);
  EXPECT_EQ(nan.g, zero.g);
}

TEST(Palette, SrgbConversionsInvertEachOther) {
  for (float v : {0.f, 0.002f, 0.2f, 0.5f, 1.f}) EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 1e-5f);
}

TEST(ViewSetup, AutomaticFramingKeepsEveryCornerOnScreen) {
  SceneBounds b;
  b.add({-30.f, 0.5f, 2.f}, 0.9f);
  b.add({25.f, 9.f, -4.f}, 0.9f);
  Camera cam;
  const ViewSetup v = computeView(cam, b, 1280, 720);
  EXPECT_GT(v.eye.y, b.max.y) << "view from above";
  for (int i = 0; i < 8; ++i) {
    const Vec3 c{(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z};
    const float* m = v.viewProj.m;
    const float x = m[0] * c.x + m[4] * c.y + m[8] * c.z + m[12];
    const float y = m[1] * c.x + m[5] * c.y + m[9] * c.z + m[13];
    const float w = m[3] * c.x + m[7] * c.y + m[11] * c.z + m[15];
    ASSERT_GT(w, 0.f);
    EXPECT_LE(std::fabs(x / w), 1.f) << "corner " << i;
    EXPECT_LE(std::fabs(y / w), 1.f) << "corner " << i;
  }
}

}  // namespace
}  // namespace haif::render
