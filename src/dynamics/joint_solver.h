// Joint rows for the SOR-PGS solver. Each joint is an equality block (anchor coincidence and locked
// rotation axes, up to 6 rows) plus up to 3 limit/motor rows with bounds, solved one by one like contact
// rows. The blocks of joints that form a tree are solved together, exactly, by the island's JointTree
// (Baumgarte bias, then a projection after integration); a joint that closes a loop is solved as its own
// small system per sweep, as a soft constraint. Rows act on the same BodyStore velocities as contacts:
//   Cdot = lin·(vB - vA) + angB·wB - angA·wA,   impulse λ: vA -= mA lin λ, wA -= IA angA λ, vB += ..., wB += ...
#pragma once

#include "core/body_store.h"
#include "dynamics/contact_solver.h"
#include "dynamics/joint.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace haif {

/// How joints are solved; the World holds one (WorldSettings::joints).
struct JointSolverParams {
  bool treeSolve = true;           ///< joints that form a tree: exact block per sweep (JointTree)
  bool geometricStiffness = true;  ///< see accumulateJointStiffness and sidewaysStiffness
  bool postProjection = true;      ///< after integration, project tree joints back onto their constraints
  float beta = 0.5f;               ///< Baumgarte factor of the tree and of limits
  /// Joints outside a tree (closing a loop) are soft constraints with this frequency (at most half the
  /// step rate) and damping ratio: rigid Baumgarte rows, solved partially and warm started, wind up and
  /// blow a loop apart.
  float softHertz = 30.0f;
  float softDampingRatio = 1.0f;
  /// Where no tree holds an island's joints (a net or grid: too many close loops), every row is soft
  /// and swept, and a row stiffer than the sweeps converge on rings: there the frequency is at most
  /// this share of the step rate per main sweep. The 30x30 curtain of stress/joint_grid still moved
  /// at 1.8 m/s RMS after a minute at 4 iterations (3 main sweeps) with 30 Hz rows, 0.001 m/s with
  /// 20.7; a 10x10 net of beads on rods 0.52 -> 0.01 m/s. Borderline measured: 22-25 Hz at 3 sweeps,
  /// ~27 at 4, 30 at 5. Loop rows beside a tree keep softHertz (a ring of 12 links at 4 iterations
  /// opened 3.2 cm at 30 Hz, 4.4 at 20.7, without ringing at either).
  float softHertzPerSweep = 0.115f;
  /// That frequency for a step of `dt` with `mainSweeps` sweeps (Baumgarte's; relax sweeps not counted).
  /// setSoftness applies the half-step-rate bound.
  float softHertzFor(int mainSweeps, float dt) const {
    return std::min(softHertz, softHertzPerSweep * float(std::max(mainSweeps, 1)) / dt);
  }
  /// The force behind a joint's geometric stiffness falls by at most this factor a step (Joint::heldForce).
  /// From the last step's force alone, the stiffness of a bridge under crates flipped with its force,
  /// high one step and low the next, and the bridge tore at 16-64 sweeps.
  float stiffnessHold = 0.97f;
};

/// One Jacobian row with I^-1 times its angular parts.
struct JointRow {
  Vec3 lin, angA, angB;
  Vec3 iAngA, iAngB;
};

