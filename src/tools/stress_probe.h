// Per-step measurements that the stress checks (docs/stress.md) need beyond RunMetrics: peak speed,
// energy gain, angular momentum drift, intermediate-axis flips, which side of a plane a body is on.
#pragma once

#include "haif/world.h"
#include "scene/stress_desc.h"

#include <cstdint>
#include <vector>

namespace haif {

/// Total angular momentum of the dynamic bodies about the origin: sum of I_w w + m x × v (kg m^2/s).
Eigen::Vector3d totalAngularMomentum(const World& world);

/// Deepest contact point (m, > 0 overlapping) of the current contacts; 0 when nothing overlaps.
double currentMaxPenetration(const World& world);

class StressProbe {
 public:
  /// Records the start state; `checks` say which bodies, axes and planes to follow (scene body
  /// index = world body id).
  void begin(const World& world, const std::vector<StressCheck>& checks);
  /// Accumulates after each step.
  void afterStep(const World& world);

  double peakSpeed() const { return peakSpeed_; }                      ///< m/s, any dynamic body
  double energyGainRatio() const { return energyGain_; }               ///< max (E - E0) / |E0|, >= 0
  double angularMomentumDrift() const { return lDrift_; }
  uint64_t speedLimited() const { return speedLimited_; }              ///< bodies the speed bound slowed, all steps              ///< max | |L| - |L0| | / |L0|
  /// Value of check `i` of those given to begin() for the checks that follow one body or plane:
  /// drop of its body (start minus current height), peak speed of its body, flips of its axis,
  /// smallest distance on its side of the plane.
  double followed(size_t i) const { return follow_[i].value; }

 private:
  struct Follow {
    StressCheckKind kind;
    int32_t body = -1;
    Vec3 axis = Vec3::UnitY();
    float offset = 0.0f;
    double startY = 0.0;  // drops of one body
    float side = 1.0f;  // no_tunnel: sign of the start side
    int state = 0;      // intermediate_axis_flip: last clear sign of axis · L (+1, -1, 0 not yet)
    double value = 0.0;
  };
  void observe(const World& world);
  double e0_ = 0.0, l0_ = 0.0;
  double peakSpeed_ = 0.0, energyGain_ = 0.0, lDrift_ = 0.0;
  uint64_t speedLimited_ = 0;
  std::vector<Follow> follow_;
};

}  // namespace haif
