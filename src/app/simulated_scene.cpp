#include "app/simulated_scene.h"

#include "tools/simulation.h"

#include <cstdio>
#include <cstdlib>

namespace haif {

namespace {

bool isBulletSpec(const std::string& spec) {
  return spec.rfind("bullet", 0) == 0 && (spec.size() == 6 || spec[6] == ':');
}

// The N of "bullet:N", or 0 when it is not a count in [1, 10000].
int bulletIterations(const std::string& spec) {
  const std::string arg = spec.size() > 7 ? spec.substr(7) : "";
  char* end = nullptr;
  const long n = std::strtol(arg.c_str(), &end, 10);
  return arg.empty() || *end != '\0' || n < 1 || n > 10000 ? 0 : int(n);
}

}  // namespace

bool checkSimulationSpec(const std::string& spec, std::string& error) {
  if (isBulletSpec(spec)) {
    if (bulletIterations(spec) == 0) {
      error = "solver spec '" + spec + "': bullet needs an iteration count, e.g. bullet:10";
      return false;
    }
#ifdef HAIF_HAVE_BULLET
    return true;
#else
    error = "solver spec '" + spec + "': this haif was not built with Bullet (no Bullet adapter in this build)";
    return false;
#endif
  }
  SolverSpec solver;
  if (!parseSolverSpec(spec, solver, error)) {
    if (error.find("unknown mode") != std::string::npos) error.insert(error.size() - 1, ", bullet");
    return false;
  }
  return true;
}

}  // namespace haif

#ifdef HAIF_HAVE_RENDER
#include "app/frame_builder.h"

namespace haif {

namespace {

/// HAIF itself under one of its iteration controllers.
class HaifScene : public SimulatedScene {
 public:
  bool open(const std::string& scenePath, const std::string& spec, const SolverSpec& solver, int threads,
            std::string& error) {
    if (!makeSimulation(scenePath, solver, threads, sim_, error)) return false;
    spec_ = spec;
    char buf[128];
    if (solver.mode == "fixed")
      std::snprintf(buf, sizeof buf, "HAIF, %d solver iterations", solver.iterations);
    else if (solver.mode == "adaptive")
      std::snprintf(buf, sizeof buf, "HAIF adaptive, %g ms budget", solver.budgetMs);
    else if (solver.mode == "model")
      std::snprintf(buf, sizeof buf, "HAIF cost model, %g ms budget", solver.budgetMs);
    else
      std::snprintf(buf, sizeof buf, "HAIF replaying %s", solver.replayPath.c_str());
    description_ = buf;
    World& w = *sim_.world;
    budgetMs_ = solver.mode == "adaptive" || solver.mode == "model" ? float(solver.budgetMs) : 0.f;
    iMin_ = float(w.controller().iMin);
    iMax_ = float(std::min(w.controller().iMax, 1000));
    metrics_.begin(w, uint64_t(std::max(1, sim_.scene.settings.frames)));
    return true;
  }

  const std::string& spec() const override { return spec_; }
  const std::string& description() const override { return description_; }
  const std::string& sceneName() const override { return sim_.scene.name; }
  int sceneFrames() const override { return sim_.scene.settings.frames; }
  int bodyCount() const override { return int(sim_.world->bodyCount()); }
  double stepSeconds() const override { return sim_.scene.settings.world.dt; }
  float budgetMs() const override { return budgetMs_; }
  float iMin() const override { return iMin_; }
  float iMax() const override { return iMax_; }
  int stepsAvailable() const override { return sim_.replaySteps; }

  bool prepare(render::Renderer& renderer, std::string& error) override {
    return builder_.registerMeshes(*sim_.world, sim_.scene, renderer, error);
  }

  bool step(std::string& error) override {
    stats_.clear();  // keeps its capacity: no allocation per step
    const bool finite = runSteps(sim_, 1, stats_, metrics_);
    const StepStats& s = sim_.world->lastStats();
    history_.totalMs.push_back(float(s.totalMs));
    history_.collisionMs.push_back(float(s.collisionMs));
    history_.solveMs.push_back(float(s.solveMs));
    history_.iterations.push_back(float(s.iterationsChosen));
    if (!finite) error = spec_ + ": the state turned NaN at step " + std::to_string(s.step);
    return finite;
  }

  const StepHistory& history() const override { return history_; }

  void buildFrame(render::FrameInput& frame) const override {
    builder_.build(*sim_.world, sim_.scene.camera, frame);
    render::Overlay& o = frame.overlay;
    const StepStats& s = sim_.world->lastStats();
    o.scene = sim_.scene.name;
    o.mode = spec_;
    o.bodies = bodyCount();
    o.islands = int(s.islands);
    o.step = int64_t(s.step);
    o.msPerStep = float(s.totalMs);
    o.iMin = iMin_;
    o.iMax = iMax_;
    o.budgetMs = budgetMs_;
    o.iterations = history_.iterations;
    o.collisionMs = history_.collisionMs;
    o.solveMs = history_.solveMs;
  }

 private:
  Simulation sim_;
  FrameBuilder builder_;
  RunMetrics metrics_;
  std::vector<StepStats> stats_;
  StepHistory history_;
  std::string spec_, description_;
  float budgetMs_ = 0.f, iMin_ = 0.f, iMax_ = 0.f;
};

}  // namespace

bool checkStepsAvailable(const SimulatedScene& scene, int steps, std::string& error) {
  const int available = scene.stepsAvailable();
  if (available < 0 || steps <= available) return true;
  error = scene.spec() + ": the log holds " + std::to_string(available) + " steps, fewer than the " +
          std::to_string(steps) + " to show";
  return false;
}

std::unique_ptr<SimulatedScene> makeSimulatedScene(const std::string& scenePath, const std::string& spec, int threads,
                                                   std::string& error) {
  if (!checkSimulationSpec(spec, error)) return nullptr;
#ifdef HAIF_HAVE_BULLET
  if (isBulletSpec(spec)) return makeBulletScene(scenePath, bulletIterations(spec), threads, error);
#endif
  SolverSpec solver;
  parseSolverSpec(spec, solver, error);
  auto scene = std::make_unique<HaifScene>();
  if (!scene->open(scenePath, spec, solver, threads, error)) return nullptr;
  return scene;
}

}  // namespace haif
#endif
