// The reference scenes of docs/reference_scenes.md: exact counts and positions from the stated formulas.
#include "scene_test_util.h"

#include <cmath>

namespace haif::test {
namespace {

Vec3 f3(double x, double y, double z) { return Vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)); }

void expectCommonSettings(const SceneDesc& s) {
  EXPECT_NEAR(s.settings.world.dt, 1.0 / 60.0, 1e-9);
  EXPECT_EQ(s.settings.world.gravity, Vec3(0.0f, -9.81f, 0.0f));
  EXPECT_EQ(s.settings.world.iterations, 10);
  EXPECT_FALSE(s.settings.world.sleeping);
  EXPECT_FLOAT_EQ(s.materials[0].friction, 0.6f);
  // The reference ground: one static box, half (500, 1, 500) at y = -1.
  ASSERT_EQ(countMotion(s, MotionType::Static), 1);
  for (const BodyDesc& b : s.bodies)
    if (b.motion == MotionType::Static) {
      EXPECT_EQ(b.shape.type, ShapeType::Box);
      EXPECT_EQ(b.shape.halfExtents, Vec3(500, 1, 500));
      EXPECT_EQ(b.position, Vec3(0, -1, 0));
    }
}

std::vector<const BodyDesc*> dynamicBodies(const SceneDesc& s) {
  std::vector<const BodyDesc*> out;
  for (const BodyDesc& b : s.bodies)
    if (b.motion == MotionType::Dynamic) out.push_back(&b);
  return out;
}

class Stacks : public ::testing::TestWithParam<int> {};

TEST_P(Stacks, ExactLayout) {
  const int n = GetParam();
  const SceneDesc s = loadReferenceScene("stacks_" + std::to_string(n) + ".json");
  expectCommonSettings(s);
  const auto boxes = dynamicBodies(s);
  ASSERT_EQ(static_cast<int>(boxes.size()), n);
  const int k = static_cast<int>(std::ceil(std::sqrt(std::ceil(n / 10.0))));
  for (int i = 0; i < n; ++i) {
    const BodyDesc& b = *boxes[static_cast<size_t>(i)];
    const int stack = i / 10, h = i % 10;
    EXPECT_EQ(b.position, f3(3.0 * (stack % k), 0.5 + 1.01 * h, 3.0 * (stack / k))) << "box " << i;
    EXPECT_EQ(b.shape.type, ShapeType::Box);
    EXPECT_EQ(b.shape.halfExtents, Vec3::Constant(0.5f));
    EXPECT_EQ(b.mass, 1.0f);
    EXPECT_TRUE(b.orientation.coeffs() == Quat::Identity().coeffs());
  }
  // A few spelled out: the top of the first stack and the first box of the last stack.
  EXPECT_EQ(boxes[9]->position, Vec3(0.0f, 9.59f, 0.0f));
  if (n == 2000) {
    EXPECT_EQ(k, 15);
    EXPECT_EQ(boxes[1990]->position, Vec3(3.0f * (199 % 15), 0.5f, 3.0f * (199 / 15)));
  }
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, Stacks, ::testing::Values(100, 500, 1000, 2000));

TEST(ReferenceScenes, Pyramid15) {
  const SceneDesc s = loadReferenceScene("pyramid_15.json");
  expectCommonSettings(s);
  const auto boxes = dynamicBodies(s);
  ASSERT_EQ(boxes.size(), 1240u);
  size_t n = 0;
  for (int i = 0; i < 15; ++i) {
    const double shift = (i % 2 == 1) ? 1.0 : 0.0;
    for (int j = i / 2; j <= 14 - (i + 1) / 2; ++j)
      for (int k = i / 2; k <= 14 - (i + 1) / 2; ++k) {
        const BodyDesc& b = *boxes[n++];
        ASSERT_EQ(b.position, f3(-15 + 2 * j + shift, 1 + 2.5 * i, -15 + 2 * k + shift)) << "layer " << i;
        EXPECT_EQ(b.shape.halfExtents, Vec3::Constant(1.0f));
        EXPECT_EQ(b.mass, 8.0f);
      }
  }
  EXPECT_EQ(boxes.front()->position, Vec3(-15, 1, -15));
  EXPECT_EQ(boxes.back()->position, Vec3(-15 + 14 + 0, 1 + 2.5f * 14, -15 + 14));
}

TEST(ReferenceScenes, LargePyramid) {
  const SceneDesc s = loadReferenceScene("large_pyramid.json");
  expectCommonSettings(s);
  const auto boxes = dynamicBodies(s);
  ASSERT_EQ(boxes.size(), 5050u);
  size_t n = 0;
  for (int i = 0; i < 100; ++i)
    for (int j = i; j < 100; ++j) {
      ASSERT_EQ(boxes[n++]->position, f3(0.5 * (i + 1) + (j - i) - 50, i + 0.5, 0)) << i << "," << j;
    }
  EXPECT_EQ(boxes.front()->position, Vec3(-49.5f, 0.5f, 0.0f));
  EXPECT_EQ(boxes.back()->position, Vec3(0.0f, 99.5f, 0.0f));
  EXPECT_EQ(boxes.back()->mass, 1.0f);
  EXPECT_EQ(boxes.back()->shape.halfExtents, Vec3::Constant(0.5f));
}

TEST(ReferenceScenes, ManyPyramids) {
  const SceneDesc s = loadReferenceScene("many_pyramids.json");
  expectCommonSettings(s);
  const auto boxes = dynamicBodies(s);
  ASSERT_EQ(boxes.size(), 10780u);
  const double G = 0.5 * 14 * 11;
  ASSERT_EQ(G, 77.0);
  size_t n = 0;
  for (int r = 0; r < 14; ++r) {
    const double z = -G + 1 + r * 2 * (G - 1) / 13;
    for (int xc = 0; xc < 14; ++xc) {
      const double cx = -G + xc * 11 + 1;
      const size_t first = n;
      for (int i = 0; i < 10; ++i)
        for (int j = i; j < 10; ++j)
          ASSERT_EQ(boxes[n++]->position, f3(cx + 0.5 * (i + 1) + (j - i) - 0.5, i + 0.5, z)) << r << "," << xc;
      // First box of a pyramid: its bottom-left corner cube; last: the apex.
      EXPECT_EQ(boxes[first]->position, f3(cx, 0.5, z));
      EXPECT_EQ(boxes[n - 1]->position, f3(cx + 4.5, 9.5, z));
    }
  }
  EXPECT_EQ(boxes.front()->position, Vec3(-76.0f, 0.5f, -76.0f));
  EXPECT_EQ(boxes.back()->position, Vec3(67.0f + 4.5f, 9.5f, 76.0f));
}

}  // namespace
}  // namespace haif::test
