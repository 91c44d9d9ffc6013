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

/// Reads the `iterations_chosen` column of a stats.csv written by statsCsv (for replay mode).
bool readChosenIterations(const std::string& path, std::vector<int>& out, std::string& error);

}  // namespace haif
