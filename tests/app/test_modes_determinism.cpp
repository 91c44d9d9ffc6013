// Fixed, model and replay modes are bit-identical for any thread count, and replaying any run's
// logged iteration counts (adaptive, model, fixed) reproduces that run exactly (docs/architecture.md,
// Threads and "The iteration controller").
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
  std::string summary;  ///< summary.json text (the replay log's scene and early-stopping rule)
};

RunResult run(const SolverSpec& spec, int threads, const std::string& scene = kScene) {
  Simulation sim;
  std::string error;
  RunResult r;
  EXPECT_TRUE(makeSimulation(scene, spec, threads, sim, error)) << error;
  if (!sim.world) return r;
  // Contact by contact: the stacks then depend on every iteration, so a hash compares schedules.
  // Solved as chains they converge in a sweep or two, and schedules would give equal states.
  sim.world->settings().chainSolve = false;
  RunMetrics metrics;
  metrics.begin(*sim.world, kSteps);
  EXPECT_TRUE(runSteps(sim, kSteps, r.stats, metrics)) << "NaN in " << spec.mode;
  r.hash = sim.world->stateHash();
  RunInfo info = runInfoFor(sim, spec.budgetMs, threads);
  info.stateHash = r.hash;
  r.summary = summaryJson(info, r.stats, metrics, *sim.world);
  return r;
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("haif_test_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// The run's stats.csv and summary.json, as `haif run` writes them; returns the stats.csv path.
std::string writeLog(const RunResult& r, const std::string& name) {
  const fs::path p = tempDir(name) / "stats.csv";
  std::ofstream(p) << statsCsv(r.stats);
  std::ofstream(p.parent_path() / "summary.json") << r.summary;
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
  rs.replayPath = writeLog(src, "replay_threads");
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
  rs.replayPath = writeLog(adaptive, "replay_adaptive");
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

// A fixed run stops no island early; its replay used to stop converged islands at the adaptive
// modes' tolerance and ran fewer sweeps (tower_collapse: 4 where the run had run 10).
TEST(ModeDeterminism, ReplayOfFixedRunReproducesIt) {
  SolverSpec spec = fixedSpec();
  spec.iterations = 10;
  const RunResult fixed = run(spec, 1);
  SolverSpec rs;
  rs.mode = "replay";
  rs.replayPath = writeLog(fixed, "replay_fixed");
  const RunResult replay = run(rs, 2);
  EXPECT_EQ(replay.hash, fixed.hash);
  ASSERT_EQ(replay.stats.size(), fixed.stats.size());
  for (size_t k = 0; k < replay.stats.size(); ++k)
    ASSERT_EQ(replay.stats[k].rowIterations, fixed.stats[k].rowIterations) << "step " << k;
  fs::remove_all(fs::path(rs.replayPath).parent_path());
}

TEST(ModeDeterminism, ReplayRefusesALogOfAnotherSceneOrWithoutItsSummary) {
  const RunResult other = run(fixedSpec(), 1, std::string(HAIF_SOURCE_DIR) + "/scenes/pyramid_15.json");
  SolverSpec rs;
  rs.mode = "replay";
  rs.replayPath = writeLog(other, "replay_other");
  Simulation sim;
  std::string error;
  EXPECT_FALSE(makeSimulation(kScene, rs, 1, sim, error));
  EXPECT_NE(error.find(rs.replayPath + ": a log of scene 'pyramid_15' (scene_hash "), std::string::npos) << error;
  EXPECT_NE(error.find("not of " + kScene), std::string::npos) << error;
  // A stats.csv alone says neither the scene nor the early-stopping rule.
  fs::remove(fs::path(rs.replayPath).parent_path() / "summary.json");
  EXPECT_FALSE(makeSimulation(kScene, rs, 1, sim, error));
  EXPECT_NE(error.find("summary.json: cannot open run summary"), std::string::npos) << error;
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
