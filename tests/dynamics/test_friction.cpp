// Coulomb friction on a ramp: a box slides when tan(theta) > mu and sticks when tan(theta) < mu.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

struct RampResult {
  float along = 0.0f;   ///< displacement down the ramp (m)
  float across = 0.0f;  ///< sideways displacement (z), perpendicular to the slope line (m)
  float normal = 0.0f;  ///< displacement along the ramp normal (m): + lifts off, - sinks in
};

RampResult slideOnRamp(float mu, float thetaDeg, float seconds) {
  World w;
  addGround(w);
  const Ramp ramp = addRamp(w, thetaDeg, mu);
  const Vec3 up = ramp.up, uphill = ramp.uphill;
  // A flat box (half height 0.25) so it cannot tip over before it slides.
  BodyDef box;
  box.shape = Shape::box(Vec3(0.5f, 0.25f, 0.5f));
  box.mass = 1.0f;
  box.friction = mu;  // friction combines as sqrt(mu_a mu_b) = mu
  box.xf.q = ramp.q;
  box.xf.p = ramp.restingPlace(0.25f);
  const uint32_t b = w.addBody(box);
  const Vec3 start = box.xf.p;
  const int steps = int(seconds * 60.0f + 0.5f);
  for (int s = 0; s < steps; ++s) w.step();
  const Vec3 d = w.bodies().xf[b].p - start;
  return {-d.dot(uphill), std::abs(d.z()), d.dot(up)};
}

class Ramp : public ::testing::TestWithParam<float> {};

TEST_P(Ramp, SlidesAboveFrictionAngle) {
  const float mu = GetParam();
  const float thetaDeg = std::atan(mu) * 180.0f / kPi + 8.0f;
  const RampResult r = slideOnRamp(mu, thetaDeg, 2.0f);
  // Sliding block: a = g (sin - mu cos), distance a t^2 / 2.
  const float th = thetaDeg * kPi / 180.0f;
  const float expected = 0.5f * 9.81f * (std::sin(th) - mu * std::cos(th)) * 4.0f;
  EXPECT_GT(r.along, 0.5f) << "mu " << mu << ", " << thetaDeg << " deg: slid " << r.along << " m";
  EXPECT_NEAR(r.along, expected, 0.15f * expected) << "mu " << mu << ", " << thetaDeg << " deg";
  EXPECT_LT(r.across, 0.05f) << "left the slope line";
  EXPECT_LT(std::abs(r.normal), 0.02f) << "lifted off or sank into the ramp";
}

TEST_P(Ramp, SticksBelowFrictionAngle) {
  const float mu = GetParam();
  const float thetaDeg = std::atan(mu) * 180.0f / kPi - 8.0f;
  const RampResult r = slideOnRamp(mu, thetaDeg, 2.0f);
  EXPECT_LT(std::abs(r.along), 0.01f) << "mu " << mu << ", " << thetaDeg << " deg: crept " << r.along << " m";
  EXPECT_LT(r.across, 0.01f);
  EXPECT_LT(std::abs(r.normal), 0.01f);
}

INSTANTIATE_TEST_SUITE_P(Friction, Ramp, ::testing::Values(0.3f, 0.6f));

}  // namespace
}  // namespace haif::test
