// A scene simulated by one engine set-up, steppable and drawable: one side of `haif compare`, one
// clip of `haif reel`. HAIF's own solver set-ups ("fixed:10", "adaptive:4", "model:4", "replay:...")
// implement it; another engine (the Bullet adapter, "bullet:10") plugs in by implementing it too.
#pragma once

#include <string>

namespace haif {

/// Checks a set-up's syntax and that this build can run it (bullet:N needs the Bullet adapter).
/// One error line naming the spec on failure.
bool checkSimulationSpec(const std::string& spec, std::string& error);

}  // namespace haif

#ifdef HAIF_HAVE_RENDER
#include "render/frame_input.h"
#include "render/renderer.h"

#include <memory>
#include <string>
#include <vector>

namespace haif {

/// Per-step history that the charts plot, oldest first.
struct StepHistory {
  std::vector<float> totalMs, collisionMs, solveMs, iterations;
};

class SimulatedScene {
 public:
  virtual ~SimulatedScene() = default;

  /// The set-up as the user wrote it ("fixed:10"), and in words ("10 solver iterations").
  virtual const std::string& spec() const = 0;
  virtual const std::string& description() const = 0;
  /// Scene name and the frame count its file asks for.
  virtual const std::string& sceneName() const = 0;
  virtual int sceneFrames() const = 0;
  virtual int bodyCount() const = 0;
  /// Simulated seconds per step (for real-time playback).
  virtual double stepSeconds() const = 0;
  /// Step budget in ms (0: none) and the iteration bounds, for chart reference lines.
  virtual float budgetMs() const = 0;
  virtual float iMin() const = 0;
  virtual float iMax() const = 0;
  /// Steps this set-up can run: a replay, the steps its log holds; -1: any number.
  virtual int stepsAvailable() const { return -1; }

  /// Uploads the scene's meshes to `renderer` (once, before the first frame).
  virtual bool prepare(render::Renderer& renderer, std::string& error) = 0;
  /// Advances one step and appends to history(). False with an error once the state turns NaN.
  virtual bool step(std::string& error) = 0;
  virtual const StepHistory& history() const = 0;
  /// Fills the frame's camera, instances and overlay panel (its text and charts) for the current state.
  virtual void buildFrame(render::FrameInput& frame) const = 0;
};

#ifdef HAIF_HAVE_BULLET
/// Provided by the Bullet adapter (built with HAIF_HAVE_BULLET): the scene simulated by Bullet with
/// `iterations` solver iterations; its spec() is "bullet:N".
std::unique_ptr<SimulatedScene> makeBulletScene(const std::string& scenePath, int iterations, int threads,
                                                std::string& error);
#endif

/// The set-up `spec` on the scene file `scenePath`. Specs: fixed:N, adaptive:MS, model:MS, replay:STATS.csv
/// and bullet:N (only in builds with the Bullet adapter: otherwise a clear error). One error line on failure.
/// False with one error line naming the set-up when it cannot run `steps` steps (a short replay log).
bool checkStepsAvailable(const SimulatedScene& scene, int steps, std::string& error);

std::unique_ptr<SimulatedScene> makeSimulatedScene(const std::string& scenePath, const std::string& spec, int threads,
                                                   std::string& error);

}  // namespace haif
#endif
