// HAIF behind the EngineRun interface: a Simulation (scene, world, iteration controller) stepped
// one step at a time.
#pragma once

#include "tools/engine_run.h"
#include "tools/simulation.h"

#include <memory>

namespace haif {

class HaifEngineRun final : public EngineRun {
 public:
  /// Loads the scene and sets up the solver (`spec`) on `threads` threads. One error line on failure.
  static std::unique_ptr<HaifEngineRun> create(const std::string& scenePath, const SolverSpec& spec, int threads,
                                               std::string& error);

  const char* engine() const override { return "haif"; }
  std::string label() const override { return label_; }
  const SceneDesc& scene() const override { return sim_.scene; }
  int threads() const override { return sim_.world->threads(); }
  uint32_t bodyCount() const override { return sim_.world->bodyCount(); }
  EngineStepInfo step() override;
  void readBodies(std::vector<BodySample>& out) const override;
  void readContacts(std::vector<ContactSample>& out) const override;
  uint64_t stateHash() const override { return sim_.world->stateHash(); }
  bool canMeasureSolveError() const override { return true; }
  void setSolveErrorInterval(int every) override { sim_.world->setSolveErrorInterval(every); }

  const World& world() const { return *sim_.world; }

 private:
  Simulation sim_;
  std::string label_;
  std::vector<float> extent_;  // smallestExtent per body
};

}  // namespace haif
