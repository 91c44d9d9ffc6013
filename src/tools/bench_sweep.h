// The benchmark's unit of work: one engine and solver set-up run on one scene for a number of
// steps, measuring its cost (ms per step) and its error (docs/metrics.md) the same way for every engine.
#pragma once

#include "tools/engine_spec.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// What to run.
struct BenchPoint {
  EngineSpec spec;  ///< engine, mode (fixed / adaptive) and its parameter
  int threads = 1;  ///< HAIF's worker threads (Bullet always runs on one)
};

/// What one run cost and how wrong it was.
struct BenchResult {
  std::string scene;
  uint32_t bodies = 0;
  std::string engine, mode;  ///< "haif" / "bullet"; "fixed" / "adaptive"
  double param = 0;          ///< iterations (fixed) or budget in ms (adaptive)
  std::string label;         ///< e.g. "haif adaptive:4"
  int threads = 1, steps = 0;
  double msMedian = 0, msP95 = 0;
  /// Median process CPU time of a step (all threads, ms): the work, which other programs on a busy
  /// machine do not inflate the way they inflate wall time; equals ms/step for one thread on an idle machine.
  double cpuMsMedian = 0;
  double iterationsMean = 0, missRate = 0;
  double solveError = NAN;   ///< mean solve error (docs/metrics.md) over the sampled steps; NaN: not available
  double maxPenetration = 0, rmsPenetration = 0, maxPenetrationFraction = 0;
  double meanDrop = 0, maxDrop = 0, jitter = 0;
  bool nan = false;
  uint64_t stateHash = 0;
  /// Runs behind this result (haif bench --repeat), and the fastest and slowest of their ms/step medians.
  int rounds = 1;
  double msMin = 0, msMax = 0;
};

/// Runs `point` on the scene at `scenePath` for `steps` steps, sampling the solve error every
/// `errorEvery` steps where the engine can (0: never). One error line on failure.
bool runBenchPoint(const std::string& scenePath, const BenchPoint& point, int steps, int errorEvery,
                   BenchResult& out, std::string& error);

/// One result for a set-up run several times (`runs`, non-empty; haif bench --repeat): ms/step is
/// the median of the runs' medians (the lower middle one for an even count), p95 and CPU time the
/// same way; errors, iterations and the state hash come from the run whose ms/step that is (fixed
/// set-ups give the same in every run). On a machine whose speed drifts, runs of different set-ups
/// taken in rotation see the same conditions, so their medians compare where single runs do not.
BenchResult combineRounds(const std::vector<BenchResult>& runs);

/// An error metric the report tabulates and plots against ms/step.
struct BenchMetric {
  const char* key;    ///< file-name and column friendly, e.g. "max_penetration"
  const char* title;  ///< e.g. "max penetration (m)"
  double (*get)(const BenchResult&);
};
/// Solve error, max penetration, mean drop and jitter, in that order.
const std::vector<BenchMetric>& benchErrorMetrics();

/// Curve a result belongs to in the plots: engine, mode and thread count, e.g. "haif adaptive, 2 threads".
std::string benchCurveName(const BenchResult& r);

}  // namespace haif
