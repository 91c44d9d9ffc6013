// The error metrics of docs/metrics.md that any engine can be measured by, computed from what the
// EngineRun interface reports (body states and contact depths), so HAIF and Bullet are judged by
// the same code: penetration, drop, jitter. (The solve error needs the solver's inside: the engine
// reports it itself, or it is not available.)
#pragma once

#include "tools/engine_run.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace haif {

class EngineMetrics {
 public:
  /// Records the start state; `plannedSteps` fixes the window of the last simulated second.
  void begin(const EngineRun& run, uint64_t plannedSteps);
  /// Accumulates after each step. Returns false once a NaN/inf appeared in the state.
  bool afterStep(const EngineRun& run);

  double maxPenetration() const { return maxPen_; }              ///< m, over all contact points and steps
  double maxPenetrationFraction() const { return maxPenFrac_; }  ///< of the smaller body's smallest extent
  double rmsPenetration() const { return penCount_ ? std::sqrt(penSq_ / double(penCount_)) : 0.0; }
  double meanDrop() const { return meanDrop_; }  ///< m: start minus latest height, mean over dynamic bodies
  double maxDrop() const { return maxDrop_; }
  /// RMS linear speed (m/s) of the dynamic bodies over the last simulated second: jitter where
  /// everything should be at rest.
  double jitter() const { return velCount_ ? std::sqrt(velSq_ / double(velCount_)) : 0.0; }
  bool nanDetected() const { return nan_; }

 private:
  std::vector<float> startY_;
  std::vector<BodySample> bodies_;
  std::vector<ContactSample> contacts_;
  uint64_t plannedSteps_ = 0, steps_ = 0, window_ = 60;
  double maxPen_ = 0, maxPenFrac_ = 0, penSq_ = 0;
  uint64_t penCount_ = 0;
  double velSq_ = 0;
  uint64_t velCount_ = 0;
  double meanDrop_ = 0, maxDrop_ = 0;
  bool nan_ = false;
};

}  // namespace haif
