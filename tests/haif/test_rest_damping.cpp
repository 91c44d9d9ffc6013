// Rest damping (haif/rest_damping.h): the creep a solve leaves in a resting pile is taken away, and
// nothing that really moves is touched.
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace haif;
using namespace haif::test;

namespace {

// RMS out-of-plane (z) displacement of a 40-box-base wall pyramid after `steps` steps at the
// 4-iteration floor of the adaptive controller.
float outOfPlaneDrift(float restDamping, int steps) {
  WorldSettings ws;
  ws.iterations = 4;
  ws.restDamping = restDamping;
  World w(ws);
  addGround(w);
  addPyramid2d(w, 40);
  for (int i = 0; i < steps; ++i) w.step();
  double z2 = 0.0;
  int n = 0;
  for (uint32_t b = 0; b < w.bodyCount(); ++b) {
    if (!w.bodies().isDynamic(b)) continue;
    z2 += double(w.bodies().xf[b].p.z()) * w.bodies().xf[b].p.z();
    ++n;
  }
  return float(std::sqrt(z2 / n));
}

// Speed of a sphere (r 0.5 m) rolling on the ground without slipping from `speed` m/s, after 5 s.
float rollingSpeedAfter5s(float speed) {
  World w;
  addGround(w);
  const uint32_t ball = addSphere(w, Vec3(0.0f, 0.5f, 0.0f));
  w.bodies().v[ball] = Vec3(speed, 0.0f, 0.0f);
  w.bodies().w[ball] = Vec3(0.0f, 0.0f, -speed / 0.5f);  // v = ω × r: rolling
  for (int i = 0; i < 300; ++i) w.step();
  return w.bodies().v[ball].norm();
}

}  // namespace

TEST(RestDamping, AWallPyramidDoesNotLeanOutOfItsPlane) {
  // The wall is one box deep. The sweeps' leftover load sank the loaded edges, the lean moved load
  // onto them, and the lean grew from float noise ~1.3 % a step (×3.7 every 100 steps) until the
  // large pyramid fell (docs/solver.md, "Rest damping").
  const float damped = outOfPlaneDrift(WorldSettings{}.restDamping, 600);  // the default
  EXPECT_LT(damped, 1e-6f) << "float noise, not a lean";
  const float control = outOfPlaneDrift(0.0f, 600);
  EXPECT_GT(control, 100.0f * damped) << "the control leans (else the test no longer tests it)";
}

TEST(RestDamping, ARollingBallAboveTheRestSpeedKeepsItsSpeed) {
  // The rest speed is 5 % of g dt: 8.2 mm/s at 60 Hz. A ball rolling at 2 cm/s is real motion and
  // keeps it (a rolling ball on a level floor meets no friction loss here); one at 0.5 mm/s is
  // the creep the damping exists for and stops.
  EXPECT_NEAR(rollingSpeedAfter5s(0.02f), 0.02f, 2e-4f);
  EXPECT_LT(rollingSpeedAfter5s(0.0005f), 1e-6f);
}

TEST(RestDamping, BodiesWithoutContactsAreNotDamped) {
  // A slow body in free flight (no gravity, nothing to touch) keeps its momentum exactly.
  WorldSettings ws;
  ws.gravity = Vec3::Zero();
  ws.restDamping = 1.0f;  // the largest allowed: any slow body in contact would be slowed
  World w(ws);
  const uint32_t box = addBox(w, Vec3(0.0f, 5.0f, 0.0f));
  w.bodies().v[box] = Vec3(1e-4f, 0.0f, 0.0f);
  for (int i = 0; i < 60; ++i) w.step();
  EXPECT_EQ(w.bodies().v[box].x(), 1e-4f);
}

TEST(RestDamping, APileOnAPlatformThatStartsMovingComesToRestOnIt) {
  // The same 40-box-base pyramid on a kinematic platform that moves at 0.5 m/s from the first step:
  // the pile's rest is the platform's motion, and speeds are damped relative to it. Measured
  // against the world the pile was never slow, and it still swayed by ±0.1 m/s after 900 steps.
  World w;
  const Vec3 platform(0.5f, 0.0f, 0.0f);
  addKinematicBox(w, Vec3(0.0f, -0.5f, 0.0f), Vec3(40.0f, 0.5f, 5.0f), platform);
  addPyramid2d(w, 40);
  for (int i = 0; i < 900; ++i) w.step();
  float off = 0.0f;
  for (uint32_t b = 0; b < w.bodyCount(); ++b)
    if (w.bodies().isDynamic(b)) off = std::max(off, (w.bodies().v[b] - platform).norm());
  EXPECT_LT(off, 0.02f);
  EXPECT_LT(maxContactDepth(w), 0.01f);
}

