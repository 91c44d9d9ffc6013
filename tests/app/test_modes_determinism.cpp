// Fixed, model and replay modes are bit-identical for any thread count, and replaying an adaptive
// run's logged iteration counts reproduces that run exactly (docs/architecture.md, Threads and
// "The iteration controller").
// Lives in tests/app because test_haif links only haif_physics and makeSimulation is in haif_tools.
#include "tools/run_report.h"
#include "tools/simulation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(HAIF_SOURCE_DIR) + "/scenes/stacks_100.json";
constexpr int kSteps = 120;

struct RunResult {
  uint64_t hash = 0;
  std::vector<StepStats> stats;
};

RunResult run(const SolverSpec& spec, int threads) {
  Simulation sim;
  std::string error;
  RunResult r;
  EXPECT_TRUE(makeSimulation(kScene, spec, threads, sim, error)) << error;
  if (!sim.world) return r;
  // Contact by contact: the stacks then depend on every iteration, so a hash compares schedules.
  // Solved as chains they converge in a sweep or two, and schedules would give equal states.
  sim.world->settings().chainSolve = false;
  RunMetrics metrics;
  metrics.begin(*sim.world, kSteps);
  EXPECT_TRUE(runSteps(sim, kSteps, r.stats, metrics)) << "NaN in " << spec.mode;
  r.hash = sim.world->stateHash();
  return r;
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("haif_test_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string writeStats(const std::vector<StepStats>& stats, const std::string& name) {
  const fs::path p = tempDir(name) / "stats.csv";
  std::ofstream(p) << statsCsv(stats);
  return p.string();
}

SolverSpec fixedSpec() {
  SolverSpec s;
  s.mode = "fixed";
  return s;
}

SolverSpec modelSpec() {
  SolverSpec s;
  s.mode = "model";
  s.budgetMs = 1.0;  // tight enough that the model picks fewer than I_max on some steps
  return s;
}

TEST(ModeDeterminism, FixedIsIdenticalForAnyThreadCount) {
  const RunResult one = run(fixedSpec(), 1);
  EXPECT_EQ(run(fixedSpec(), 2).hash, one.hash);
  EXPECT_EQ(run(fixedSpec(), 4).hash, one.hash);
  EXPECT_EQ(run(fixedSpec(), 1).hash, one.hash);
}

TEST(ModeDeterminism, ModelIsIdenticalForAnyThreadCount) {
  const RunResult one = run(modelSpec(), 1);
  const RunResult two = run(modelSpec(), 2), four = run(modelSpec(), 4);
  EXPECT_EQ(two.hash, one.hash);
  EXPECT_EQ(four.hash, one.hash);
  // The decisions themselves are the same (they come from the model, not the clock).
  ASSERT_EQ(one.stats.size(), four.stats.size());
  for (size_t k = 0; k < one.stats.size(); ++k)
    ASSERT_EQ(one.stats[k].iterationsChosen, four.stats[k].iterationsChosen) << "step " << k;
}

TEST(ModeDeterminism, ReplayIsIdenticalForAnyThreadCount) {
  const RunResult src = run(modelSpec(), 1);
  SolverSpec rs;
  rs.mode = "replay";
  rs.replayPath = writeStats(src.stats, "replay_threads");
  const RunResult one = run(rs, 1);
  EXPECT_EQ(one.hash, src.hash) << "replay of a model run must reproduce it";
  EXPECT_EQ(run(rs, 2).hash, one.hash);
  EXPECT_EQ(run(rs, 4).hash, one.hash);
  fs::remove_all(fs::path(rs.replayPath).parent_path());
}

TEST(ModeDeterminism, ReplayOfAdaptiveRunReproducesIt) {
  SolverSpec as;
  as.mode = "adaptive";
  as.budgetMs = 1.0;
  const RunResult adaptive = run(as, 1);
  SolverSpec rs;  // defaults for residual tolerance and iMin, as the adaptive run had
  rs.mode = "replay";
  rs.replayPath = writeStats(adaptive.stats, "replay_adaptive");
  const RunResult replay = run(rs, 1);
  EXPECT_EQ(replay.hash, adaptive.hash);
  ASSERT_EQ(replay.stats.size(), adaptive.stats.size());
  for (size_t k = 0; k < replay.stats.size(); ++k) {
    ASSERT_EQ(replay.stats[k].iterationsChosen, adaptive.stats[k].iterationsChosen) << "step " << k;
    ASSERT_EQ(replay.stats[k].rowIterations, adaptive.stats[k].rowIterations) << "step " << k;
  }
  // On more threads too.
  EXPECT_EQ(run(rs, 4).hash, adaptive.hash);
  fs::remove_all(fs::path(rs.replayPath).parent_path());
}

TEST(ModeDeterminism, DifferentIterationCountsGiveDifferentStates) {
  // Guards the tests above: the hash must be sensitive to the iteration schedule.
  SolverSpec a = fixedSpec(), b = fixedSpec();
  a.iterations = 4;
  b.iterations = 12;
  EXPECT_NE(run(a, 1).hash, run(b, 1).hash);
}

TEST(ModeDeterminism, ReplayOfMissingLogIsAnError) {
  SolverSpec rs;
  rs.mode = "replay";
  rs.replayPath = "/nonexistent/haif/stats.csv";
  Simulation sim;
  std::string error;
  EXPECT_FALSE(makeSimulation(kScene, rs, 1, sim, error));
  EXPECT_NE(error.find(rs.replayPath), std::string::npos) << error;
}

}  // namespace
}  // namespace haif
