// The Bullet baseline behind the EngineRun interface (built only when Bullet is found).
#pragma once

#include "bullet/bullet_world.h"
#include "tools/engine_run.h"

#include <memory>

namespace haif {

class BulletEngineRun final : public EngineRun {
 public:
  /// Loads the scene into a Bullet world with `iterations` solver iterations (<= 0: the scene's).
  static std::unique_ptr<BulletEngineRun> create(const std::string& scenePath, int iterations, std::string& error);

  const char* engine() const override { return "bullet"; }
  std::string label() const override { return "bullet fixed:" + std::to_string(world_.iterations()); }
  const SceneDesc& scene() const override { return scene_; }
  int threads() const override { return 1; }
  uint32_t bodyCount() const override { return world_.bodyCount(); }
  EngineStepInfo step() override;
  void readBodies(std::vector<BodySample>& out) const override;
  void readContacts(std::vector<ContactSample>& out) const override;
  uint64_t stateHash() const override;

  const BulletWorld& world() const { return world_; }

 private:
  SceneDesc scene_;
  BulletWorld world_;
  mutable std::vector<BulletContactPoint> points_;
  mutable std::vector<BodySample> hashScratch_;
};

}  // namespace haif
