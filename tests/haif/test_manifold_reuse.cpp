// The world keeps a pair's manifold while its bodies rest on each other, makes it again while they
// slide, and either way the bodies end where they end with every manifold made fresh.
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace haif {
namespace {

struct Trace {
  std::vector<uint32_t> reusedPerStep, contactsPerStep;
  std::vector<Vec3> finalPositions;
};

// A 3-box column and a box sliding across the ground at `slideSpeed`, stepped `steps` times.
Trace run(bool reuse, float slideSpeed, int steps) {
  WorldSettings ws;
  ws.reuseManifolds = reuse;
  World w(ws);
  test::addGround(w);
  test::addColumn(w, 3, 0.0f, 0.0f);
  const uint32_t slider = test::addBox(w, Vec3(4.0f, 0.5f, 0.0f));
  w.bodies().v[slider] = Vec3(slideSpeed, 0.0f, 0.0f);
  Trace r;
  for (int s = 0; s < steps; ++s) {
    w.step();
    r.reusedPerStep.push_back(w.lastStats().manifoldsReused);
    r.contactsPerStep.push_back(w.lastStats().contacts);
  }
  for (uint32_t i = 0; i < w.bodyCount(); ++i) r.finalPositions.push_back(w.bodies().xf[i].p);
  return r;
}

TEST(ManifoldReuse, RestingPairsKeepTheirManifoldsSlidingPairsDoNot) {
  // μ = 0.6 stops a 3 m/s slide in v² / (2 μ g) = 0.76 m, about 31 steps.
  const Trace r = run(true, 3.0f, 90);
  // While the slider moves, only the column's 3 contacts can be kept; its own is made every step.
  for (int s = 2; s < 25; ++s) EXPECT_LE(r.reusedPerStep[size_t(s)], 3u) << "step " << s;
  // Once it rests, every manifold is kept.
  for (int s = 45; s < 90; ++s) EXPECT_EQ(r.reusedPerStep[size_t(s)], r.contactsPerStep[size_t(s)]) << "step " << s;
  const Trace off = run(false, 3.0f, 90);
  for (uint32_t s : off.reusedPerStep) EXPECT_EQ(s, 0u);
  // Same motion: the slider stops at the same place, the column stands where it stood.
  ASSERT_EQ(r.finalPositions.size(), off.finalPositions.size());
  for (size_t i = 0; i < r.finalPositions.size(); ++i)
    EXPECT_LT((r.finalPositions[i] - off.finalPositions[i]).norm(), 1e-4f) << "body " << i;
  EXPECT_NEAR(r.finalPositions.back().x(), 4.0f + 0.76f, 0.05f);
}

TEST(ManifoldReuse, ASlowlyRollingBallKeepsRolling) {
  // A rolling ball's contact stays under its centre while any point fixed in the ball turns away. A
  // kept manifold turned its normal with the ball (up to the 0.01 rad reuse limit), and the tilted
  // normal pushed a ball rolling at 1 cm/s on a level floor up to 14 cm/s in 5 s (and sank it 1.5 mm).
  for (bool reuse : {true, false}) {
    WorldSettings ws;
    ws.reuseManifolds = reuse;
    World w(ws);
    test::addGround(w);
    const uint32_t ball = test::addSphere(w, Vec3(0.0f, 0.5f, 0.0f));
    w.bodies().v[ball] = Vec3(0.01f, 0.0f, 0.0f);
    w.bodies().w[ball] = Vec3(0.0f, 0.0f, -0.02f);  // rolling: v = -ω × r at the contact
    for (int s = 0; s < 300; ++s) w.step();
    EXPECT_NEAR(w.bodies().v[ball].x(), 0.01f, 1e-4f) << (reuse ? "reuse on" : "reuse off");
    EXPECT_NEAR(w.bodies().xf[ball].p.y(), 0.5f, 1e-4f) << (reuse ? "reuse on" : "reuse off");
  }
}

}  // namespace
}  // namespace haif
