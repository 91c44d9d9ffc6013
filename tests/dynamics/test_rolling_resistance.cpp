// Rolling resistance: a torque against a rolling body's roll of c_r N r. A body rolling without
// slipping then slows at c_r g / (1 + I / (m r²)) (a solid sphere: c_r g / 1.4) and holds still on a
// slope while tan θ ≤ c_r, as the laws say; shapes that do not roll are left as they were.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

constexpr float kG = 9.81f;

uint32_t addRoller(World& w, const Shape& shape, const Vec3& p, const Quat& q, float rollingResistance,
                   const Vec3& v = Vec3::Zero(), const Vec3& spin = Vec3::Zero()) {
  BodyDef d;
  d.shape = shape;
  d.xf.p = p;
  d.xf.q = q;
  d.mass = 1.0f;
  d.rollingResistance = rollingResistance;
  d.linearVelocity = v;
  d.angularVelocity = spin;
  return w.addBody(d);
}

// A ball of radius r rolling along +x at v0 without slipping (ω = -(v0 / r) z).
struct Roll {
  float distance = 0.0f;  ///< along x (m)
  float speed = 0.0f;     ///< at the end (m/s)
  float speedAt1s = 0.0f;
  float across = 0.0f;    ///< |z| (m)
};

Roll rollBall(float rollingResistance, float v0, float seconds) {
  World w;
  addGround(w);
  const float r = 0.5f;
  const uint32_t b =
      addRoller(w, Shape::sphere(r), Vec3(0, r, 0), Quat::Identity(), rollingResistance, Vec3(v0, 0, 0), Vec3(0, 0, -v0 / r));
  Roll out;
  const int steps = int(seconds * 60.0f + 0.5f);
  for (int s = 1; s <= steps; ++s) {
    w.step();
    if (s == 60) out.speedAt1s = w.bodies().v[b].norm();
  }
  out.distance = w.bodies().xf[b].p.x();
  out.speed = w.bodies().v[b].norm();
  out.across = std::abs(w.bodies().xf[b].p.z());
  return out;
}

TEST(RollingResistance, ABallSlowsAndStopsAsTheLawSays) {
  const float cr = 0.1f, v0 = 2.0f;
  const float a = cr * kG / 1.4f;  // 0.70 m/s²
  const Roll r = rollBall(cr, v0, 4.0f);
  EXPECT_NEAR(r.speedAt1s, v0 - a, 0.03f * (v0 - a));
  EXPECT_NEAR(r.distance, v0 * v0 / (2.0f * a), 0.03f * v0 * v0 / (2.0f * a));  // 2.85 m, then at rest
  EXPECT_LT(r.speed, 1e-3f);
  EXPECT_LT(r.across, 1e-3f);
}

TEST(RollingResistance, WithoutItABallRollsOn) {
  const Roll r = rollBall(0.0f, 2.0f, 4.0f);
  EXPECT_NEAR(r.speed, 2.0f, 0.01f);
  EXPECT_NEAR(r.distance, 8.0f, 0.05f);
}

// A ball set at rest on a ramp tilted by theta (friction 0.6, ample for rolling): distance it rolls
// down the slope in `seconds`.
float rollDownRamp(float rollingResistance, float thetaDeg, float seconds) {
  World w;
  addGround(w);
  const Ramp ramp = addRamp(w, thetaDeg);
  const Vec3 start = ramp.restingPlace(0.5f);
  const uint32_t b = addRoller(w, Shape::sphere(0.5f), start, Quat::Identity(), rollingResistance);
  const int steps = int(seconds * 60.0f + 0.5f);
  for (int s = 0; s < steps; ++s) w.step();
  return -(w.bodies().xf[b].p - start).dot(ramp.uphill);
}

TEST(RollingResistance, ABallHoldsOnASlopeFlatterThanItsCoefficient) {
  const float cr = 0.1f;
  EXPECT_LT(std::abs(rollDownRamp(cr, std::atan(0.5f * cr) * 180.0f / kPi, 2.0f)), 0.01f);
  // Without it the same ball rolls: a = g sin θ / 1.4, 0.49 m in 2 s.
  EXPECT_GT(rollDownRamp(0.0f, std::atan(0.5f * cr) * 180.0f / kPi, 2.0f), 0.4f);
}

TEST(RollingResistance, ABallRollsDownASteeperSlopeAtTheRateTheLawSays) {
  const float cr = 0.1f, th = std::atan(2.0f * cr);
  const float a = kG * (std::sin(th) - cr * std::cos(th)) / 1.4f;  // 0.69 m/s²
  EXPECT_NEAR(rollDownRamp(cr, th * 180.0f / kPi, 2.0f), 0.5f * a * 4.0f, 0.05f * 0.5f * a * 4.0f);
}

