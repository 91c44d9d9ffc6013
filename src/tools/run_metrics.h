// Error metrics of a run (docs/metrics.md), accumulated step by step.
#pragma once

#include "haif/world.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace haif {

class RunMetrics {
 public:
  /// Records the start state; `plannedSteps` fixes the window of the last simulated second.
  void begin(const World& world, uint64_t plannedSteps);
  /// Accumulates after each step. Returns false once a NaN/inf appeared in the state.
  bool afterStep(const World& world);

  double maxPenetration() const { return maxPen_; }            ///< m
  double maxPenetrationFraction() const { return maxPenFrac_; }///< of the smaller body's smallest extent
  double rmsPenetration() const { return penCount_ ? std::sqrt(penSq_ / double(penCount_)) : 0.0; }
  double meanDrop(const World& world) const;                   ///< m: start minus end height, dynamic bodies
  double maxDrop(const World& world) const;
  double rmsVelocityLastSecond() const { return velCount_ ? std::sqrt(velSq_ / double(velCount_)) : 0.0; }
  bool nanDetected() const { return nan_; }
  double energyDriftRelative(const World& world) const;        ///< (E - E0) / E0, total mechanical energy
  /// Joint error (docs/metrics.md) after each step over the unbroken joints: anchor separation and angle.
  double maxJointError() const { return maxJointM_; }          ///< m
  double rmsJointError() const { return jointCount_ ? std::sqrt(jointSq_ / double(jointCount_)) : 0.0; }  ///< m
  double maxJointErrorAngle() const { return maxJointRad_; }   ///< rad

 private:
  std::vector<float> startY_;
  std::vector<float> extent_;  // per body: smallestExtent of its shape
  uint64_t plannedSteps_ = 0, steps_ = 0;
  double maxPen_ = 0, maxPenFrac_ = 0, penSq_ = 0;
  uint64_t penCount_ = 0;
  double velSq_ = 0;
  uint64_t velCount_ = 0;
  bool nan_ = false;
  double maxJointM_ = 0, maxJointRad_ = 0, jointSq_ = 0;
  uint64_t jointCount_ = 0;
  double e0_ = 0;
};

}  // namespace haif
