// The "stress" block of a scene file: how long `haif stress` runs the scene and the checks it must
// pass (docs/stress.md). Plain data; `haif run` and every other reader ignore it.
#pragma once

#include "core/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// What a check measures. Each compares one metric of the run with a limit.
enum class StressCheckKind : uint8_t {
  MaxDrop,               ///< max_drop_m: start minus end height (m) <= max, all dynamic bodies or one
  MinDrop,               ///< min_drop_m: one body's start minus end height (m) >= min (it fell)
  MaxPenetration,        ///< max_penetration_m: deepest contact over the run (m) <= max
  FinalPenetration,      ///< final_penetration_m: deepest contact after the last step (m) <= max
  PeakSpeed,             ///< peak_speed: fastest dynamic body (or one body) over the run (m/s) <= max
  EnergyGainRatio,       ///< energy_gain_ratio: max over steps of (E - E0) / |E0| <= max
  AngularMomentumDrift,  ///< angular_momentum_drift: max over steps of | |L| - |L0| | / |L0| <= max
  IntermediateAxisFlip,  ///< intermediate_axis_flip: one body's axis turns over against its L >= min_flips times
  NoTunnel,              ///< no_tunnel: one body's centre never crosses a plane (metric: min distance on its side)
  MaxJointError,         ///< max_joint_error_m: largest joint anchor error over the run (m) <= max
  SpeedLimited,          ///< speed_limited: bodies the speed bound slowed, summed over the run, <= max
};

struct StressCheck {
  StressCheckKind kind = StressCheckKind::MaxDrop;
  std::string name;        ///< as written in the file, e.g. "max_drop_m"
  double limit = 0.0;      ///< max, min, or min_flips
  int32_t body = -1;       ///< scene body index, -1: all dynamic bodies
  Vec3 axis = Vec3::UnitY();  ///< intermediate_axis_flip: body-frame axis; no_tunnel: plane normal (unit)
  float offset = 0.0f;     ///< no_tunnel: plane offset, points x with dot(normal, x) = offset
  std::string where;       ///< place in the scene file, e.g. "stress.checks[2]"
};

struct StressDesc {
  bool given = false;       ///< the scene file has a "stress" block
  int steps = 300;          ///< steps of the full run
  int quickSteps = 300;     ///< steps under --quick (default: steps)
  bool inQuick = true;      ///< false: skipped under --quick
  std::string quickNote;    ///< why it is skipped or shortened under --quick (shown in stress.json)
  std::vector<StressCheck> checks;
};

}  // namespace haif
