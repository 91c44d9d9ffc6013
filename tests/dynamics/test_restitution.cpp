// Restitution: a ball dropped from h rebounds to e^2 h (v' = -e v at impact).
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

// Height of the sphere's bottom at the top of its first rebound (0 if it never left the ground).
float firstReboundHeight(float e, float h) {
  World w;
  addGround(w, 0.6f, e);
  BodyDef d;
  d.shape = Shape::sphere(0.5f);
  d.mass = 1.0f;
  d.restitution = e;
  d.xf.p = Vec3(0.0f, 0.5f + h, 0.0f);
  const uint32_t ball = w.addBody(d);
  bool bounced = false;
  float peak = 0.0f;
  for (int s = 0; s < 240; ++s) {
    const float vyBefore = w.bodies().v[ball].y();
    w.step();
    const float vy = w.bodies().v[ball].y();
    if (!bounced && vyBefore < -1.0f && vy > 0.0f) bounced = true;  // the impact reversed the velocity
    if (bounced) {
      peak = std::max(peak, w.bodies().xf[ball].p.y() - 0.5f);
      if (vy < 0.0f && vyBefore >= 0.0f) break;  // past the apex
    }
  }
  return peak;
}

class Bounce : public ::testing::TestWithParam<float> {};

TEST_P(Bounce, ReboundsToESquaredH) {
  const float e = GetParam(), h = 2.0f;
  const float got = firstReboundHeight(e, h), want = e * e * h;
  EXPECT_NEAR(got, want, 0.15f * want) << "e = " << e << ": rebound " << got << " m, expected " << want << " m";
}

INSTANTIATE_TEST_SUITE_P(Restitution, Bounce, ::testing::Values(0.5f, 0.8f));

TEST(Restitution, ZeroDoesNotBounce) {
  const float got = firstReboundHeight(0.0f, 2.0f);
  EXPECT_LT(got, 0.01f) << "restitution 0 rebounded " << got << " m";
}

}  // namespace
}  // namespace haif::test
