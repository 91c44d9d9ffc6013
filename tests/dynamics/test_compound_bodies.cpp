// Bodies of several shapes (compounds) in a world: resting on their parts, free rotation with a
// tensor that is not diagonal, and a drum of parts turning with bodies inside.
#include "collision/compound.h"
#include "collision/convex_hull.h"
#include "support/physics_test_util.h"


namespace haif::test {
namespace {

struct Part {
  Shape shape;
  Vec3 at;
  Quat q = Quat::Identity();
};

uint32_t addCompound(World& w, const std::vector<Part>& parts, const Vec3& p, BodyKind kind = BodyKind::Dynamic,
                     const Quat& q = Quat::Identity(), float mass = 0.0f) {
  std::vector<Shape> shapes;
  std::vector<Transform> poses;
  for (const Part& part : parts) {
    shapes.push_back(part.shape);
    poses.push_back(Transform{part.at, part.q});
  }
  std::string why;
  auto c = buildCompound(shapes, poses, &why);
  EXPECT_TRUE(c) << why;
  BodyDef d;
  d.kind = kind;
  d.shape = Shape::compoundOf(c);
  d.xf.p = p + q * c->centroid;
  d.xf.q = q;
  d.mass = mass;
  d.density = 500.0f;
  return w.addBody(d);
}

float tiltOf(const Quat& q) { return 2.0f * std::acos(std::min(1.0f, std::abs(q.w()))); }

// Two balls on a bar, dropped tilted: it lands on both balls and lies still, level, at ball height.
TEST(CompoundBodies, DumbbellComesToRestOnBothBalls) {
  World w;
  addGround(w);
  const float r = 0.25f;
  const uint32_t b = addCompound(w, {{Shape::sphere(r), Vec3(-0.6f, 0, 0)}, {Shape::sphere(r), Vec3(0.6f, 0, 0)},
                                     {Shape::box(Vec3(0.6f, 0.04f, 0.04f)), Vec3::Zero()}},
                                 Vec3(0, 1.0f, 0), BodyKind::Dynamic, Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitZ())));
  float deepest = 0.0f;
  for (int s = 0; s < 240; ++s) {
    w.step();
    if (s > 120) deepest = std::max(deepest, maxContactDepth(w));
  }
  const BodyStore& bs = w.bodies();
  EXPECT_NEAR(bs.xf[b].p.y(), r, w.settings().contact.slop + 1e-3f);
  const Vec3 bar = bs.xf[b].q * Vec3::UnitX();
  EXPECT_LT(std::abs(bar.y()), 2e-3f) << "the bar is not level: both balls must touch";
  EXPECT_LT(bs.v[b].norm(), 1e-2f);
  EXPECT_LT(bs.w[b].norm(), 2e-2f);
  EXPECT_LT(deepest, w.settings().contact.slop + 1e-3f);
  EXPECT_EQ(w.lastStats().contactPoints, 2u);
}

// A table (top and four legs) stands for 10 s: no sinking, no tilt, no walk.
TEST(CompoundBodies, TableStandsOnItsFourLegs) {
  World w;
  addGround(w);
  std::vector<Part> parts{{Shape::box(Vec3(1.0f, 0.05f, 0.6f)), Vec3(0, 0.75f, 0)}};
  for (float x : {-0.9f, 0.9f})
    for (float z : {-0.5f, 0.5f}) parts.push_back({Shape::box(Vec3(0.05f, 0.35f, 0.05f)), Vec3(x, 0.35f, z)});
  const uint32_t t = addCompound(w, parts, Vec3::Zero());
  const Vec3 start = w.bodies().xf[t].p;
  float moved = 0.0f, tilt = 0.0f;
  for (int s = 0; s < 600; ++s) {
    w.step();
    moved = std::max(moved, (w.bodies().xf[t].p - start).norm());
    tilt = std::max(tilt, tiltOf(w.bodies().xf[t].q));
  }
  EXPECT_LT(moved, w.settings().contact.slop + 1e-3f);
  EXPECT_LT(tilt, 1e-3f);
  EXPECT_EQ(w.lastStats().contactPoints, 4u) << "one point under each leg";
}