/// Solver data of one joint, prepared once per step from the current body state.
struct JointConstraint {
  uint32_t a, b;        // body ids (kWorldBody allowed)
  uint32_t joint;       // index of the Joint it came from
  float invMassA, invMassB;
  bool dynA, dynB;      // only dynamic, awake bodies receive velocity changes
  int blockRows;        // equality rows in use
  int8_t sidewaysRows;  // the last block rows: a taut rod's or rope's sideways stiffness (sidewaysStiffness)
  int extraRows;        // limit/motor rows in use
  bool motor;           // extra row 0 is a motor (solved before the block; limits come after it)
  bool motorThroughTree;  // solved with the island's other motors through its tree (motor_mass.h), not swept
  bool inTree;          // the block is solved by the island's JointTree, not on its own
  uint8_t pullRows;     // bit i: block row i is a taut rope's length, its impulse stays <= 0 (pulling)
  int8_t ownRows;       // block rows of its own joint (the first ones; mergeParallelJoints may add more)
  int32_t host;         // >= 0: its block rows were moved to js[host] (mergeParallelJoints), from row hostRow
  int8_t hostRow;
  bool hostReversed;    // the host's bodies are this joint's B and A
  JointRow block[kJointBlockRows];
  float blockInvK[kJointBlockRows * kJointBlockRows];  // (J M^-1 J^T)^-1, row-major, blockRows^2 used; only
                                                       // outside a tree (prepareSoftBlock)
  float blockError[kJointBlockRows];                   // position error C of each row
  float treeBiasRate;                                  // 1/s: bias = rate * C in the tree (Baumgarte)
  float softBiasRate;                                  // 1/s: bias = rate * C of a soft block (outside a tree)
  float blockImpulse[kJointBlockRows];
  float blockCompliance[kJointBlockRows];  // 1/kg: a soft row solves J v + compliance * impulse = 0; 0 rigid
  float massScale, impulseScale;  // soft block coefficients of the main sweeps
  JointRow extra[kJointExtraRows];
  float extraMass[kJointExtraRows];   // 1 / (J M^-1 J^T)
  float extraBias[kJointExtraRows];   // main sweeps
  float extraRelaxBias[kJointExtraRows];  // relax sweeps: no position correction
  float extraLo[kJointExtraRows], extraHi[kJointExtraRows];  // impulse bounds (N s)
  float extraImpulse[kJointExtraRows];
  int8_t extraSlot[kJointExtraRows];  // which Joint::extraImpulse entry a row warm-starts from
};

/// Geometric stiffness of the joints at their bodies: for each body, the sum over its joints of their
/// force (Joint::heldForce: the last step's, or more while it falls) times the lever arm (N m). A light
/// link pulled hard along a chain has a rotation mode far faster than the step (a 100 kg load on 1 kg
/// links: ~200 rad/s at 60 Hz) that the linearised joint rows meet only a step late, so it spins up and
/// tears the chain. Adds to `angular` (per body). A rod's or rope's turn is sidewaysStiffness.
void accumulateJointStiffness(const BodyStore& bodies, const Joint& j, float* angular);

/// A taut rod or rope pulled with force f turns its pull as its ends move across it: a sideways
/// stiffness of f / length between its anchors. On short links it is far faster than the step (0.44 m
/// planks on 6 cm rods under 540 N: ~190 rad/s, 3 radians a step at 60 Hz), and met only by the next
/// step's rows it spins up: a sagging plank bridge nudged at 3 m/s tore by a metre. Where that mode is
/// too fast for the step and the joint is in a tree, its block gets two sideways rows, soft, with
/// part of that stiffness treated implicitly (backward Euler), exact in the tree's solve (prepareRows
/// says how much). N/m; 0 for a joint that pushes or carries nothing. (Session 42 added f / length to
/// the mass of beads instead, in all directions: the rows replace it.)
float sidewaysStiffness(const Joint& j, const Vec3& separation);

/// A joint outside the tree is a soft block of its own (solveJointIteration): takes its sideways rows
/// out and inverts its block (blockInvK). JointTree::build does this for the joints it leaves out;
/// without a tree, every joint needs it.
void prepareSoftBlock(JointConstraint& jc);

/// Adds h^2 times a body's geometric stiffness to its world inertia for this step's solve (Andrews et
/// al. 2017, diagonal geometric stiffness): the fast mode is then treated implicitly, damped instead of
/// spun up, and slow motion is left alone. Every row touching the body (joints and contacts) must see
/// the same inertia, or the sweep stops being a projection and pumps energy (crates bounced off a rope
/// bridge); integration restores the true inertia.
void stiffenInertia(BodyStore& bodies, uint32_t body, float stiffness, float dt);

