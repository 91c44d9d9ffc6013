// The adaptive iteration controller with an injected clock: I = clamp(floor(alpha T_remaining / t_iter),
// iMin, iMax), smoothed upwards, immediate downwards (adaptive_controller.h).
#include "haif/adaptive_controller.h"
#include "haif/world.h"

#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace haif {
namespace {

ControlContext context(double budgetMs, double elapsedMs, uint32_t totalRows = 3000, uint32_t largestRows = 300,
                       int threads = 1, uint32_t bodies = 100) {
  ControlContext c;
  c.budgetMs = budgetMs;
  c.elapsedMs = elapsedMs;
  c.totalRows = totalRows;
  c.largestRows = largestRows;
  c.islands = 10;
  c.bodies = bodies;
  c.contactPoints = totalRows / 3;
  c.threads = threads;
  return c;
}

// The documented formula, computed here from the inputs, for an adaptive controller that has not
// observed a step yet (so its post-solve estimate is the model's msPerBody * bodies / 2).
int expectedUnclamped(const CostModel& m, const AdaptiveSettings& s, const ControlContext& c) {
  const double crit = CostModel::criticalRows(c.totalRows, c.largestRows, c.threads, m.parallelEfficiency);
  const double post = m.msPerBody * 0.5 * c.bodies;
  const double remaining = c.budgetMs - c.elapsedMs - post - m.msPerRowPrepare * crit;
  const double tIter = m.msPerRowIteration * crit;
  return int(std::floor(s.alpha * std::max(0.0, remaining) / tIter));
}

TEST(AdaptiveController, CriticalPathIsLargerOfBiggestIslandAndShare) {
  EXPECT_DOUBLE_EQ(CostModel::criticalRows(3000, 300, 1, 0.85), 3000.0);
  EXPECT_DOUBLE_EQ(CostModel::criticalRows(3000, 300, 4, 0.85), 3000.0 / (1.0 + 3 * 0.85));
  EXPECT_DOUBLE_EQ(CostModel::criticalRows(3000, 2500, 4, 0.85), 2500.0);  // one giant island dominates
  CostModel m;
  AdaptiveController ac(m, AdaptiveSettings{}, true);
  const ControlContext c = context(4.0, 1.0, 3000, 300, 4);
  EXPECT_DOUBLE_EQ(ac.iterationMs(c), m.msPerRowIteration * 3000.0 / (1.0 + 3 * 0.85));
}

TEST(AdaptiveController, FollowsTheFormula) {
  CostModel m;
  AdaptiveSettings s;
  int inRange = 0;
  for (double budget : {2.0, 3.0, 4.0, 8.0, 16.0})
    for (double elapsed : {0.0, 0.5, 1.0, 2.5})
      for (int threads : {1, 2, 4}) {
        AdaptiveController ac(m, s, true);  // fresh: no smoothing history
        const ControlContext c = context(budget, elapsed, 3000, 300, threads);
        const int raw = expectedUnclamped(m, s, c);
        const int got = ac.choose(c);
        EXPECT_EQ(got, std::clamp(raw, s.iMin, s.iMax)) << "budget " << budget << " elapsed " << elapsed
                                                        << " threads " << threads;
        inRange += raw > s.iMin && raw < s.iMax;
      }
  EXPECT_GT(inRange, 10) << "too few cases exercise the formula away from the clamps";
}

TEST(AdaptiveController, ElapsedTimeReducesIterations) {
  CostModel m;
  AdaptiveSettings s;
  AdaptiveController fresh1(m, s, true), fresh2(m, s, true);
  const int early = fresh1.choose(context(4.0, 0.2));
  const int late = fresh2.choose(context(4.0, 2.5));
  EXPECT_GT(early, late) << "time already spent must leave less for the solver";
}

TEST(AdaptiveController, RespectsIMinAndIMax) {
  CostModel m;
  AdaptiveSettings s;
  s.iMin = 3;
  s.iMax = 20;
  AdaptiveController big(m, s, true);
  EXPECT_EQ(big.choose(context(1000.0, 0.0)), 20);
  AdaptiveController tiny(m, s, true);
  EXPECT_EQ(tiny.choose(context(0.001, 0.0)), 3) << "a budget too small for iMin still gets iMin";
  AdaptiveController over(m, s, true);
  EXPECT_EQ(over.choose(context(4.0, 50.0)), 3) << "already over budget: iMin, never less";
  AdaptiveController none(m, s, true);
  EXPECT_EQ(none.choose(context(0.0, 0.0)), 20) << "no budget: full precision";
}

TEST(AdaptiveController, RisesByAtMostMaxStepUpButFallsAtOnce) {
  CostModel m;
  AdaptiveSettings s;
  s.maxStepUp = 2;
  AdaptiveController ac(m, s, true);
  const ControlContext low = context(1.0, 0.0), high = context(100.0, 0.0);
  const int first = ac.choose(low);
  ASSERT_GT(expectedUnclamped(m, s, high), first + 10) << "test set-up: the high budget must allow far more";
  int prev = first;
  for (int k = 0; k < 5; ++k) {
    const int I = ac.choose(high);
    EXPECT_EQ(I, std::min(prev + s.maxStepUp, s.iMax)) << "step " << k;
    prev = I;
  }
  const int dropped = ac.choose(low);
  EXPECT_EQ(dropped, std::clamp(expectedUnclamped(m, s, low), s.iMin, s.iMax)) << "must fall at once";
}

TEST(AdaptiveController, FirstStepIsNotLearnedFrom) {
  // Step 0 pays one-time costs (every pair new, arrays grow): a slow step 0 changes nothing.
  CostModel m;
  AdaptiveController ac(m, AdaptiveSettings{}, true);
  const ControlContext c = context(4.0, 0.0);
  const double before = ac.iterationMs(c);
  SolveObservation obs;
  obs.iterations = 4;
  obs.rowIterations = uint64_t(c.totalRows) * 4u;
  obs.solveMs = 100.0;
  obs.integrateMs = 0.01;
  ac.observe(c, obs);
  EXPECT_EQ(ac.iterationMs(c), before);
  ControlContext next = c;
  next.step = 1;
  ac.observe(next, obs);
  EXPECT_GT(ac.iterationMs(next), 10.0 * before) << "from step 1 on, measured steps replace the model at once";
}

TEST(AdaptiveController, ModelModeIgnoresTheClock) {
  CostModel m;
  AdaptiveSettings s;
  AdaptiveController a(m, s, false), b(m, s, false);
  EXPECT_FALSE(a.usesClock());
  EXPECT_EQ(a.name(), "model");
  EXPECT_EQ(a.choose(context(4.0, 0.0)), b.choose(context(4.0, 3.9)));
  // Learning is off in model mode: an observation changes nothing.
  SolveObservation obs;
  obs.solveMs = 50.0;
  obs.iterations = 10;
  obs.criticalRowIterations = 3000;
  const ControlContext c = context(4.0, 0.0);
  const double before = a.iterationMs(c);
  a.observe(c, obs);
  EXPECT_EQ(a.iterationMs(c), before);
}

TEST(AdaptiveController, PlansWithTheIntegrationTimeItMeasured) {
  // After steps whose integration took 2 ms, the time left for sweeps is the budget less 2 ms, not
  // less the model's guess: the count is exactly the formula's with the measured time. (Ignoring the
  // measurement moved the choice by one iteration, which a tolerance of 1 let through.)
  CostModel m;
  AdaptiveSettings s;
  AdaptiveController ac(m, s, true);
  const ControlContext c = context(4.0, 0.5, 3000, 300, 1, 100);
  ac.choose(c);
  SolveObservation obs;  // no solve time and no step total: only the integration time is learned
  obs.integrateMs = 2.0;
  ControlContext later = c;
  for (int k = 1; k <= 5; ++k) {
    later.step = uint64_t(k);
    ac.observe(later, obs);
  }
  const double crit = CostModel::criticalRows(c.totalRows, c.largestRows, c.threads, m.parallelEfficiency);
  const double remaining = c.budgetMs - c.elapsedMs - 2.0 - m.msPerRowPrepare * crit;
  const int expected = int(std::floor(s.alpha * remaining / (m.msPerRowIteration * crit)));
  ASSERT_GT(expected, ac.iMin);
  ASSERT_LT(expected, ac.iMax);
  ASSERT_LT(expected, expectedUnclamped(m, s, c) - 1) << "the model's guess must differ, or this tests nothing";
  EXPECT_EQ(ac.choose(c), expected);
}

TEST(AdaptiveController, LearnsFromSlowSolves) {
  // A measured solve far slower than the model raises the per-row estimate, lowering later counts.
  CostModel m;
  AdaptiveSettings s;
  AdaptiveController ac(m, s, true);
  const ControlContext c = context(8.0, 0.5);
  const int before = ac.choose(c);
  const double itBefore = ac.iterationMs(c);
  SolveObservation obs;
  obs.iterations = before;
  obs.criticalRowIterations = uint64_t(c.largestRows) * uint64_t(before);
  obs.solveMs = 20.0 * (m.msPerRowPrepare + before * m.msPerRowIteration) * c.totalRows;  // 20x the model
  obs.integrateMs = 0.01;
  ControlContext later = c;
  for (int k = 1; k <= 10; ++k) {  // step 0 is not learned from (one-time costs)
    later.step = uint64_t(k);
    ac.observe(later, obs);
  }
  EXPECT_GT(ac.iterationMs(c), 2.0 * itBefore);
  EXPECT_LT(ac.choose(c), before);
}

TEST(ReplayController, ReplaysCountsAndRepeatsTheLast) {
  ReplayController r({5, 7, 9});
  ControlContext c;
  const int want[] = {5, 7, 9, 9, 9};
  for (uint64_t k = 0; k < 5; ++k) {
    c.step = k;
    EXPECT_EQ(r.choose(c), want[k]);
  }
}

// A World whose budget cannot be met reports every miss (the miss is never hidden).
TEST(AdaptiveController, TinyBudgetInWorldReportsEveryMiss) {
  WorldSettings ws;
  ws.budgetMs = 0.001;
  World w(ws);
  test::addGround(w);
  test::addColumn(w, 5, 0.0f, 0.0f, 1.01f);
  AdaptiveSettings s;
  s.iMin = 4;
  w.setController(std::make_unique<AdaptiveController>(CostModel{}, s, true));
  for (int k = 0; k < 30; ++k) {
    w.step();
    const StepStats& st = w.lastStats();
    EXPECT_TRUE(st.deadlineMiss) << "step " << k << " took " << st.totalMs << " ms of a 0.001 ms budget";
    EXPECT_GT(st.totalMs, st.budgetMs);
    EXPECT_EQ(st.budgetMs, 0.001);
    if (st.contactPoints > 0) {
      EXPECT_EQ(st.iterationsChosen, s.iMin) << "step " << k;
    }
  }
}

TEST(AdaptiveController, GenerousBudgetInWorldMissesNothing) {
  WorldSettings ws;
  ws.budgetMs = 10000.0;
  World w(ws);
  BodyDef d;
  d.shape = Shape::box(Vec3::Constant(0.5f));
  d.mass = 1.0f;
  d.xf.p = Vec3(0.0f, 0.5f, 0.0f);
  w.addBody(d);
  AdaptiveSettings s;
  w.setController(std::make_unique<AdaptiveController>(CostModel{}, s, true));
  for (int k = 0; k < 10; ++k) {
    w.step();
    EXPECT_FALSE(w.lastStats().deadlineMiss) << "step " << k << ": " << w.lastStats().totalMs << " ms";
  }
}

}  // namespace
}  // namespace haif

