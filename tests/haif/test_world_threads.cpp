// The thread count: set through setThreads() or written into settings(), the parallel stages run on
// that many threads from the next step, and the result does not depend on it.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

uint64_t pyramidAfter(World& w, int steps) {
  addGround(w);
  addPyramid2d(w, 12);
  for (int s = 0; s < steps; ++s) w.step();
  return w.stateHash();
}

TEST(WorldThreads, AThreadCountWrittenIntoSettingsTakesEffectAtTheNextStep) {
  World w;
  EXPECT_EQ(w.workerThreads(), 1);
  w.settings().threads = 3;  // as a tool that copies settings in would
  EXPECT_EQ(w.workerThreads(), 1);
  w.step();
  EXPECT_EQ(w.workerThreads(), 3);
  EXPECT_EQ(w.threads(), 3);
  w.setThreads(2);
  EXPECT_EQ(w.workerThreads(), 2);
}

TEST(WorldThreads, TheStateDoesNotDependOnHowTheCountWasSet) {
  World a, b;
  a.setThreads(2);
  b.settings().threads = 2;
  EXPECT_EQ(pyramidAfter(a, 60), pyramidAfter(b, 60));
  EXPECT_EQ(b.workerThreads(), 2);
}

}  // namespace
}  // namespace haif::test
