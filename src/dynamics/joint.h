// Joints: persistent constraints between two bodies (or a body and the world), described by a frame
// on each body. The joint's axis is the x axis of its frame, its reference direction the y axis.
#pragma once

#include "core/math.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace haif {

/// Stands for the world (a fixed frame at the origin) in place of a body id.
inline constexpr uint32_t kWorldBody = 0xffffffffu;

enum class JointType : uint8_t {
  Ball = 0,   ///< anchors coincide; free rotation
  Hinge,      ///< anchors coincide, axes aligned; rotation about the axis (limits, motor)
  Fixed,      ///< anchors coincide, frames aligned
  Distance,   ///< anchor distance within [minDistance, maxDistance]: a rod when equal, a rope when min = 0
  Slider,     ///< frames aligned, anchor B on the axis through anchor A; translation along it (limits, motor)
  ConeTwist,  ///< anchors coincide; the axis of B stays in a cone about the axis of A, twist limited
  Count
};

const char* jointTypeName(JointType t);

/// A target position of a servo motor at a time: rad (hinge) or m (slider).
struct ServoKey {
  float time = 0.0f;
  float position = 0.0f;
};

struct JointDef {
  JointType type = JointType::Ball;
  uint32_t bodyA = kWorldBody, bodyB = kWorldBody;
  Vec3 localAnchorA = Vec3::Zero();  ///< in body A's frame (world frame for kWorldBody)
  Vec3 localAnchorB = Vec3::Zero();
  Quat localFrameA = Quat::Identity();  ///< joint frame in body A's frame: x = axis, y = reference
  Quat localFrameB = Quat::Identity();
  bool collideConnected = false;  ///< false: the two bodies do not collide with each other

  bool limitEnabled = false;  ///< hinge: angle (rad), slider: translation (m) within [lower, upper]
  float lower = 0.0f, upper = 0.0f;
  float minDistance = 0.0f;   ///< distance joint (m)
  float maxDistance = 0.0f;
  float swingLimit = kPi;     ///< cone-twist: half angle of the cone (rad)
  float twistLower = -kPi, twistUpper = kPi;  ///< cone-twist: twist about the axis (rad)

  bool motorEnabled = false;  ///< hinge, slider: drive the relative speed to motorSpeed
  float motorSpeed = 0.0f;    ///< rad/s or m/s
  float maxMotorForce = 0.0f; ///< N m (hinge) or N (slider); the motor never pushes harder
  std::vector<ServoKey> servo;  ///< non-empty: the motor follows these positions (piecewise linear in time)
  bool servoLoop = false;       ///< repeat the trajectory after its last key
  float servoTime = 0.1f;       ///< s: the servo closes a position error in about this time

  float breakForce = std::numeric_limits<float>::infinity();   ///< N: the joint breaks above this
  float breakTorque = std::numeric_limits<float>::infinity();  ///< N m
};

/// Rows of a joint's equality block (solved together) and of its limit/motor rows (solved one by one).
inline constexpr int kJointBlockRows = 6;
inline constexpr int kJointExtraRows = 3;

/// A joint in a World: its definition and what persists from step to step.
struct Joint {
  JointDef def;
  float blockImpulse[kJointBlockRows] = {};  ///< accumulated impulses (warm start), row meaning fixed per type
  float extraImpulse[kJointExtraRows] = {};
  bool broken = false;
  /// Distance joint with min < max (a rope): this step its max bound is an equality row that may only
  /// pull (solved with the tree), not a limit row (prepareJointForStep).
  bool taut = false;
  bool inTree = false;  ///< last step its equality rows were solved by the island's joint tree
  Vec3 lastForce = Vec3::Zero();   ///< N: constraint force on B during the last step
  float heldForce = 0.0f;          ///< N: |lastForce|, let fall by at most JointSolverParams::stiffnessHold a step
  Vec3 lastTorque = Vec3::Zero();  ///< N m
};

/// Solver rows a joint uses per sweep (its share of an island's work).
uint32_t jointRowCount(const JointDef& d);

/// How far a joint is from satisfied: anchor separation (m) and angular error (rad), limits included.
struct JointError {
  float linear = 0.0f;
  float angular = 0.0f;
};

/// A joint def whose frames are placed from world data at the bodies' current transforms, so the
/// joint starts satisfied: `anchor` and `axis` in world space (the axis is the frame's x; the reference
/// y is any perpendicular). `anchorB` differs from `anchor` only for distance joints.
JointDef jointAtWorld(JointType type, uint32_t bodyA, uint32_t bodyB, const Transform& xfA, const Transform& xfB,
                      const Vec3& anchor, const Vec3& axis, const Vec3& anchorB);

}  // namespace haif
