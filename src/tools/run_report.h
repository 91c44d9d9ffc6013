// stats.csv (one row per step) and summary.json of a run (docs/metrics.md).
#pragma once

#include "haif/step_stats.h"
#include "tools/run_metrics.h"

#include <string>
#include <utility>
#include <vector>

namespace haif {

struct RunInfo {
  std::string scene;
  uint64_t sceneHash = 0;         ///< SceneDesc::sourceHash: replay checks that its log is of this scene
  float residualTolerance = 0.f;  ///< the early-stopping rule of the run (0: none), for replay
  uint32_t bodies = 0;
  int threads = 1;
  std::string mode;
  double budgetMs = 0;
  int iMin = 0;  ///< the controller's floor on the iteration count (budgeted runs)
  uint64_t stateHash = 0;
  double renderMsPerFrameMedian = -1;  ///< < 0: not rendered
  /// With `haif run --render-phases`: the median ms of each render phase, in render order.
  std::vector<std::pair<std::string, double>> renderPhaseMsMedian;
};

/// The CSV header and one line per step.
std::string statsCsv(const std::vector<StepStats>& steps);

/// Value at quantile q in [0, 1] of `values` (nearest rank; 0 for none).
double quantile(std::vector<double> values, double q);

/// summary.json text.
std::string summaryJson(const RunInfo& info, const std::vector<StepStats>& steps, const RunMetrics& metrics,
                        const World& world);

/// The keys of summary.json whose values are numbers (or null when not measured), in the order it
/// writes them, budgeted modes' keys included: what the checks of `haif suite` may name. Read from
/// summaryJson itself, so the list cannot drift from the file.
const std::vector<std::string>& summaryNumberKeys();

/// Reads the `iterations_chosen` column of a stats.csv written by statsCsv (for replay mode).
bool readChosenIterations(const std::string& path, std::vector<int>& out, std::string& error);

/// What replay mode reads back from a run: the iteration count of each step (its stats.csv) and,
/// from the summary.json beside it, the scene it ran and its early-stopping rule, without which a
/// replay of a fixed run (no early stop) stopped converged islands early and ran fewer sweeps.
struct ReplayLog {
  std::vector<int> iterations;
  std::string scene;             ///< the run's scene name (for messages)
  std::string sceneHash;         ///< summary.json "scene_hash", 16 hex digits
  float residualTolerance = 0.f; ///< islands stopped below this correction (0: never)
  int iMin = 1;                  ///< ... but not before this many sweeps
  bool hadBudget = true;         ///< summary.json "budget_ms" > 0: a fixed run had no frame budget
};

/// Reads RUN/stats.csv (`statsPath`) and RUN/summary.json. One error line naming the file on failure.
bool readReplayLog(const std::string& statsPath, ReplayLog& out, std::string& error);

/// A 64-bit hash as summary.json writes it (16 hex digits).
std::string hashText(uint64_t hash);

}  // namespace haif
