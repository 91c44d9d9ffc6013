// Contacts solved through the joints of their island. Each sweep solves an island's contacts, then
// its joint tree exactly: two blocks of one Gauss-Seidel sweep. Where a contact's push is mostly
// carried away by a joint, that split converges a sliver per sweep: a 5 kg wheel on a hinge under a
// 2000 kg car passes a push on to the car at 5/2005 a sweep, and the wheels sank 13 cm into the ground
// and sprang out, again and again, at 4 sweeps; a chain of 0.5 kg links pulled one 19.5 cm into the
// 100 kg ball it carried, as they wrapped onto it.
//
// The small-island system (contact_chain.h) then takes the joints into its rows: with the tree's
// equality rows J and K = J M⁻¹ Jᵀ, the contacts' virtual rows R see the bodies through the joints,
//   A = R (M⁻¹ − M⁻¹ Jᵀ K⁻¹ J M⁻¹) Rᵀ,
// and every round of the solve starts from velocities the joints hold (the tree solved again), so an
// impulse μ moves the rows by exactly A μ once the joints have taken their share.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact_chain.h"
#include "dynamics/joint_tree.h"
#include "dynamics/motor_mass.h"

#include <Eigen/Core>

namespace haif {

/// The joints a small island's contacts are solved through, and per-body scratch for their response.
struct JointCoupling {
  JointTree* tree = nullptr;       ///< the island's tree, built over all its joints (no loops)
  JointConstraint* joints = nullptr;
  uint32_t jointCount = 0;
  /// Per body of the world, zero outside jointResponse: the velocity the joints give a body for one
  /// row's push (the island's own bodies only, so islands solved at once do not share entries).
  Eigen::Vector3d* dv = nullptr;
  Eigen::Vector3d* dw = nullptr;
  /// Per body of the world, zero outside a sweep's rounds: the velocity the contacts gave a body
  /// since the joints last held it, summed from their impulses in double.
  Eigen::Vector3d* changeV = nullptr;
  Eigen::Vector3d* changeW = nullptr;
  const ContactConstraint* contacts = nullptr;  ///< the island's contacts the system solves
  uint32_t contactCount = 0;
  /// The island's servos and motors solved through its tree (null or count 0: none), read as holding
  /// their axes when judging what the joints carry (jointsCarryContacts).
  const TreeMotors* motors = nullptr;
};

/// Notes the velocity change of contact c's impulses `applied` (per point) on its bodies.
void addContactChange(const JointCoupling& coupling, const ContactConstraint& c, const float* applied);
/// Notes a velocity change of one body (friction rows, solved as usual).
void addBodyChange(const JointCoupling& coupling, uint32_t body, const Vec3& dv, const Vec3& dw);
/// Solves the tree's rows against the change noted since the joints last held the bodies, and clears
/// it: the joints' answer to the contacts' impulses is then the linear one the system was factored
/// for. Solving the tree against the velocities themselves instead reads them in float, and where
/// its rows are nearly redundant (a rope bridge hinged to a post at each end) it magnifies that
/// rounding into an answer unlike the factored one: the rounds never settled, and a bridge's crates
/// were thrown off it at 20 m/s.
void holdJointChange(BodyStore& bodies, const JointCoupling& coupling);

/// The joints' part of a row's response: sets coupling.dv/dw to −M⁻¹ Jᵀ K⁻¹ J M⁻¹ R_rᵀ, the velocity
/// the joints take back from a unit push of link `link`'s virtual row r (contact c). False: the
/// tree's factor does not hold its joints against the push (the answer is not to be used).
bool jointResponse(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint& c,
                   const ChainLink& link, int r);
/// What the island's motors, holding their axes, take back of the motion jointResponse left row r of
/// link `link` (contact c): gᵀ S⁻¹ g (dynamics/motor_mass.h); call before clearJointResponse.
double motorsAtResponse(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint& c,
                        const ChainLink& link, int r);
/// Row q of link `link` (contact c) read at coupling.dv/dw: R_q Δ.
double rowAtResponse(const JointCoupling& coupling, const ContactConstraint& c, const ChainLink& link, int q);
/// Zeroes the scratch jointResponse wrote.
void clearJointResponse(const JointCoupling& coupling);

/// Islands are solved through their joints where a contact moves at most 1/(this × exact_mass_ratio)
/// as much through the joints (jointsCarryContacts): 1/8 by default. At 1/4 a rope bridge's crates
/// (15 kg on 4 kg planks, 1/2-1/8) were taken, and sank 1-2 cm deeper into it than swept (rows that
/// depend on each other through the bridge's joints pulled, and the rounds gave way to the passes);
/// cars of 20 kg wheels under 1000 kg (1/9) and a 100 kg weight on a chain of 0.5 kg links (1/50)
/// are taken.
inline constexpr float kJointCoupledRatioFactor = 2.0f;

/// True when a contact of the island moves along its normal by at most 1/ratio as much for a push
/// through the joints (and the motors, holding their axes) as for the same push on its own bodies,
/// for some link's force row: a sweep then passes the push on to the joints at about 1/ratio a sweep.
/// Or when a contact presses two dynamic bodies whose masses differ by `ratio` or more: a sweep
/// passes a push through the lighter one a fraction of the heavier one's share, joints or not (a
/// ragdoll landing on its own forearm, 1.5 kg under a 20 kg chest, sank 5.9 cm into it at 10
/// sweeps); in an island with motors, a jointed body weighs what the joints and motors make it along
/// the row (a servo's hand on a crate). Either way, only if no contact row is held (almost) still by
/// the joints.
bool jointsCarryContacts(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint* cs,
                         const ChainLink* links, uint32_t n, float ratio);

/// A sweep's motors solved with the island's contacts answering them: after the contacts' rounds
/// settled on `system`'s factor (rows A through the tree), the motors' system through the tree and
/// the contacts, S' = S − Cᵀ A⁺ C (C: the contact rows under each motor's push), so that a servo
/// pressing its hand on a crate on the ground meets the crate's answer within the sweep: solved
/// with S alone it drives the hand on at its speed each sweep and reaches its force bound a few
/// N m s a step. False (nothing applied: solve with solveTreeMotors): no motors, no contacts
/// factored, S' not positive definite, or the contacts' answer would pull on a point (the motors
/// draw the bodies apart; the contacts would let go). `largest` as solveTreeMotors returns it.
bool solveMotorsThroughContacts(BodyStore& bodies, const JointCoupling& coupling, ContactConstraint* cs,
                                const ChainLink* links, const DenseNormalSystem& system, bool useBias, float& largest);

}  // namespace haif
