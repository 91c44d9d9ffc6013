// No explosion, ever: a bound on how fast any body may move, from what the scene gives it.
//
// A body crushed between a moving kinematic body and static geometry, or caught in contacts and
// joints that cannot all hold, has no solution the sweeps can find: its impulses grow from sweep to
// sweep and from step to step (warm starting carries them), and the body leaves at whatever speed
// the last one gave it (a sweeper in a pit threw a body out at 1184 m/s). Energy in a scene comes
// only from the bodies' start speeds, their fall, kinematic surfaces, joint motors, user forces and
// water, so
//   V = factor (fastest start + free fall from the highest start to the lowest body now
//               + 2 × (fastest kinematic surface + fastest motor surface)
//               + Σ user-force impulse per mass) + floor
// bounds every body's surface speed |v| + |ω| r (r: its bounding radius). The factor leaves room for
// what collisions pass on (a heavy body hitting a light one at rest gives it up to twice its speed).
// A motor is a source like a kinematic surface: it drives its bodies' relative speed to its aim, so
// an island's motors together move a surface at most at the sum of their aims times their levers
// (World::motorSurfaceSpeed). Twice that: a wheel rolling at its motor's aim moves its rim at 2 ω r.
// A body over V is slowed to V along its own motion (not stopped), a NaN one is stopped; both are
// counted in StepStats::speedLimited so a reviewer sees the bound act.
#pragma once

#include "collision/shape.h"
#include "core/body_store.h"

#include <cstdint>
#include <vector>

namespace haif {

struct SpeedBoundSettings {
  float factor = 2.0f;  ///< 0 turns the bound off
  float floor = 2.0f;   ///< m/s added to the bound: push-out of bodies that start overlapping
};

class SpeedBound {
 public:
  /// Records a body (its bounding radius; start speed and height are read at the next update).
  void addBody(const Shape& shape);
  /// Once per step, before the forces are integrated: new bodies' start speeds and heights, the
  /// fastest kinematic surface, and the user forces about to act. `waterLift`: the densest water over
  /// the lightest body's density (0 without water): buoyancy lifts such a body by g times it.
  /// `floor`: the lowest point of the static geometry along up (+inf without any: none): a body that
  /// fell below it left the scene (through the ground, off its edge) and can strike nothing, so
  /// the fall term stops there instead of growing with it.
  void update(const BodyStore& bodies, const Vec3& gravity, float dt, float waterLift, float floor);
  /// The fastest surface the motors of one island drive this step (m/s), once their aims are known
  /// (after the islands are built, before apply).
  void setMotorSurface(float speed);
  /// Slows every awake dynamic body in [begin, end) whose surface speed is over the bound; returns
  /// how many it slowed. A body wholly below the floor has left the scene and is let fall (slowing
  /// it protects nothing, and counting it hid real acts). Thread-safe over disjoint ranges.
  uint32_t apply(BodyStore& bodies, uint32_t begin, uint32_t end) const;
  /// Tracks the lowest dynamic body (for the free-fall term); call after positions moved.
  void noteLowest(const BodyStore& bodies, const Vec3& up);
  float limit() const { return limit_; }
  /// A body's bounding radius about its centre of mass (0 for planes and meshes).
  float reach(uint32_t body) const { return reach_[body]; }
  const float* reaches() const { return reach_.data(); }

  SpeedBoundSettings settings;

 private:
  std::vector<float> reach_;  // per body: bounding radius (m)
  uint32_t seen_ = 0;         // bodies whose start state has been read
  float fastestStart_ = 0.0f, highestStart_ = -1e30f, lowest_ = 1e30f;
  float forceAllowance_ = 0.0f;  // m/s of speed user forces have given at most, summed over steps
  float limit_ = 1e30f;
  float base_ = 0.0f;          // fastest start + free fall + 2 × kinematic + force allowance (m/s)
  float motorSurface_ = 0.0f;  // the fastest motor surface (m/s)
  void setLimit();
  Vec3 up_ = Vec3::UnitY();
  float floor_ = -1e30f;  // the static floor along up_ (-1e30: none)
};

}  // namespace haif
