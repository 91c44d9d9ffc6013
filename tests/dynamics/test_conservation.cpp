// Free flight in zero gravity: nothing acts on the bodies, so momentum (and angular momentum) must
// be conserved; contacts apply equal and opposite impulses, so they conserve them too.
#include "support/physics_test_util.h"

#include <random>

namespace haif::test {
namespace {

WorldSettings zeroG() {
  WorldSettings s;
  s.gravity = Vec3::Zero();
  s.iterations = 10;
  return s;
}

double rel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() / std::max(1e-12, b.norm()); }

TEST(Conservation, LinearMomentumInFreeFlight) {
  World w(zeroG());
  BodyDef d;
  d.shape = Shape::box(Vec3(0.3f, 0.6f, 0.2f));
  d.mass = 2.5f;
  d.xf.p = Vec3(0, 0, 0);
  d.linearVelocity = Vec3(1.5f, -0.7f, 0.3f);
  d.angularVelocity = Vec3(0.4f, 2.0f, -1.0f);
  w.addBody(d);
  d.shape = Shape::sphere(0.4f);
  d.mass = 0.8f;
  d.xf.p = Vec3(-20, 5, 3);
  d.linearVelocity = Vec3(-2.0f, 0.1f, 0.9f);
  w.addBody(d);
  const Eigen::Vector3d p0 = linearMomentum(w);
  for (int s = 0; s < 600; ++s) w.step();
  EXPECT_LT(rel(linearMomentum(w), p0), 1e-6) << "momentum " << linearMomentum(w).transpose() << " vs " << p0.transpose();
  // Positions follow x = x0 + v t.
  EXPECT_NEAR(w.bodies().xf[0].p.x(), 1.5f * 10.0f, 1e-3f);
  EXPECT_NEAR(w.bodies().xf[1].p.z(), 3.0f + 0.9f * 10.0f, 1e-3f);
}

TEST(Conservation, AngularMomentumOfSpinningBox) {
  World w(zeroG());
  BodyDef d;
  d.shape = Shape::box(Vec3(0.2f, 0.5f, 1.0f));  // three distinct principal moments
  d.mass = 3.0f;
  d.xf.q = Quat(Eigen::AngleAxisf(0.3f, Vec3(1, 2, 3).normalized()));
  d.angularVelocity = Vec3(2.0f, 1.0f, 3.0f);  // not along a principal axis: the body tumbles
  const uint32_t b = w.addBody(d);
  const Eigen::Vector3d L0 = angularMomentum(w, b);
  double worst = 0.0;
  Vec3 w0 = w.bodies().w[b];
  for (int s = 0; s < 600; ++s) {
    w.step();
    worst = std::max(worst, rel(angularMomentum(w, b), L0));
  }
  EXPECT_LT(worst, 1e-4) << "|L| drift; L0 = " << L0.transpose() << ", L = " << angularMomentum(w, b).transpose();
  // The tumble is real: the angular velocity changed direction (else the test would be trivial).
  EXPECT_GT((w.bodies().w[b] - w0).norm(), 0.1f);
  // And the body did not translate.
  EXPECT_LT(w.bodies().xf[b].p.norm(), 1e-6f);
}

// Rotational kinetic energy 0.5 w . I_w w of body i.
double rotationalEnergy(const World& w, uint32_t i) {
  return 0.5 * w.bodies().w[i].cast<double>().dot(angularMomentum(w, i));
}

// The zero_g_spin stress scene: a 0.8 x 0.4 x 0.2 m box spun about its intermediate axis with a slight
// wobble (off the separatrix, so the motion is periodic). Free rotation keeps |L| and the energy; the
// y axis turns over against L every 5 s (4 times in 20 s by an accurate reference integration). The old
// explicit update kept |L| but gained 240 % energy and ended spinning about the least-inertia axis.
TEST(Conservation, IntermediateAxisSpinKeepsEnergyAndFlips) {
  World w(zeroG());
  BodyDef d;
  d.shape = Shape::box(Vec3(0.4f, 0.2f, 0.1f));
  d.mass = 1.0f;
  d.angularVelocity = Vec3(0.04f, 4.0f, 0.02f);
  const uint32_t b = w.addBody(d);
  const double e0 = rotationalEnergy(w, b);
  const Eigen::Vector3d L0 = angularMomentum(w, b);
  double worstGain = 0.0, worstLoss = 0.0, worstL = 0.0;
  int flips = 0, side = 1;
  for (int s = 0; s < 1200; ++s) {
    w.step();
    const double e = rotationalEnergy(w, b);
    worstGain = std::max(worstGain, (e - e0) / e0);
    worstLoss = std::max(worstLoss, (e0 - e) / e0);
    worstL = std::max(worstL, rel(angularMomentum(w, b), L0));
    const float c = (w.bodies().xf[b].q * Vec3::UnitY()).dot(L0.normalized().cast<float>());
    if (c * float(side) < -0.5f) {
      ++flips;
      side = -side;
    }
  }
  EXPECT_LT(worstGain, 1e-3) << "the spin gained energy";
  EXPECT_LT(worstLoss, 1e-3) << "the spin lost energy";
  EXPECT_LT(worstL, 1e-4) << "|L| drift";
  EXPECT_GE(flips, 3) << "the intermediate axis must turn over (4 times by the reference)";
  EXPECT_LE(flips, 5);
}

// A thin rod (tiny moment about its axis) tumbling fast in zero gravity: the explicit update pumped
// energy into the spin about the thin axis until it blew up (random world seed 1113).
TEST(Conservation, ThinCapsuleTumbleDoesNotSpinUp) {
  World w(zeroG());
  BodyDef d;
  d.shape = Shape::capsule(0.03f, 0.6f);
  d.mass = 80.0f;
  d.xf.q = Quat(Eigen::AngleAxisf(0.7f, Vec3(1, 0.3f, -0.4f).normalized()));
  d.angularVelocity = Vec3(3.0f, 1.5f, -2.0f);
  const uint32_t b = w.addBody(d);
  const double e0 = rotationalEnergy(w, b);
  const Eigen::Vector3d L0 = angularMomentum(w, b);
  double worstGain = 0.0, worstL = 0.0;
  for (int s = 0; s < 600; ++s) {
    w.step();
    worstGain = std::max(worstGain, (rotationalEnergy(w, b) - e0) / e0);
    worstL = std::max(worstL, rel(angularMomentum(w, b), L0));
  }
  EXPECT_LT(worstGain, 1e-3) << "speed " << w.bodies().w[b].norm() << " rad/s";
  EXPECT_LT(worstL, 5e-5);  // 2e-5 with w taken from L in the body frame; 6e-5 before
}

// A sphere glancing off a spinning box, no gravity: the impulses between them may not change the
// pair's linear or angular momentum. The relax sweeps (after the positions moved) applied each impulse
// at lever arms from before the move, two points (vA - vB) dt apart, and the angular momentum drifted
// by 2.06 % here; the rows of pairs that moved against each other are re-aimed about one point now
// (reaimForRelax). At 10 iterations and at the adaptive floor of 4.
TEST(Conservation, MomentumThroughAGlancingCollision) {
  for (const int iterations : {10, 4}) {
    WorldSettings ws = zeroG();
    ws.iterations = iterations;
    World w(ws);
    BodyDef d;
    d.shape = Shape::sphere(0.5f);
    d.mass = 1.0f;
    d.friction = 0.5f;
    d.restitution = 0.3f;
    d.xf.p = Vec3(-3.0f, 0.3f, 0.0f);
    d.linearVelocity = Vec3(4.0f, 0.0f, 0.0f);
    d.angularVelocity = Vec3(0.0f, 0.0f, 5.0f);
    const uint32_t a = w.addBody(d);
    d.shape = Shape::box(Vec3(0.4f, 0.6f, 0.5f));
    d.mass = 2.0f;
    d.xf.p = Vec3(0.0f, 0.0f, 0.1f);
    d.linearVelocity = Vec3(-1.0f, 0.0f, 0.0f);
    d.angularVelocity = Vec3::Zero();
    const uint32_t b = w.addBody(d);
    auto totalL = [&] {
      Eigen::Vector3d L = Eigen::Vector3d::Zero();
      for (uint32_t i : {a, b})
        L += w.bodies().xf[i].p.cast<double>().cross(double(w.bodies().mass[i]) * w.bodies().v[i].cast<double>()) +
             angularMomentum(w, i);
      return L;
    };
    const Eigen::Vector3d p0 = linearMomentum(w), L0 = totalL();
    const Vec3 va0 = w.bodies().v[a];
    bool touched = false;
    for (int s = 0; s < 120; ++s) {
      w.step();
      touched = touched || w.lastStats().contactPoints > 0;
    }
    ASSERT_TRUE(touched) << "the bodies never met";
    EXPECT_GT((w.bodies().v[a] - va0).norm(), 1.0f) << "the collision changed nothing";
    // Float rounding of sums of ~1e2 terms: 1e-5 of the momenta (the issue asked 0.5 % and 1 %).
    EXPECT_LT(rel(linearMomentum(w), p0), 1e-5) << iterations << ": " << linearMomentum(w).transpose() << " vs " << p0.transpose();
    EXPECT_LT(rel(totalL(), L0), 1e-5) << iterations << ": " << totalL().transpose() << " vs " << L0.transpose();
  }
}

// A crowd of spheres and boxes converging in zero gravity (without spin, whose free tumbling has its
// own rounding): one island of hundreds of collisions,
// swept by the scalar rows and by the 8-lane wide sweep (WorldSettings::wideSolve). The wide sweep
// runs on packed copies of the rows; when the re-aimed rows of moving pairs (reaimForRelax) were not
// packed again before the relax sweeps, the crowd's angular momentum drifted by a few per cent and a
// wide large_pyramid collapsed in a one-minute run at 4 iterations.
TEST(Conservation, MomentumThroughACrowdScalarAndWide) {
  for (const bool wide : {false, true}) {
    WorldSettings ws = zeroG();
    ws.iterations = 4;
    ws.wideSolve = wide;
    World w(ws);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        for (int k = 0; k < 5; ++k) {
          BodyDef d;
          d.shape = (i + j + k) % 2 ? Shape::sphere(0.45f) : Shape::box(Vec3(0.3f, 0.4f, 0.35f));
          d.mass = 1.0f + 0.5f * float((i * 7 + j * 3 + k) % 4);
          d.friction = 0.5f;
          d.xf.p = 1.4f * Vec3(float(i) - 2.0f, float(j) - 2.0f, float(k) - 2.0f);
          d.linearVelocity = -0.3f * d.xf.p + 0.3f * Vec3(u(rng), u(rng), u(rng));
          w.addBody(d);
        }
    auto totalL = [&] {
      Eigen::Vector3d L = Eigen::Vector3d::Zero();
      for (uint32_t b = 0; b < w.bodies().size(); ++b)
        L += w.bodies().xf[b].p.cast<double>().cross(double(w.bodies().mass[b]) * w.bodies().v[b].cast<double>()) +
             angularMomentum(w, b);
      return L;
    };
    const Eigen::Vector3d p0 = linearMomentum(w), L0 = totalL();
    int mostContacts = 0;
    for (int s = 0; s < 90; ++s) {
      w.step();
      mostContacts = std::max(mostContacts, int(w.lastStats().contactPoints));
    }
    ASSERT_GT(mostContacts, 200) << "the crowd never met";
    const double scale = std::max(p0.norm(), 1.0), scaleL = std::max(L0.norm(), 1.0);
    EXPECT_LT((linearMomentum(w) - p0).norm() / scale, 1e-4) << (wide ? "wide" : "scalar");
    // Scalar and wide (fixed): 4.3e-5 and 4.4e-5; the wide sweep without its rows re-aimed: 2.4e-4.
    EXPECT_LT((totalL() - L0).norm() / scaleL, 1e-4)
        << (wide ? "wide" : "scalar") << ": " << totalL().transpose() << " vs " << L0.transpose();
  }
}

}  // namespace
}  // namespace haif::test
