// The bound on every body's speed (haif/speed_bound.h): it follows what the scene can give a body, it
// slows only bodies over it, and it keeps a crushed body from being shot out.
#include "haif/speed_bound.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace haif;
using namespace haif::test;

namespace {

float surfaceSpeed(const World& w, uint32_t i, float reach) {
  return w.bodies().v[i].norm() + w.bodies().w[i].norm() * reach;
}

}  // namespace

TEST(SpeedBound, LimitGrowsWithStartSpeedFallAndKinematicSurfaces) {
  WorldSettings ws;
  World w(ws);
  addGround(w);
  BodyDef d;
  d.shape = Shape::sphere(0.5f);
  d.xf.p = Vec3(0.0f, 20.5f, 0.0f);
  d.linearVelocity = Vec3(3.0f, 0.0f, 0.0f);
  w.addBody(d);
  w.step();
  const float factor = ws.speedBound.factor, floor = ws.speedBound.floor;
  // A body's reach is its bounding box's half diagonal: the fall counts from its highest to its
  // lowest point (it may tip over on the way).
  const float reach = 0.5f * std::sqrt(3.0f);
  EXPECT_NEAR(w.speedLimit(), factor * (3.0f + std::sqrt(2.0f * 9.81f * 2.0f * reach)) + floor, 0.5f);
  for (int i = 0; i < 150; ++i) w.step();  // it has landed: a fall of 20 m
  const float fall = std::sqrt(2.0f * 9.81f * (20.0f + 2.0f * reach));
  EXPECT_NEAR(w.speedLimit(), factor * (3.0f + fall) + floor, 0.05f * fall * factor);
  // A kinematic plate sweeping at 7 m/s may hit bodies at twice its speed.
  addKinematicBox(w, Vec3(50.0f, 5.0f, 0.0f), Vec3(1.0f, 0.1f, 1.0f), Vec3(7.0f, 0.0f, 0.0f));
  w.step();
  EXPECT_NEAR(w.speedLimit(), factor * (3.0f + fall + 14.0f) + floor, 0.05f * fall * factor);
}

TEST(SpeedBound, SlowsOnlyBodiesOverTheLimitAlongTheirMotionAndStopsNaN) {
  BodyStore bodies;
  for (int i = 0; i < 3; ++i) {
    bodies.add(BodyKind::Dynamic, Transform(), 1.0f, Mat3::Identity());
  }
  SpeedBound bound;
  for (int i = 0; i < 3; ++i) bound.addBody(Shape::sphere(1.0f));
  bodies.v[0] = Vec3(1.0f, 0.0f, 0.0f);  // the fastest start: 1 m/s
  bound.update(bodies, Vec3::Zero(), 1.0f / 60.0f, 0.0f, std::numeric_limits<float>::infinity());
  const float limit = bound.limit();
  EXPECT_FLOAT_EQ(limit, bound.settings.factor * 1.0f + bound.settings.floor);
  bodies.v[1] = Vec3(0.0f, 3.0f * limit, 0.0f);
  bodies.w[1] = Vec3(0.0f, 0.0f, 1.0f * limit);  // reach sqrt(3) m (bounding box): surface speed 4.7 limit
  bodies.v[2] = Vec3(std::nanf(""), 0.0f, 0.0f);
  EXPECT_EQ(bound.apply(bodies, 0, 3), 2u);
  EXPECT_EQ(bodies.v[0], Vec3(1.0f, 0.0f, 0.0f)) << "a body under the limit is untouched";
  EXPECT_NEAR(bodies.v[1].y() + std::sqrt(3.0f) * bodies.w[1].z(), limit, 1e-4f * limit) << "slowed to the limit";
  EXPECT_NEAR(bodies.v[1].y() / bodies.w[1].z(), 3.0f, 1e-4f) << "along its own motion";
  EXPECT_EQ(bodies.v[2], Vec3::Zero()) << "a NaN velocity is stopped";
}

TEST(SpeedBound, CrushedBoxIsNotShotOut) {
  // A kinematic slab comes down at 2 m/s onto a box on the ground and passes through where the box
  // is: no solution exists. The box must leave at a bounded speed, never faster than the bound, and
  // the steps where the bound acts are counted.
  World w;
  addGround(w);
  const uint32_t box = addBox(w, Vec3(0.0f, 0.5f, 0.0f), Vec3::Constant(0.5f), 1.0f);
  addKinematicBox(w, Vec3(0.0f, 1.5f, 0.0f), Vec3(3.0f, 0.25f, 3.0f), Vec3(0.0f, -2.0f, 0.0f));
  float fastest = 0.0f;
  const float reach = std::sqrt(3.0f) * 0.5f;
  for (int i = 0; i < 90; ++i) {
    w.step();
    const float s = surfaceSpeed(w, box, reach);
    ASSERT_TRUE(std::isfinite(s)) << "step " << i;
    EXPECT_LE(s, w.speedLimit() * 1.0001f) << "step " << i;
    fastest = std::max(fastest, s);
  }
  EXPECT_LE(fastest, 2.0f * (2.0f * 2.0f) + 2.0f + 1e-3f) << "2 x (2 x the slab's speed) + floor";
}

