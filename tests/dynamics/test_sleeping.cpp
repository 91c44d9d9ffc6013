// Sleeping: a resting stack goes to sleep, does no solver work while asleep, and wakes when hit.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

// n boxes stacked: n = 1 checks the sleep/wake mechanics alone, n = 5 a real stack.
class SleepingStack : public ::testing::TestWithParam<int> {};

TEST_P(SleepingStack, SleepsAndWakesWhenHit) {
  WorldSettings s;
  s.sleeping = true;
  World w(s);
  addGround(w);
  const int n = GetParam();
  std::vector<uint32_t> ids;
  for (int h = 0; h < n; ++h) ids.push_back(addBox(w, Vec3(0.0f, 0.5f + 1.01f * float(h), 0.0f)));

  int sleptAt = -1;
  for (int step = 0; step < 300 && sleptAt < 0; ++step) {
    w.step();
    if (w.lastStats().sleepingBodies == uint32_t(n)) sleptAt = step;
  }
  if (sleptAt < 0) {
    float vmax = 0.0f;
    for (uint32_t i : ids) vmax = std::max(vmax, w.bodies().v[i].norm());
    FAIL() << "the stack never fell asleep in 5 s; fastest box still moves at " << vmax << " m/s (sleep threshold "
           << s.sleepLinear << ")";
  }
  EXPECT_EQ(w.lastStats().awakeBodies, 0u);
  // Sleep is decided at the end of a step, so the first step that runs fully asleep is the next one.
  w.step();
  const StepStats& st = w.lastStats();
  EXPECT_EQ(st.sleepingBodies, uint32_t(n));
  EXPECT_EQ(st.awakeBodies, 0u);
  EXPECT_EQ(st.rowIterations, 0u) << "a sleeping island must do no solver work";
  EXPECT_EQ(st.islands, 0u);
  // Sleeping bodies do not move.
  const uint64_t asleepHash = w.stateHash();
  for (int k = 0; k < 30; ++k) {
    w.step();
    EXPECT_EQ(w.lastStats().sleepingBodies, uint32_t(n));
    EXPECT_EQ(w.lastStats().rowIterations, 0u);
  }
  EXPECT_EQ(w.stateHash(), asleepHash);

  // Drop a heavy box on top.
  const float topY = w.bodies().xf[ids.back()].p.y();
  const uint32_t dropped = addBox(w, Vec3(0.1f, topY + 3.0f, 0.0f), Vec3::Constant(0.5f), 5.0f);
  bool stackWoke = false, freeFallKeptStackAsleep = true, hit = false;
  for (int k = 0; k < 120; ++k) {
    w.step();
    const StepStats& ss = w.lastStats();
    const bool touching = w.bodies().xf[dropped].p.y() < topY + 1.1f;
    if (!touching && !hit && ss.sleepingBodies != uint32_t(n)) freeFallKeptStackAsleep = false;
    hit = hit || touching;
    if (ss.sleepingBodies == 0 && ss.awakeBodies == uint32_t(n + 1)) {
      stackWoke = true;
      EXPECT_GT(ss.rowIterations, 0u);
      break;
    }
  }
  EXPECT_TRUE(freeFallKeptStackAsleep) << "a body falling in free space woke the stack before touching it";
  EXPECT_TRUE(stackWoke) << "the stack did not wake when a box landed on it";
  // The dropped box is supported by the (awake) stack, not passing through it.
  for (int k = 0; k < 60; ++k) w.step();
  EXPECT_GT(w.bodies().xf[dropped].p.y(), topY + 0.9f) << "dropped box sank into the sleeping stack";
}

INSTANTIATE_TEST_SUITE_P(Sleeping, SleepingStack, ::testing::Values(1, 5));

TEST(Sleeping, DisabledMeansNobodySleeps) {
  World w;  // sleeping defaults to false (WorldSettings; the reference scenes of docs/reference_scenes.md do not sleep)
  addGround(w);
  addBox(w, Vec3(0.0f, 0.5f, 0.0f));
  for (int s = 0; s < 120; ++s) w.step();
  EXPECT_EQ(w.lastStats().sleepingBodies, 0u);
  EXPECT_EQ(w.lastStats().awakeBodies, 1u);
  EXPECT_FALSE(w.lastStats().stages & kStageSleep);
}

}  // namespace
}  // namespace haif::test
