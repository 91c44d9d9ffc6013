// A scene loaded into a World with a solver set-up: what `run`, `bench` and `calibrate` share.
#pragma once

#include "haif/world.h"
#include "scene/scene_desc.h"
#include "tools/run_metrics.h"
#include "tools/run_report.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace haif {

/// How the solver chooses its iteration count.
struct SolverSpec {
  std::string mode = "fixed";   ///< fixed | adaptive | model | replay
  int iterations = -1;          ///< fixed: count (-1: the scene's); adaptive/model: I_max bound if > 0
  double budgetMs = 4.0;        ///< adaptive/model
  int iMin = 4;                 ///< adaptive/model
  std::string replayPath;       ///< replay: stats.csv of the run to replay
  std::string calibrationPath;  ///< adaptive/model: cost model file ("" = built-in defaults)
  float residualTolerance = 1e-5f;  ///< adaptive/model: islands stop below this correction (m/s)
};

/// Parses "fixed:10", "adaptive:4", "model:4", "replay:RUN/stats.csv".
bool parseSolverSpec(const std::string& text, SolverSpec& out, std::string& error);

struct Simulation {
  SceneDesc scene;
  std::unique_ptr<World> world;
  std::string mode;
  int replaySteps = -1;  ///< replay: the steps its log holds (it cannot run more); -1: any number
};

/// What summary.json says of the run besides its steps: scene, scene hash, mode, budget (none in
/// fixed mode), threads and the early-stopping rule that replay reproduces.
RunInfo runInfoFor(const Simulation& sim, double budgetMs, int threads);

/// False with one error line when `steps` is more than a replay's log holds.
bool checkReplayLength(const Simulation& sim, const SolverSpec& spec, int steps, std::string& error);

/// Loads the scene, builds its world and installs the controller. One error line on failure.
bool makeSimulation(const std::string& scenePath, const SolverSpec& spec, int threads, Simulation& sim,
                    std::string& error);

/// Steps `steps` times, filling per-step stats and metrics; `afterStep` (may be empty) runs after
/// every step. `holdBeside` (may be empty) is called with true before each step and with false
/// after it: encoders running beside a filmed run wait while a step runs (tools/video.h,
/// EncodingHold). Stops early, returning false, when the state turns NaN.
bool runSteps(Simulation& sim, int steps, std::vector<StepStats>& stats, RunMetrics& metrics,
              const std::function<void(const World&)>& afterStep = {},
              const std::function<void(bool)>& holdBeside = {});

}  // namespace haif
