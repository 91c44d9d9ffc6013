#include "tools/simulation.h"

#include "haif/adaptive_controller.h"
#include "scene/build_world.h"
#include "scene/scene_loader.h"
#include "tools/run_report.h"

#include <cstdlib>

namespace haif {

bool parseSolverSpec(const std::string& text, SolverSpec& out, std::string& error) {
  const size_t colon = text.find(':');
  const std::string mode = text.substr(0, colon);
  const std::string arg = colon == std::string::npos ? "" : text.substr(colon + 1);
  SolverSpec s;
  s.mode = mode;
  char* end = nullptr;
  if (mode == "fixed") {
    const long v = std::strtol(arg.c_str(), &end, 10);
    if (arg.empty() || *end != '\0' || v < 1 || v > 10000) {
      error = "solver spec '" + text + "': fixed needs an iteration count, e.g. fixed:10";
      return false;
    }
    s.iterations = int(v);
  } else if (mode == "adaptive" || mode == "model") {
    const double v = std::strtod(arg.c_str(), &end);
    if (arg.empty() || *end != '\0' || !(v > 0.0) || v > 10000.0) {
      error = "solver spec '" + text + "': " + mode + " needs a budget in ms, e.g. " + mode + ":4";
      return false;
    }
    s.budgetMs = v;
  } else if (mode == "replay") {
    if (arg.empty()) {
      error = "solver spec '" + text + "': replay needs a stats.csv, e.g. replay:output/run/stats.csv";
      return false;
    }
    s.replayPath = arg;
  } else {
    error = "solver spec '" + text + "': unknown mode '" + mode + "' (fixed, adaptive, model, replay)";
    return false;
  }
  out = s;
  return true;
}

bool makeSimulation(const std::string& scenePath, const SolverSpec& spec, int threads, Simulation& sim,
                    std::string& error) {
  if (!loadSceneFile(scenePath, sim.scene, error)) return false;
  WorldSettings ws = sim.scene.settings.world;
  ws.threads = threads;
  sim.world = std::make_unique<World>(ws);
  if (!buildWorld(sim.scene, *sim.world, error)) return false;
  World& w = *sim.world;
  sim.mode = spec.mode;
  if (spec.mode == "fixed") {
    const int n = spec.iterations > 0 ? spec.iterations : sim.scene.settings.world.iterations;
    w.settings().iterations = n;
    w.setController(std::make_unique<FixedController>(n));
  } else if (spec.mode == "adaptive" || spec.mode == "model") {
    CostModel model;
    if (!spec.calibrationPath.empty() && !model.load(spec.calibrationPath, error)) return false;
    AdaptiveSettings as;
    as.iMin = spec.iMin;
    if (spec.iterations > 0) as.iMax = std::max(spec.iterations, as.iMin);
    w.settings().budgetMs = spec.budgetMs;
    w.settings().residualTolerance = spec.residualTolerance;
    w.setController(std::make_unique<AdaptiveController>(model, as, spec.mode == "adaptive"));
  } else if (spec.mode == "replay") {
    ReplayLog log;
    if (!readReplayLog(spec.replayPath, log, error)) return false;
    if (log.sceneHash != hashText(sim.scene.sourceHash)) {
      error = spec.replayPath + ": a log of scene '" + log.scene + "' (scene_hash " + log.sceneHash + "), not of " +
              scenePath + " (scene_hash " + hashText(sim.scene.sourceHash) + "): replay a run of this scene file";
      return false;
    }
    // Replay reproduces the recorded run: its counts and its early-stopping rule, none in a fixed
    // run (a replay that stopped converged islands early ran 4 sweeps where the run had run 10).
    w.settings().residualTolerance = log.residualTolerance;
    // ... and its budget or none: without one, islands in motion get sweeps for their depth
    // (World::sweepsForDepth), which a budget leaves to the controller.
    w.settings().budgetMs = log.hadBudget ? spec.budgetMs : 0.0;
    sim.replaySteps = int(log.iterations.size());
    auto c = std::make_unique<ReplayController>(std::move(log.iterations));
    c->iMin = log.iMin;
    w.setController(std::move(c));
  } else {
    error = "unknown mode '" + spec.mode + "' (fixed, adaptive, model, replay)";
    return false;
  }
  return true;
}

RunInfo runInfoFor(const Simulation& sim, double budgetMs, int threads) {
  World& w = *sim.world;  // controller() has no const overload
  RunInfo info;
  info.scene = sim.scene.name;
  info.sceneHash = sim.scene.sourceHash;
  info.bodies = w.bodyCount();
  info.threads = threads;
  info.mode = sim.mode;
  info.budgetMs = sim.mode == "fixed" ? 0.0 : budgetMs;
  info.iMin = w.controller().iMin;
  info.residualTolerance = w.settings().residualTolerance;
  return info;
}

bool checkReplayLength(const Simulation& sim, const SolverSpec& spec, int steps, std::string& error) {
  if (sim.replaySteps < 0 || steps <= sim.replaySteps) return true;
  error = spec.replayPath + ": the log holds " + std::to_string(sim.replaySteps) + " steps, fewer than the " +
          std::to_string(steps) + " to run: run at most " + std::to_string(sim.replaySteps) + " (--frames)";
  return false;
}

bool runSteps(Simulation& sim, int steps, std::vector<StepStats>& stats, RunMetrics& metrics,
              const std::function<void(const World&)>& afterStep, const std::function<void(bool)>& holdBeside) {
  World& w = *sim.world;
  stats.reserve(stats.size() + size_t(steps));
  for (int s = 0; s < steps; ++s) {
    if (holdBeside) holdBeside(true);
    w.step();
    if (holdBeside) holdBeside(false);
    stats.push_back(w.lastStats());
    const bool finite = metrics.afterStep(w);
    if (afterStep) afterStep(w);
    if (!finite) return false;
  }
  return true;
}

}  // namespace haif
