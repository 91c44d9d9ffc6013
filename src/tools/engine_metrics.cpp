#include "tools/engine_metrics.h"

#include <algorithm>

namespace haif {

void EngineMetrics::begin(const EngineRun& run, uint64_t plannedSteps) {
  *this = EngineMetrics{};
  plannedSteps_ = plannedSteps;
  window_ = uint64_t(std::max(1L, std::lround(1.0 / run.scene().settings.world.dt)));
  run.readBodies(bodies_);
  startY_.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) startY_[i] = bodies_[i].p.y();
}

bool EngineMetrics::afterStep(const EngineRun& run) {
  ++steps_;
  run.readContacts(contacts_);
  for (const ContactSample& c : contacts_) {
    const double d = std::max(0.0f, c.depth);  // depth beyond nothing, not beyond the slop
    maxPen_ = std::max(maxPen_, d);
    if (c.extent > 0.0f && c.extent < 1e29f) maxPenFrac_ = std::max(maxPenFrac_, d / c.extent);
    penSq_ += d * d;
    ++penCount_;
  }
  run.readBodies(bodies_);
  const bool last = plannedSteps_ <= window_ || steps_ > plannedSteps_ - window_;
  double dropSum = 0.0, dropMax = 0.0;
  size_t dynamic = 0;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodySample& b = bodies_[i];
    if (!b.dynamic) continue;
    if (!isFinite(b.p) || !isFinite(b.v) || !isFinite(b.w) || !std::isfinite(b.q.w())) nan_ = true;
    const double drop = double(startY_[i]) - b.p.y();
    dropSum += drop;
    dropMax = std::max(dropMax, drop);
    ++dynamic;
    if (last) {
      velSq_ += b.v.squaredNorm();
      ++velCount_;
    }
  }
  meanDrop_ = dynamic ? dropSum / double(dynamic) : 0.0;
  maxDrop_ = dropMax;
  return !nan_;
}

}  // namespace haif
