#include "tools/bullet_engine_run.h"

#include "scene/scene_loader.h"

#include <algorithm>
#include <chrono>

namespace haif {

std::unique_ptr<BulletEngineRun> BulletEngineRun::create(const std::string& scenePath, int iterations,
                                                         std::string& error) {
  auto run = std::unique_ptr<BulletEngineRun>(new BulletEngineRun());
  if (!loadSceneFile(scenePath, run->scene_, error)) return nullptr;
  if (!run->world_.build(run->scene_, iterations, error)) return nullptr;
  return run;
}

EngineStepInfo BulletEngineRun::step() {
  const auto t0 = std::chrono::steady_clock::now();
  world_.step();
  EngineStepInfo info;
  info.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  info.iterations = world_.iterations();
  return info;
}

void BulletEngineRun::readBodies(std::vector<BodySample>& out) const {
  out.resize(world_.bodyCount());
  for (uint32_t i = 0; i < world_.bodyCount(); ++i) {
    BodySample& s = out[i];
    const Transform xf = world_.pose(i);
    s.p = xf.p;
    s.q = xf.q;
    s.v = world_.linearVelocity(i);
    s.w = world_.angularVelocity(i);
    s.dynamic = world_.isDynamic(i);
  }
}

void BulletEngineRun::readContacts(std::vector<ContactSample>& out) const {
  world_.readContactPoints(points_);
  out.clear();
  for (const BulletContactPoint& p : points_)
    out.push_back({p.depth, std::min(world_.smallestExtent(p.a), world_.smallestExtent(p.b))});
}

uint64_t BulletEngineRun::stateHash() const {
  readBodies(hashScratch_);
  return hashPoses(hashScratch_);
}

}  // namespace haif
