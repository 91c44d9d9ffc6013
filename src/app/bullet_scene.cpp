// `bullet:N` as one side of `haif compare` or a clip of `haif reel`: Bullet steps the scene; a HAIF
// World built from the same file (never stepped) supplies the shapes and render meshes, and takes
// Bullet's poses before each frame, so both engines are drawn by the same code.
#if defined(HAIF_HAVE_BULLET) && defined(HAIF_HAVE_RENDER)
#include "app/frame_builder.h"
#include "app/simulated_scene.h"
#include "scene/build_world.h"
#include "tools/bullet_engine_run.h"

#include <cmath>

namespace haif {

namespace {

class BulletScene final : public SimulatedScene {
 public:
  bool open(const std::string& scenePath, int iterations, std::string& error) {
    run_ = BulletEngineRun::create(scenePath, iterations, error);
    if (!run_) return false;
    shadow_ = std::make_unique<World>(run_->scene().settings.world);
    if (!buildWorld(run_->scene(), *shadow_, error)) return false;
    spec_ = "bullet:" + std::to_string(iterations);
    description_ = "Bullet 3, " + std::to_string(iterations) + " solver iterations";
    return true;
  }

  const std::string& spec() const override { return spec_; }
  const std::string& description() const override { return description_; }
  const std::string& sceneName() const override { return run_->scene().name; }
  int sceneFrames() const override { return run_->scene().settings.frames; }
  int bodyCount() const override { return int(run_->bodyCount()); }
  double stepSeconds() const override { return run_->scene().settings.world.dt; }
  float budgetMs() const override { return 0.f; }
  float iMin() const override { return float(iterations()); }
  float iMax() const override { return float(iterations()); }

  bool prepare(render::Renderer& renderer, std::string& error) override {
    return builder_.registerMeshes(*shadow_, run_->scene(), renderer, error);
  }

  bool step(std::string& error) override {
    const EngineStepInfo info = run_->step();
    ++steps_;
    history_.totalMs.push_back(float(info.ms));
    history_.collisionMs.push_back(0.f);  // Bullet's step is not split into stages here
    history_.solveMs.push_back(float(info.ms));
    history_.iterations.push_back(float(info.iterations));
    run_->readBodies(samples_);
    for (const BodySample& s : samples_)
      if (!std::isfinite(s.p.x()) || !std::isfinite(s.p.y()) || !std::isfinite(s.p.z())) {
        error = spec_ + ": the state turned NaN at step " + std::to_string(steps_ - 1);
        return false;
      }
    BodyStore& bodies = shadow_->bodies();
    for (uint32_t i = 0; i < samples_.size() && i < bodies.size(); ++i) {
      bodies.xf[i].p = samples_[i].p;
      bodies.xf[i].q = samples_[i].q;
      bodies.v[i] = samples_[i].v;
      bodies.w[i] = samples_[i].w;
    }
    return true;
  }

  const StepHistory& history() const override { return history_; }

  void buildFrame(render::FrameInput& frame) const override {
    builder_.build(*shadow_, run_->scene().camera, frame);
    render::Overlay& o = frame.overlay;
    o.scene = run_->scene().name;
    o.mode = spec_;
    o.bodies = bodyCount();
    o.islands = 0;
    o.step = steps_ - 1;
    o.msPerStep = history_.totalMs.empty() ? 0.f : history_.totalMs.back();
    o.iMin = iMin();
    o.iMax = iMax();
    o.budgetMs = 0.f;
    o.iterations = history_.iterations;
    o.collisionMs = history_.collisionMs;
    o.solveMs = history_.solveMs;
  }

 private:
  int iterations() const { return run_->world().iterations(); }

  std::unique_ptr<BulletEngineRun> run_;
  std::unique_ptr<World> shadow_;
  FrameBuilder builder_;
  std::vector<BodySample> samples_;
  StepHistory history_;
  std::string spec_, description_;
  int64_t steps_ = 0;
};

}  // namespace

std::unique_ptr<SimulatedScene> makeBulletScene(const std::string& scenePath, int iterations, int threads,
                                                std::string& error) {
  (void)threads;  // the baseline runs Bullet's single-threaded solver
  auto scene = std::make_unique<BulletScene>();
  if (!scene->open(scenePath, iterations, error)) return nullptr;
  return scene;
}

}  // namespace haif
#endif
