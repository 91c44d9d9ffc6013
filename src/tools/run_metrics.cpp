#include "tools/run_metrics.h"

#include <cmath>

namespace haif {

void RunMetrics::begin(const World& world, uint64_t plannedSteps) {
  *this = RunMetrics{};
  plannedSteps_ = plannedSteps;
  const BodyStore& b = world.bodies();
  startY_.resize(b.size());
  for (size_t i = 0; i < b.size(); ++i) startY_[i] = b.xf[i].p.y();
  e0_ = world.kineticEnergy() + world.potentialEnergy();
}

bool RunMetrics::afterStep(const World& world) {
  ++steps_;
  const BodyStore& b = world.bodies();
  // A hull's smallest extent is a pass over its faces and vertices: once per body, not per contact.
  for (uint32_t i = uint32_t(extent_.size()); i < world.bodyCount(); ++i) extent_.push_back(smallestExtent(world.shape(i)));
  for (const Contact& c : world.contacts()) {
    if (!c.touching()) continue;
    const float ext = std::min(extent_[c.a], extent_[c.b]);
    for (int i = 0; i < c.manifold.count; ++i) {
      const double d = std::max(0.0f, c.manifold.points[i].depth);
      maxPen_ = std::max(maxPen_, d);
      if (ext > 0.0f && ext < 1e29f) maxPenFrac_ = std::max(maxPenFrac_, d / ext);
      penSq_ += d * d;
      ++penCount_;
    }
  }
  for (uint32_t j = 0; j < world.jointCount(); ++j) {
    if (world.joint(j).broken) continue;
    const JointError e = world.jointError(j);
    maxJointM_ = std::max(maxJointM_, double(e.linear));
    maxJointRad_ = std::max(maxJointRad_, double(e.angular));
    jointSq_ += double(e.linear) * double(e.linear);
    ++jointCount_;
  }
  const uint64_t window = static_cast<uint64_t>(std::lround(1.0 / world.settings().dt));
  const bool last = plannedSteps_ <= window || steps_ > plannedSteps_ - window;
  for (size_t i = 0; i < b.size(); ++i) {
    if (b.kind[i] != BodyKind::Dynamic) continue;
    if (!isFinite(b.xf[i].p) || !isFinite(b.v[i]) || !isFinite(b.w[i]) || !std::isfinite(b.xf[i].q.w())) nan_ = true;
    if (last) {
      velSq_ += b.v[i].squaredNorm();
      ++velCount_;
    }
  }
  return !nan_;
}

double RunMetrics::meanDrop(const World& world) const {
  const BodyStore& b = world.bodies();
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    if (b.kind[i] != BodyKind::Dynamic) continue;
    sum += startY_[i] - b.xf[i].p.y();
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

double RunMetrics::maxDrop(const World& world) const {
  const BodyStore& b = world.bodies();
  double m = 0.0;
  for (size_t i = 0; i < b.size(); ++i)
    if (b.kind[i] == BodyKind::Dynamic) m = std::max(m, double(startY_[i] - b.xf[i].p.y()));
  return m;
}

double RunMetrics::energyDriftRelative(const World& world) const {
  const double e = world.kineticEnergy() + world.potentialEnergy();
  return e0_ != 0.0 ? (e - e0_) / std::fabs(e0_) : 0.0;
}

}  // namespace haif
