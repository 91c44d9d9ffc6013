// Islands that converge early hand their unspent iterations to islands that still need them.
#include "haif/world.h"

#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace haif {
namespace {

using test::addBox;
using test::addGround;

/// Always I = 4, and islands may stop after one sweep once converged.
class FourIterations final : public IterationController {
 public:
  FourIterations() { iMin = 1; iMax = 4; }
  int choose(const ControlContext&) override { return 4; }
  std::string name() const override { return "four"; }
};

TEST(SpareIterations, GoToTheIslandThatStillNeedsThem) {
  WorldSettings ws;
  ws.residualTolerance = 1e-3f;
  ws.chainSolve = false;  // solved as a chain, the stack would converge in a sweep or two as well
  ws.movingLayersPerSweep = 0.0f;  // landing, it would get main sweeps for its depth: here the spare ones count
  World w(ws);
  w.setController(std::make_unique<FourIterations>());
  addGround(w);
  // Many single boxes already at rest (they converge in a sweep) and one stack dropped onto
  // itself with gaps (4 sweeps cannot converge it while it lands).
  for (int i = 0; i < 20; ++i) addBox(w, Vec3(3.0f * float(i + 1), 0.5f, 0.0f));
  for (int h = 0; h < 10; ++h) addBox(w, Vec3(0.0f, 0.5f + 1.05f * float(h), 0.0f));

  const int relax = World::relaxIterationsFor(4);
  int stepsWithExtra = 0;
  for (int s = 0; s < 60; ++s) {
    w.step();
    const StepStats& st = w.lastStats();
    // Never more work than I sweeps over every row (plus the relax sweeps).
    EXPECT_LE(st.rowIterations, uint64_t(4 + relax) * w.islands().totalRows) << "step " << s;
    EXPECT_LE(st.iterationsMax, 2 * 4 + relax) << "an island at most doubles its count";
    if (st.iterationsMax > 4 + relax) ++stepsWithExtra;
  }
  EXPECT_GT(stepsWithExtra, 0) << "the landing stack never got the resting boxes' spare iterations";
}

TEST(SpareIterations, NotInFixedMode) {
  WorldSettings ws;
  ws.iterations = 4;
  ws.residualTolerance = 1e-3f;  // fixed mode runs its I: iMin == I, so nothing stops early
  World w(ws);
  addGround(w);
  for (int i = 0; i < 5; ++i) addBox(w, Vec3(3.0f * float(i + 1), 0.5f, 0.0f));
  for (int h = 0; h < 10; ++h) addBox(w, Vec3(0.0f, 0.5f + 1.05f * float(h), 0.0f));
  for (int s = 0; s < 30; ++s) {
    w.step();
    EXPECT_EQ(w.lastStats().iterationsMax, 4) << "step " << s;
  }
}

}  // namespace
TEST(SpareIterations, SharedInResidualOrderTheSameOnAnyThreadCount) {
  // Spare sweeps go to the unconverged islands in order of their residual (ties by index). Four
  // stacks with different gaps land beside boxes at rest that free their sweeps: they compete for
  // the spare sweeps, and the order, and so the state, must not depend on the thread count.
  auto run = [](int threads, int* extraOnTallest) {
    WorldSettings ws;
    ws.residualTolerance = 1e-3f;
    ws.chainSolve = false;
    ws.threads = threads;
    World w(ws);
    w.setController(std::make_unique<FourIterations>());
    addGround(w);
    for (int i = 0; i < 30; ++i) addBox(w, Vec3(3.0f * float(i + 1), 0.5f, 0.0f));
    for (int s = 0; s < 4; ++s)
      for (int h = 0; h < 6; ++h) addBox(w, Vec3(-3.0f * float(s + 1), 0.5f + (1.02f + 0.02f * float(s)) * float(h), 0.0f));
    int most = 0;
    for (int k = 0; k < 60; ++k) {
      w.step();
      most = std::max(most, w.lastStats().iterationsMax);
    }
    if (extraOnTallest) *extraOnTallest = most;
    return w.stateHash();
  };
  int most = 0;
  const uint64_t one = run(1, &most);
  EXPECT_EQ(run(2, nullptr), one);
  EXPECT_EQ(run(4, nullptr), one);
  EXPECT_GT(most, 4 + World::relaxIterationsFor(4)) << "no island got spare sweeps";
}

}  // namespace haif
