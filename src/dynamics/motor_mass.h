// Servos along a jointed arm, solved together through the joint tree. A motor row swept with the mass
// of its own two bodies asks too little of an arm whose links carry more links: the tree shares its
// push with all of them, and the sweeps reach the motor's speed a fraction at a time. A servo
// following a path then lags, its position error grows its speed, and it overshoots: robot_arm's
// 2 kg hand swung at up to 16 m/s at 4 iterations (2.9 m/s converged) and the speed bound caught a
// body 699 times in a minute. Measured through the tree one by one, six servos stacked in a mast
// still fought each other sweep after sweep (each turns everything above it). So the motors of a
// tree are solved together: S Δλ = −(J v + b) with S = J M⁻¹ Jᵀ − Gᵀ A⁻¹ G over the motors (G: the
// tree rows' velocity under each motor's push, A: the tree's system), the tree's answer to their
// pushes then comes from its own solve, which follows in the sweep (solveJointIteration).
#pragma once

#include "core/body_store.h"
#include "dynamics/joint_solver.h"
#include "dynamics/joint_tree.h"

#include <cstdint>
#include <vector>

namespace haif {

/// Motors solved together, at most: S is factored every step (the cube of the count) and each motor
/// costs a solve of the tree to make. Islands with more keep the sweep's motor pass.
inline constexpr uint32_t kMaxTreeMotors = 16;

/// An island's motors seen through its joint tree: their system S, made once a step. Buffers grow to
/// the largest island seen and are reused.
struct TreeMotors {
  uint32_t count = 0;              ///< motors solved here (0: none, or the island is past the cap)
  std::vector<uint32_t> joint;     ///< index into the island's joints, per motor
  std::vector<double> system;      ///< S, count x count, row-major
  std::vector<double> push, answer;  ///< per motor, the tree's rows: G under its push, A⁻¹ G (scratch)
};

/// Makes `motors` for the island's joints `js` at the rows prepared for this step, after tree.build.
/// Marks them (JointConstraint::motorThroughTree) so that the sweep's own motor pass leaves them.
/// Past kMaxTreeMotors motors, or a motor whose axis the tree (nearly) locks, none are taken.
void prepareTreeMotors(JointConstraint* js, uint32_t n, JointTree& tree, TreeMotors& motors);

/// What the motors take back of a push when they hold their axes: with `rowVelocity[a]` motor a's
/// row read under the push (the tree's answer included), the motors' impulses d = −S⁻¹ g give the
/// pushed row back gᵀ S⁻¹ g of its motion (S is symmetric: the row's motion under motor a's push
/// through the tree is motor a's row under the row's push). Force bounds are not read: whether a
/// motor has the force to hold is for the solve to find (a servo at its bound last step pushes as
/// hard this step, and the bodies it drives are no lighter for it). Zero when `motors` is empty.
double motorsTakeBack(const TreeMotors& motors, const double* rowVelocity);

/// The motors' impulse changes d for one sweep, against the system S (m × m, row-major) and its
/// Cholesky factor L: S d = −(J v + b) at the bodies' velocities, projected onto the force bounds.
void motorChanges(const BodyStore& bodies, const JointConstraint* js, const TreeMotors& motors, const double* S,
                  const double* L, bool useBias, double* d);
/// Adds d to the motors' impulses and applies it to their bodies; returns the largest velocity change
/// asked of a motor row (|d| S_aa).
float applyMotorChanges(BodyStore& bodies, JointConstraint* js, const TreeMotors& motors, const double* S,
                        const double* d);
/// In-place Cholesky factor of an SPD m × m matrix (row-major, lower triangle); false when not
/// positive definite.
bool choleskyFactor(double* s, uint32_t m);

/// One sweep's motors: the impulses that bring every motor to its speed once the tree answers
/// (projected onto their force bounds), applied to the motors' bodies. The tree's solve must follow.
/// Returns the largest velocity change asked of a motor row.
float solveTreeMotors(BodyStore& bodies, JointConstraint* js, const TreeMotors& motors, bool useBias);

}  // namespace haif