// An L of two bars spun in zero gravity: its tensor has off-diagonal terms, and free rotation must
// still keep |L| and the energy: the integrator takes a full tensor, not only its diagonal.
TEST(CompoundBodies, LShapeSpinsFreeKeepingMomentumAndEnergy) {
  WorldSettings ws;
  ws.gravity = Vec3::Zero();
  World w(ws);
  const uint32_t b = addCompound(w, {{Shape::box(Vec3(0.5f, 0.05f, 0.05f)), Vec3(0.5f, 0, 0)},
                                     {Shape::box(Vec3(0.05f, 0.3f, 0.05f)), Vec3(0, 0.3f, 0)}},
                                 Vec3::Zero());
  w.bodies().w[b] = Vec3(1.0f, 2.0f, 0.5f);
  auto energy = [&] {
    const BodyStore& bs = w.bodies();
    const Eigen::Vector3d wv = bs.w[b].cast<double>();
    return 0.5 * wv.dot(angularMomentum(w, b));
  };
  const double e0 = energy();
  const Eigen::Vector3d L0 = angularMomentum(w, b);
  double worstE = 0.0, worstL = 0.0;
  for (int s = 0; s < 600; ++s) {
    w.step();
    worstE = std::max(worstE, std::abs(energy() - e0) / e0);
    worstL = std::max(worstL, (angularMomentum(w, b) - L0).norm() / L0.norm());
  }
  EXPECT_LT(worstE, 1e-3);
  EXPECT_LT(worstL, 1e-4);
  EXPECT_LT(w.bodies().v[b].norm(), 1e-6f) << "a free spin must not move the centre of mass";
}

// A drum of 16 boxes and two end walls (one kinematic compound) turning at 0.5 rad/s about z with 60
// bodies inside: they are carried and tumble, none leaves the drum, none moves faster than the
// drum's rim speed plus a fall across it, the pile rides up the rising side, and the result is the
// same on 1, 2 and 4 threads.
uint64_t runDrum(int threads, float* outside, float* fastest, float* meanX) {
  WorldSettings ws;
  ws.threads = threads;
  World w(ws);
  const int n = 16;
  const float R = 2.0f, t = 0.15f, L = 1.0f;
  std::vector<Part> parts;
  for (int k = 0; k < n; ++k) {
    const float a = 2.0f * kPi * float(k) / float(n);
    const float c = R + t;
    parts.push_back({Shape::box(Vec3(t, c * std::tan(kPi / float(n)) + 0.03f, L + 2 * t)), Vec3(c * std::cos(a), c * std::sin(a), 0),
                     Quat(Eigen::AngleAxisf(a, Vec3::UnitZ()))});
  }
  for (float s : {-1.0f, 1.0f}) parts.push_back({Shape::box(Vec3(R + 2 * t, R + 2 * t, t)), Vec3(0, 0, s * (L + t))});
  const uint32_t drum = addCompound(w, parts, Vec3::Zero(), BodyKind::Kinematic);
  w.bodies().w[drum] = Vec3(0, 0, 0.5f);
  for (int i = 0; i < 60; ++i) {
    const Vec3 p(-1.0f + 0.5f * float(i % 5), -1.2f + 0.45f * float(i / 15), -0.6f + 0.4f * float((i / 5) % 3));
    if (i % 2) addBox(w, p, Vec3::Constant(0.15f), 1.0f);
    else addSphere(w, p, 0.15f, 1.0f);
  }
  // Rim speed plus what a body gains falling across the drum.
  const float bound = 0.5f * R + std::sqrt(2.0f * 9.81f * 2.0f * R);
  *outside = -1e30f;
  *fastest = 0.0f;
  for (int s = 0; s < 600; ++s) {
    w.step();
    for (uint32_t i = drum + 1; i < w.bodyCount(); ++i) {
      const Vec3& p = w.bodies().xf[i].p;
      *outside = std::max({*outside, std::hypot(p.x(), p.y()) - R, std::abs(p.z()) - L});
      *fastest = std::max(*fastest, w.bodies().v[i].norm() / bound);
    }
  }
  *meanX = 0.0f;
  for (uint32_t i = drum + 1; i < w.bodyCount(); ++i) *meanX += w.bodies().xf[i].p.x() / float(w.bodyCount() - drum - 1);
  return w.stateHash();
}

TEST(CompoundBodies, KinematicDrumTumblesBodiesAndKeepsThemIn) {
  float outside = 0.0f, fastest = 0.0f, meanX = 0.0f;
  runDrum(2, &outside, &fastest, &meanX);
  EXPECT_LT(outside, 0.0f) << "a body's centre left the drum by " << outside << " m";
  EXPECT_LT(fastest, 1.0f) << "a body moved at " << fastest << " of the bound";
  // Turning counter-clockwise about z, the drum's bottom moves towards +x: the pile rides up that side.
  EXPECT_GT(meanX, 0.2f) << "the drum did not carry the pile";
  expectSameStateForThreadCounts([](int threads) {
    float o, f, x;
    return runDrum(threads, &o, &f, &x);
  });
}


