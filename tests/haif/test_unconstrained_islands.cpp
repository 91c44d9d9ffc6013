// Islands of one body and no constraint come last in the solve order and are not solved
// (World::solve ends its batches before them): the islands before them all are, and the bodies in
// them move as integration alone moves them.
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <vector>

namespace haif {
namespace {

using test::addBox;
using test::addGround;

TEST(UnconstrainedIslands, BodiesInFlightFlyFreelyAndEveryIslandBeforeThemIsSolved) {
  World w;
  w.settings().iterations = 10;
  w.settings().sleeping = false;
  addGround(w);
  // Bodies in flight among the resting ones in index order, and a resting box last: its island is
  // the last with a constraint, just before the ones that are not solved.
  std::vector<uint32_t> resting, flying;
  std::vector<Vec3> launch;
  for (int i = 0; i < 6; ++i) {
    resting.push_back(addBox(w, Vec3(3.0f * float(i) - 9.0f, 0.5f, 0.0f)));
    flying.push_back(addBox(w, Vec3(3.0f * float(i) - 9.0f, 40.0f + 3.0f * float(i), 5.0f)));
    launch.push_back(Vec3(0.3f * float(i), 2.0f, -0.2f * float(i)));
    w.bodies().v[flying.back()] = launch.back();
    w.bodies().w[flying.back()] = Vec3(0.5f, -0.3f * float(i), 0.2f);
  }
  const std::vector<uint32_t> column = test::addColumn(w, 2, 9.0f, 0.0f);
  resting.push_back(addBox(w, Vec3(-12.0f, 0.5f, 0.0f)));

  const float dt = w.settings().dt;
  const Vec3 g = w.settings().gravity;
  const int steps = 60;
  for (int s = 0; s < steps; ++s) {
    w.step();
    // Each resting box and the column make an island with rows; every one of them ran the step's
    // main sweeps (solveIslands) and its relax sweeps (relaxIslands), and the stats count them.
    const StepStats& st = w.lastStats();
    EXPECT_EQ(st.iterationsMin, 10) << "step " << s;
    EXPECT_EQ(st.islands, resting.size() + 1 + flying.size()) << "step " << s;
  }
  for (size_t i = 0; i < flying.size(); ++i) {
    const Vec3 expected = launch[i] + g * (dt * float(steps));
    EXPECT_LT((w.bodies().v[flying[i]] - expected).norm(), 1e-3f) << "body " << flying[i];
  }
  // Solved every step, the resting boxes and the column stay where they were put.
  for (const uint32_t b : resting) EXPECT_NEAR(w.bodies().xf[b].p.y(), 0.5f, 0.01f) << "body " << b;
  EXPECT_NEAR(w.bodies().xf[column.back()].p.y(), 1.5f, 0.02f);
  EXPECT_LT(test::maxContactDepth(w), 0.02f);
}

}  // namespace
}  // namespace haif
