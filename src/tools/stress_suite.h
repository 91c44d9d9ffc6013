// The stress suite (docs/stress.md): scenes under scenes/stress/, each with a "stress" block of checks,
// simulated in fixed mode and judged by those checks. What `haif stress` and the CI test share.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace haif {

/// One check of one scene after its run.
struct StressCheckResult {
  std::string check;      ///< check name, e.g. "max_drop_m"
  std::string criterion;  ///< readable rule, e.g. "max_drop_m <= 0.05"
  double value = 0.0;     ///< measured metric
  double limit = 0.0;
  bool pass = false;
};

struct StressSceneResult {
  std::string name, file;
  bool skipped = false;    ///< not run (--quick and the scene is out of the quick set)
  std::string note;        ///< the scene's quick_note under --quick
  bool pass = false;       ///< ran, no NaN, every check passed
  uint32_t bodies = 0;
  int steps = 0, stepsRun = 0, iterations = 0;
  double dt = 0.0;
  bool nan = false;        ///< the state turned NaN/inf (the run stopped there)
  std::vector<std::pair<std::string, double>> metrics;  ///< general metrics, in a fixed order
  std::vector<StressCheckResult> checks;
  double wallSeconds = 0.0;
};

class RunMetrics;
class StressProbe;
class World;
struct StressCheck;

/// The measured value of check `i` (its index in the list given to StressProbe::begin) after a run,
/// and whether it passes: what `haif stress` and the run jobs of `haif suite` judge by.
StressCheckResult judgeStressCheck(const StressCheck& c, size_t i, const StressProbe& probe, const RunMetrics& metrics,
                                   const World& world);

/// The scene files (*.json) in `dir`, sorted by name. False with `error` when none can be listed.
bool findStressScenes(const std::string& dir, std::vector<std::string>& paths, std::string& error);

/// Loads, runs and judges one stress scene. False with one error line when the file is bad input (a
/// malformed scene, no "stress" block, an unknown check); a scene that fails its checks returns true.
bool runStressScene(const std::string& path, bool quick, int threads, StressSceneResult& out, std::string& error);

/// stress.json: {"quick", "passed", "failed", "skipped", "scenes": [{"name", "pass", "metrics", "criterion", ...}]}.
std::string stressJson(const std::vector<StressSceneResult>& results, bool quick);

/// One line for the terminal: name, PASS/FAIL/SKIP and the key metric (the first failing check, else the first check).
std::string stressLine(const StressSceneResult& r);

}  // namespace haif