// A centrifuge without gravity: two walls (one kinematic compound) turning at 4 rad/s about y, and a
// column of boxes riding the +x wall. Each step the wall's surface moves on an arc, ½ ω² r dt² (3 mm)
// further into the column than its velocity says; solved at the step's first normals, the bottom box
// stayed where Baumgarte's push-out balances that, slop + ½ ω² r dt² / β = 3.2 cm deep in the wall
// (and a pile riding a drum's wall at 6 m/s sank through it). The surface's lead is asked of the
// contact in every sweep, so the column rests on the wall (0.1 mm deep on average, 0.5 mm drift).
float centrifugeDepth(int columnHeight, float* radiusDrift) {
  WorldSettings ws;
  ws.gravity = Vec3::Zero();
  World w(ws);
  const float R = 2.5f, t = 0.15f, omega = 4.0f, h = 0.2f;
  std::vector<Part> parts;
  for (float s : {-1.0f, 1.0f}) parts.push_back({Shape::box(Vec3(t, 0.5f, 0.5f)), Vec3(s * (R + t), 0, 0)});
  const uint32_t ring = addCompound(w, parts, Vec3::Zero(), BodyKind::Kinematic);
  w.bodies().w[ring] = Vec3(0, omega, 0);
  std::vector<uint32_t> column;
  for (int k = 0; k < columnHeight; ++k) {
    const float x = R - h - 2.0f * h * float(k);
    column.push_back(addBox(w, Vec3(x, 0, 0), Vec3::Constant(h), 1.0f));
    w.bodies().v[column.back()] = Vec3(0, omega, 0).cross(Vec3(x, 0, 0));
    w.bodies().w[column.back()] = Vec3(0, omega, 0);
  }
  float depthSum = 0.0f;
  int samples = 0;
  *radiusDrift = 0.0f;
  for (int s = 0; s < 600; ++s) {
    w.step();
    *radiusDrift = std::max(*radiusDrift, std::abs(w.bodies().xf[column[0]].p.norm() - (R - h)));
    if (s < 120) continue;  // settled
    for (const Contact& c : w.contacts())
      if ((c.a == ring) != (c.b == ring)) {
        float deepest = 0.0f;
        for (int i = 0; i < c.manifold.count; ++i) deepest = std::max(deepest, c.manifold.points[i].depth);
        depthSum += deepest;
        ++samples;
      }
  }
  return samples ? depthSum / float(samples) : 1e9f;
}

TEST(CompoundBodies, AColumnRidingACentrifugesWallRestsOnIt) {
  const float slop = SolverParams{}.slop;
  for (int height : {1, 3}) {
    float drift = 0.0f;
    const float depth = centrifugeDepth(height, &drift);
    EXPECT_LT(depth, slop) << height << " box(es): mean depth in the wall (3.1 cm without the lead)";
    EXPECT_LT(drift, 0.005f) << height << " box(es): the bottom box left its radius by (3.1 cm without the lead)";
  }
}

// A top: a 12-sided double cone (radius 0.25 m, its tip 0.2 m below the rim, 5 cm above it) on a
// thin axle whose end is 1 cm above the tip, spun upright at 40 rad/s on its tip (a spin of 26 rad/s
// keeps it upright). Friction acts where the pair touches (dynamics/friction_patch.h): the rim's
// speculative points, 21 cm up, took the tip's friction to their mean, 10 cm from it, with a twist
// lever of 17 cm, and the top lost its spin within a second and fell; the axle's end, 1 cm up the
// normal from the tip, is no width of the patch (it slowed the spin by 0.9 rad/s²).
TEST(CompoundBodies, ATopSpinningOnItsTipKeepsItsSpin) {
  World w;
  addGround(w);
  std::vector<Vec3> cone{Vec3(0.0f, -0.2f, 0.0f), Vec3(0.0f, 0.05f, 0.0f)};
  for (int a = 0; a < 12; ++a)
    cone.push_back(Vec3(0.25f * std::cos(float(a) * kPi / 6.0f), 0.0f, 0.25f * std::sin(float(a) * kPi / 6.0f)));
  std::string why;
  auto hull = buildConvexHull(cone, &why);
  ASSERT_TRUE(hull) << why;
  const uint32_t top = addCompound(w, {{Shape::convexHull(hull), Vec3::Zero()}, {Shape::capsule(0.03f, 0.16f), Vec3::Zero()}},
                                   Vec3(0.0f, 0.201f, 0.0f));
  w.bodies().w[top] = Vec3(0.0f, 40.0f, 0.0f);
  for (int s = 0; s < 300; ++s) w.step();
  const BodyStore& bs = w.bodies();
  EXPECT_GT(bs.w[top].y(), 39.5f) << "the spin was lost";
  EXPECT_GT((bs.xf[top].q * Vec3::UnitY()).y(), std::cos(0.02f)) << "the top's axis tilted";
  EXPECT_LT(Vec3(bs.xf[top].p.x(), 0.0f, bs.xf[top].p.z()).norm(), 0.01f) << "the top wandered off its place";
}

}  // namespace
}  // namespace haif::test
