#include "tools/haif_engine_run.h"

#include <algorithm>
#include <cstdio>

namespace haif {

std::unique_ptr<HaifEngineRun> HaifEngineRun::create(const std::string& scenePath, const SolverSpec& spec,
                                                     int threads, std::string& error) {
  auto run = std::unique_ptr<HaifEngineRun>(new HaifEngineRun());
  if (!makeSimulation(scenePath, spec, threads, run->sim_, error)) return nullptr;
  const World& w = *run->sim_.world;
  if (spec.mode == "fixed")
    run->label_ = "haif fixed:" + std::to_string(w.settings().iterations);
  else if (spec.mode == "replay")
    run->label_ = "haif replay";
  else {
    char budget[32];
    std::snprintf(budget, sizeof budget, "%g", spec.budgetMs);
    run->label_ = "haif " + spec.mode + ":" + budget;
  }
  run->extent_.resize(w.bodyCount());
  for (uint32_t i = 0; i < w.bodyCount(); ++i) run->extent_[i] = smallestExtent(w.shape(i));
  return run;
}

EngineStepInfo HaifEngineRun::step() {
  World& w = *sim_.world;
  w.step();
  const StepStats& s = w.lastStats();
  EngineStepInfo info;
  info.ms = s.totalMs;
  info.iterations = s.iterationsChosen;
  info.solveError = s.solveError;
  info.deadlineMiss = s.deadlineMiss;
  return info;
}

void HaifEngineRun::readBodies(std::vector<BodySample>& out) const {
  const BodyStore& b = sim_.world->bodies();
  out.resize(b.size());
  for (size_t i = 0; i < b.size(); ++i) {
    BodySample& s = out[i];
    s.p = b.xf[i].p;
    s.q = b.xf[i].q;
    s.v = b.v[i];
    s.w = b.w[i];
    s.dynamic = b.kind[i] == BodyKind::Dynamic;
  }
}

void HaifEngineRun::readContacts(std::vector<ContactSample>& out) const {
  out.clear();
  for (const Contact& c : sim_.world->contacts()) {
    if (!c.touching()) continue;
    const float ext = std::min(extent_[c.a], extent_[c.b]);
    for (int i = 0; i < c.manifold.count; ++i) out.push_back({c.manifold.points[i].depth, ext});
  }
}

}  // namespace haif
