// One physics engine stepping one scene, behind a small interface, so that the benchmark (and
// side-by-side comparisons) can drive HAIF and the Bullet baseline the same way and compute the
// same error metrics from what every engine can report: body states and contact depths.
#pragma once

#include "core/math.h"
#include "scene/scene_desc.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// What one step cost and did.
struct EngineStepInfo {
  double ms = 0.0;          ///< wall time of the step (HAIF: without its solve-error measurement)
  int iterations = 0;       ///< solver iterations the step ran (HAIF: the count chosen)
  double solveError = NAN;  ///< solve error (docs/metrics.md), when the engine measured it this step
  bool deadlineMiss = false;///< over the step budget (engines with a budget only)
};

/// State of one body after a step, in scene order. Positions are centres of mass.
struct BodySample {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();
  Vec3 v = Vec3::Zero();  ///< linear velocity (m/s)
  Vec3 w = Vec3::Zero();  ///< angular velocity (rad/s)
  bool dynamic = false;
};

/// One contact point of the last step's collision pass.
struct ContactSample {
  float depth = 0.0f;   ///< penetration (m); <= 0: separated or just touching
  float extent = 0.0f;  ///< smallest extent of the smaller of the two bodies (m), to express depth as a fraction
};

class EngineRun {
 public:
  virtual ~EngineRun() = default;

  /// "haif" or "bullet".
  virtual const char* engine() const = 0;
  /// Engine and solver set-up, e.g. "haif fixed:10" or "bullet fixed:10".
  virtual std::string label() const = 0;
  virtual const SceneDesc& scene() const = 0;
  virtual int threads() const = 0;
  virtual uint32_t bodyCount() const = 0;

  /// Advances the scene by one time step.
  virtual EngineStepInfo step() = 0;
  /// Every body's state, in scene order (reuses `out`'s storage).
  virtual void readBodies(std::vector<BodySample>& out) const = 0;
  /// The contact points found by the last step's collision detection (reuses `out`'s storage).
  virtual void readContacts(std::vector<ContactSample>& out) const = 0;
  /// Hash of every body's position and orientation bits: equal states give equal hashes.
  virtual uint64_t stateHash() const = 0;

  /// Whether step() can report the solve error (docs/metrics.md) (it needs the engine's solver inside).
  virtual bool canMeasureSolveError() const { return false; }
  /// Measure the solve error every `every` steps (0: never); ignored where it cannot be measured.
  virtual void setSolveErrorInterval(int every) { (void)every; }
};

/// FNV-1a over the float bits of each pose (p.xyz, q.xyzw): the same hash World::stateHash gives.
uint64_t hashPoses(const std::vector<BodySample>& bodies);

}  // namespace haif