TEST(RollingResistance, ACapsuleOnItsSideSlowsByItsOwnInertia) {
  World w;
  addGround(w);
  const float r = 0.3f, halfHeight = 0.5f, cr = 0.08f, v0 = 1.5f;
  const Shape capsule = Shape::capsule(r, halfHeight);
  // Lying along z (its core is along local y), rolling along x.
  const Quat q(Eigen::AngleAxisf(kPi / 2.0f, Vec3::UnitX()));
  const uint32_t b = addRoller(w, capsule, Vec3(0, r, 0), q, cr, Vec3(v0, 0, 0), Vec3(0, 0, -v0 / r));
  const MassProperties mp = computeMassProperties(capsule, 1.0f);
  const float iAxis = mp.inertia(1, 1) / mp.mass;  // about the core, per unit mass
  const float a = cr * kG / (1.0f + iAxis / (r * r));
  for (int s = 0; s < 60; ++s) w.step();
  EXPECT_NEAR(w.bodies().v[b].x(), v0 - a, 0.03f * (v0 - a));
  for (int s = 0; s < 180; ++s) w.step();
  EXPECT_NEAR(w.bodies().xf[b].p.x(), v0 * v0 / (2.0f * a), 0.03f * v0 * v0 / (2.0f * a));
  EXPECT_LT(w.bodies().v[b].norm(), 1e-3f);
  EXPECT_LT(std::abs(w.bodies().xf[b].p.z()), 1e-3f);
}

// A box has no rolling radius: the same slide with or without a coefficient, to the bit.
TEST(RollingResistance, ShapesThatDoNotRollAreLeftAsTheyWere) {
  auto slide = [](float cr) {
    World w;
    addGround(w);
    addRoller(w, Shape::box(Vec3(0.5f, 0.25f, 0.5f)), Vec3(0, 0.25f, 0), Quat::Identity(), cr, Vec3(3, 0, 1));
    for (int s = 0; s < 120; ++s) w.step();
    return w.stateHash();
  };
  EXPECT_EQ(slide(0.0f), slide(0.5f));
}

// Either surface's coefficient acts: a plain ball on a resisting floor slows as on the law's.
TEST(RollingResistance, AResistingFloorSlowsAPlainBall) {
  World w;
  BodyDef floor;
  floor.kind = BodyKind::Static;
  floor.shape = Shape::plane(Vec3::UnitY(), 0.0f);
  floor.rollingResistance = 0.1f;
  w.addBody(floor);
  const uint32_t b = addRoller(w, Shape::sphere(0.5f), Vec3(0, 0.5f, 0), Quat::Identity(), 0.0f, Vec3(2, 0, 0),
                               Vec3(0, 0, -4));
  for (int s = 0; s < 60; ++s) w.step();
  EXPECT_NEAR(w.bodies().v[b].x(), 2.0f - 0.1f * kG / 1.4f, 0.03f * 1.3f);
}

// Balls rolling into each other and into a wall come to rest, with the same state at any thread count.
uint64_t ballsAfter(int threads, int steps, float* speed = nullptr, bool wide = false) {
  World w;
  w.setThreads(threads);
  w.settings().wideSolve = wide;
  addGround(w);
  addStaticBox(w, Vec3(6, 1, 0), Vec3(0.5f, 1, 5));
  for (int i = 0; i < 24; ++i) {
    const float x = float(i % 6) - 3.0f, z = float(i / 6) * 1.2f - 2.0f;
    addRoller(w, Shape::sphere(0.4f), Vec3(x, 0.4f, z), Quat::Identity(), 0.05f, Vec3(1.0f + 0.1f * i, 0, 0.2f),
              Vec3(0.5f, 0, -(1.0f + 0.1f * i) / 0.4f));
  }
  for (int s = 0; s < steps; ++s) w.step();
  if (speed) {
    *speed = 0.0f;
    for (size_t i = 0; i < w.bodies().size(); ++i) *speed = std::max(*speed, w.bodies().v[i].norm());
  }
  return w.stateHash();
}

TEST(RollingResistance, BallsComeToRestAndTheStateDoesNotDependOnThreads) {
  float speed = 0.0f;
  const uint64_t one = ballsAfter(1, 600, &speed);
  EXPECT_LT(speed, 1e-3f);
  EXPECT_EQ(one, ballsAfter(2, 600));
  EXPECT_EQ(one, ballsAfter(4, 600));
}

// The wide solve's lanes hold no rolling row: a world with rolling resistance is swept as usual,
// and its balls come to rest there too.
TEST(RollingResistance, TheWideSolveLeavesNoRollingRowOut) {
  float speed = 0.0f;
  ballsAfter(2, 600, &speed, true);
  EXPECT_LT(speed, 1e-3f);
}

}  // namespace
}  // namespace haif::test
