// Sizes and masses at the edges of what the loader accepts (haif/body_limits.h): bodies of 1 mm
// and 1 km, of 1e-9 and 1e12 kg, spinning, landing and resting on the ground stay finite and rest.
// A float inverse of their inertia tensors was NaN on the first step (the determinant under- or
// overflowed).
#include "haif/body_limits.h"
#include "support/physics_test_util.h"

#include <cmath>

namespace haif::test {
namespace {

struct Corner {
  float size, mass;
};

class BodySizes : public ::testing::TestWithParam<Corner> {};

TEST_P(BodySizes, LandAndRestWithoutNaN) {
  const Corner c = GetParam();
  World w;
  BodyDef ground;  // wide enough for two bodies of the largest size
  ground.kind = BodyKind::Static;
  ground.shape = Shape::box(Vec3(10.0f * c.size + 10.0f, 1.0f, 10.0f * c.size + 10.0f));
  ground.xf.p = Vec3(0.0f, -1.0f, 0.0f);
  w.addBody(ground);
  const float h = 0.5f * c.size;
  BodyDef box;
  box.shape = Shape::box(Vec3::Constant(h));
  box.xf.p = Vec3(0.0f, h + std::min(0.5f * h, 1.0f), 0.0f);
  box.mass = c.mass;
  box.angularVelocity = Vec3(0.0f, 3.0f, 0.0f);
  const uint32_t b = w.addBody(box);
  BodyDef ball;
  ball.shape = Shape::sphere(h);
  ball.xf.p = Vec3(3.0f * c.size, h + std::min(0.2f * h, 1.0f), 0.0f);
  ball.mass = c.mass;
  ball.linearVelocity = Vec3(0.1f * c.size, 0.0f, 0.0f);
  const uint32_t s = w.addBody(ball);
  for (int i = 0; i < 240; ++i) {
    w.step();
    for (const uint32_t id : {b, s}) {
      ASSERT_TRUE(isFinite(w.bodies().xf[id].p) && isFinite(w.bodies().v[id]) && isFinite(w.bodies().w[id]))
          << "step " << i << ", body " << id;
    }
  }
  // Landed, resting on its face (within the slop or 1% of its size) and no longer falling.
  const float tol = std::max(0.006f, 0.01f * c.size);
  EXPECT_NEAR(w.bodies().xf[b].p.y(), h, tol);
  EXPECT_NEAR(w.bodies().xf[s].p.y(), h, tol);
  EXPECT_LT(std::fabs(w.bodies().v[b].y()), 0.05f);
}

INSTANTIATE_TEST_SUITE_P(Corners, BodySizes,
                         ::testing::Values(Corner{kMinBodySize, kMinBodyMass}, Corner{kMinBodySize, kMaxBodyMass},
                                           Corner{kMaxBodySize, kMinBodyMass}, Corner{kMaxBodySize, kMaxBodyMass},
                                           Corner{kMinBodySize, 1.0f}, Corner{kMaxBodySize, 1e9f}),
                         [](const ::testing::TestParamInfo<Corner>& i) { return "case" + std::to_string(i.index); });

TEST(BodyInertia, InverseIsFiniteAtTheCornersOfTheSupportedSizes) {
  // The tensor of a 1 mm, 1e-9 kg box (1.7e-16 kg m^2) has a determinant below float's range, and
  // that of a 1 km, 1e12 kg box above it.
  for (const Corner c : {Corner{kMinBodySize, kMinBodyMass}, Corner{kMaxBodySize, kMaxBodyMass}}) {
    const float i = c.mass * c.size * c.size / 6.0f;
    BodyStore bodies;
    bodies.add(BodyKind::Dynamic, Transform(), c.mass, Mat3::Identity() * i);
    EXPECT_NEAR(bodies.invInertiaLocal[0](0, 0) * i, 1.0f, 1e-5f) << c.size << " m, " << c.mass << " kg";
    EXPECT_TRUE(bodies.invInertiaWorld[0].allFinite());
  }
}

}  // namespace
}  // namespace haif::test