namespace haif {
namespace {

// A solve whose once-per-step part is 7x a sweep (the model says 2x) and whose sweep is 1.5x the
// model's. With the measured split of the solve the controller must learn both, not one scale at
// the model's ratio, and then spend the budget the formula gives with the true costs.
TEST(AdaptiveController, LearnsPrepareAndSweepCostsSeparately) {
  CostModel m;
  AdaptiveSettings s;
  AdaptiveController ac(m, s, true);
  ControlContext c = context(6.0, 0.5, 3000, 300, 1, 100);
  const double crit = CostModel::criticalRows(c.totalRows, c.largestRows, c.threads, m.parallelEfficiency);
  const double sweep = 1.5 * m.msPerRowIteration, prepare = 7.0 * sweep;
  const double post = 0.05;
  int I = 0;
  for (int k = 0; k < 60; ++k) {
    c.step = uint64_t(k);
    I = ac.choose(c);
    SolveObservation obs;
    obs.iterations = I;
    obs.rowIterations = uint64_t(c.totalRows) * uint64_t(I);
    obs.criticalRowIterations = uint64_t(c.largestRows) * uint64_t(I);
    obs.solveMs = crit * (prepare + I * sweep);
    obs.fixedThreadMs = crit * prepare;  // one thread: thread time is wall time
    obs.sweepThreadMs = crit * I * sweep;
    obs.integrateMs = post;
    ac.observe(c, obs);
  }
  EXPECT_NEAR(ac.iterationMs(c), sweep * crit, 0.1 * sweep * crit);
  const int ideal = int(std::floor(s.alpha * (c.budgetMs - c.elapsedMs - post - prepare * crit) / (sweep * crit)));
  ASSERT_GT(ideal, s.iMin + 2) << "test set-up: the budget must leave room above iMin";
  EXPECT_NEAR(I, ideal, 1);
}

}  // namespace
// A recorded-style cost trace replayed through the controller, no clock: each step's true cost is
// the model's shape with hidden factors (sweeps 1.6x dearer than the model, integration 0.4 ms) and
// scatter (lognormal, sigma 0.15, and one step in 20 taking 1.4x: other work on the same cores).
// Returns the share of steps over a 4 ms budget and the mean iteration count.
std::pair<double, double> replayScatteredTrace(double aimQuantile, int steps = 3000) {
  CostModel m;
  AdaptiveSettings s;
  s.aimQuantile = aimQuantile;
  AdaptiveController ac(m, s, true);
  std::mt19937 rng(7);
  std::lognormal_distribution<double> scatter(0.0, 0.15);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int misses = 0;
  double iterations = 0.0;
  for (int k = 0; k < steps; ++k) {
    ControlContext c = context(4.0, 0.5 + 0.1 * u(rng), 6000, 600, 1, 400);
    c.step = uint64_t(k);
    const int I = ac.choose(c);
    const double crit = ac.criticalRows(c);
    const double noise = scatter(rng) * (u(rng) < 0.05 ? 1.4 : 1.0);
    SolveObservation obs;
    obs.iterations = I;
    obs.rowIterations = uint64_t(c.totalRows) * uint64_t(I);
    obs.criticalRowIterations = uint64_t(c.largestRows) * uint64_t(I);
    obs.fixedThreadMs = m.msPerRowPrepare * crit * noise;
    obs.sweepThreadMs = 1.6 * m.msPerRowIteration * crit * I * noise;
    obs.solveMs = obs.fixedThreadMs + obs.sweepThreadMs;
    obs.integrateMs = 0.4 * noise;
    obs.totalMs = c.elapsedMs + obs.solveMs + obs.integrateMs;
    ac.observe(c, obs);
    if (k >= 100) {  // after the learning start
      misses += obs.totalMs > c.budgetMs ? 1 : 0;
      iterations += I;
    }
  }
  return {double(misses) / (steps - 100), iterations / (steps - 100)};
}

TEST(AdaptiveController, ScatteredCostsMissAtMostOnePercent) {
  // Planning at the mean (the median overrun) misses about half the steps whose cost scatters
  // upward; at the 95th percentile of the recent overruns, under 1 % with the budget still used.
  const auto [aimed, iterations] = replayScatteredTrace(0.95);
  const auto [median, medianIterations] = replayScatteredTrace(0.5);
  EXPECT_LT(aimed, 0.01);
  EXPECT_GT(median, 0.1) << "the control should miss";
  EXPECT_GT(iterations, 0.6 * medianIterations) << "the margin must not starve the solver";
  EXPECT_GT(iterations, double(AdaptiveSettings{}.iMin) + 2.0);
}

}  // namespace haif