/// A rope (a distance joint with min < max) is taut for this step when its ends' velocities (gravity
/// included) would leave it within kRopeTautSlop of its length or longer at the end of the step. A rope
/// hung at exactly its length is taut from the first step: judged slack there, a plank bridge on ropes
/// fell for one step, jerked and flailed.
/// A taut rope's length is an equality row that may only pull, solved exactly with the joint tree
/// (a chain of ropes carrying a load is then as stiff as a chain of rods); a slack one keeps its limit
/// row. The step's prepare: decides that (Joint::taut), then builds the rows as prepareJoint does,
/// from the same geometry.
void prepareJointForStep(const BodyStore& bodies, Joint& j, uint32_t ji, const SolverParams& p,
                         const JointSolverParams& jp, float time, JointConstraint& jc);
inline constexpr float kRopeTautSlop = 1e-3f;  ///< m

/// Single-row joints (rods, taut ropes) between the same two dynamic bodies (the two ropes at each
/// junction of a rope bridge) are one node of the joint tree: left apart, the second closes a loop, is
/// solved as a soft row beside the tree's exact one, and the two fought until a plank bridge on paired
/// rods tore. Moves the row of each later such joint into the first one's block (up to
/// kJointBlockRows); its limit and motor rows stay its own. Pairs of larger joints (two ball joints or
/// hinges at a plank's edges) share rows that say the same (a redundant block) and stay as they were:
/// merged, a bridge of paired ball joints gained energy under other compiler flags (ThreadSanitizer's
/// build). `order` is scratch (kept between calls).
void mergeParallelJoints(JointConstraint* js, uint32_t n, std::vector<std::pair<uint64_t, uint32_t>>& order);

/// The soft block coefficients of a joint outside a tree: a spring-damper of `hertz` (at most half the
/// step rate) and `dampingRatio`, solved implicitly.
void setSoftness(JointConstraint& jc, float hertz, float dampingRatio, float dt);

/// Builds the rows of joint `j` (index ji) into `jc`; `time` is the simulated time at the end of the
/// step (servo motors aim at their trajectory there).
void prepareJoint(const BodyStore& bodies, const Joint& j, uint32_t ji, const SolverParams& p,
                  const JointSolverParams& jp, float time, JointConstraint& jc);

/// Pseudo-inverse of a symmetric positive semi-definite m x m matrix (row-major) by LDL^T: a row that
/// depends on earlier ones (pivot <= tolerance) is left out instead of blowing up. The rows come from
/// float data, so redundancy shows as pivots of ~1e-7 of the diagonal, not zero.
void invertSymmetric(const double* K, int m, double tolerance, double* inverse);

/// Applies the accumulated (warm-start) impulses to the body velocities.
void warmStartJoints(BodyStore& bodies, const JointConstraint* js, size_t n);

/// One sweep over the joints; returns the largest velocity correction (m/s or rad/s). `useBias`
/// false: the relax sweep after integration (no position correction, motors still drive).
/// `tree` (may be null) solves the blocks of the joints marked inTree exactly, as one block of the sweep.
float solveJointIteration(BodyStore& bodies, JointConstraint* js, size_t n, class JointTree* tree, float omega,
                          bool useBias);

/// Writes accumulated impulses back to the joints and records their force and torque (impulse / dt).
void storeJointImpulses(const JointConstraint* js, size_t n, float dt, float stiffnessHold, Joint* joints);

/// Position-level error of a joint at the bodies' current transforms (docs/metrics.md, "Joint error").
JointError measureJointError(const BodyStore& bodies, const Joint& j);

/// Current relative position of a hinge (angle about the axis, rad) or slider (translation, m).
float jointPosition(const BodyStore& bodies, const JointDef& d);

/// The relative speed (rad/s or m/s) a hinge's or slider's motor drives at in the step ending at
/// simulated time `time`, from the joint's `position` (jointPosition) at its start: the motor's
/// speed, or a servo's trajectory slope plus its position error closed in servoTime.
float motorAim(const JointDef& d, float position, float time, float dt);

}  // namespace haif