TEST(SpeedBound, ABodyFallingOutOfTheSceneDoesNotLoosenTheBound) {
  // A ball dropped beside the ground falls forever. Counted to wherever it is, the fall term grew
  // without end and loosened the bound for every body (a swept pit lost bodies through its floor and
  // its bound reached hundreds of m/s); it stops at the lowest static geometry (the ground's bottom).
  // Nor is the ball itself slowed once it is wholly below that: it can strike nothing there, and
  // counting it reported the bound acting every step of a swept pit whose spheres rolled off the
  // ground's edge (1596 times in 3600 steps), hiding any real act.
  World w;
  addGround(w);  // top at y = 0, bottom at y = -2
  addSphere(w, Vec3(600.0f, 5.0f, 0.0f), 0.5f);
  uint32_t limited = 0;
  for (int i = 0; i < 300; ++i) {
    w.step();
    limited += w.lastStats().speedLimited;
  }
  EXPECT_LT(w.bodies().xf[1].p.y(), -50.0f) << "the ball should have fallen far past the ground";
  EXPECT_EQ(limited, 0u);
  EXPECT_NEAR(w.bodies().v[1].norm(), 9.81f * 300.0f * w.settings().dt, 0.01f) << "it falls freely";
  EXPECT_GT(w.bodies().v[1].norm(), w.speedLimit()) << "faster than the bound (else this tests nothing)";
  const float reach = 0.5f * std::sqrt(3.0f);
  const float fall = 5.0f + reach + 2.0f;  // from its top at the start to the ground's bottom
  const SpeedBoundSettings s;
  EXPECT_NEAR(w.speedLimit(), s.factor * std::sqrt(2.0f * 9.81f * fall) + s.floor, 0.01f);
}

namespace {

// A car: a 600 kg chassis on four 15 kg wheels of radius 0.4 m, each turned by a hinge motor at
// `spin` rad/s (forwards along +x). Returns the chassis.
uint32_t addCar(World& w, float z, float spin) {
  const uint32_t chassis = addBox(w, Vec3(0.0f, 0.75f, z), Vec3(1.5f, 0.25f, 0.8f), 600.0f);
  for (float dx : {-1.1f, 1.1f}) {
    for (float dz : {-0.95f, 0.95f}) {
      const Vec3 hub(dx, 0.4f, z + dz);
      const uint32_t wheel = addSphere(w, hub, 0.4f, 15.0f);
      JointDef j = jointAtWorld(JointType::Hinge, chassis, wheel, w.bodies().xf[chassis], w.bodies().xf[wheel], hub,
                                Vec3::UnitZ(), hub);
      j.motorEnabled = true;
      j.motorSpeed = -spin;
      j.maxMotorForce = 600.0f;
      w.addJoint(j);
    }
  }
  return chassis;
}

}  // namespace

TEST(SpeedBound, AMotorDrivenCarReachesItsMotorsSpeed) {
  // A motor is a source of speed like a kinematic surface. Left out of the bound, a car whose wheels
  // were driven at 20 m/s was held at 8.7 m/s (the bound of its fall) and slowed every step.
  World w;
  addGround(w, 1.0f);
  const float spin = 50.0f, radius = 0.4f;  // 20 m/s
  const uint32_t car = addCar(w, 0.0f, spin);
  uint32_t limited = 0;
  for (int i = 0; i < 360; ++i) {
    w.step();
    limited += w.lastStats().speedLimited;
  }
  EXPECT_EQ(limited, 0u) << "the bound slowed the car";
  EXPECT_NEAR(w.bodies().v[car].x(), spin * radius, 0.03f * spin * radius) << "it drives at its wheels' speed";
  EXPECT_NEAR(w.bodies().xf[car].p.y(), 0.75f, 0.02f) << "on its wheels";
}

TEST(SpeedBound, MotorsOfOneIslandAddUpAndIslandsDoNot) {
  // The motors of an island move a surface at most at the sum of their aims times their levers (an
  // arm's joints turn in series); two islands apart do not add. Each world is measured against the
  // same cars with their motors at rest.
  const float lever = 0.4f * std::sqrt(3.0f);  // a wheel's reach: its bounding box's half diagonal
  const SpeedBoundSettings s;
  auto limitOf = [](int cars, float spin) {
    World w;
    addGround(w, 1.0f);
    for (int c = 0; c < cars; ++c) addCar(w, 5.0f * float(c), spin);
    w.step();
    return w.speedLimit();
  };
  for (int cars : {1, 2}) {
    const float motors = (limitOf(cars, 10.0f) - limitOf(cars, 0.0f)) / s.factor;
    EXPECT_NEAR(motors, 2.0f * 4.0f * 10.0f * lever, 1e-3f) << cars << " cars: twice one car's four wheels";
  }
}
