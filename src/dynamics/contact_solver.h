// SOR projected Gauss-Seidel over contact constraints (DESIGN.md §2):
//   dλ = -ω (J v + b) / (J M^-1 J^T),  λ <- clamp(λ + dλ, lo, hi),  v += M^-1 J^T dλ_applied.
// One normal row and two friction rows per contact point; friction bounded by μ·λ_normal.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"

#include <cstdint>
#include <vector>

namespace haif {

struct SolverParams {
  float dt = 1.0f / 60.0f;
  float omega = 1.0f;                 ///< SOR relaxation factor in [1, 2)
  float beta = 0.2f;                  ///< Baumgarte factor
  float slop = 0.005f;                ///< penetration allowed before correction (m)
  float restitutionThreshold = 1.0f;  ///< approach speed (m/s) below which contacts do not bounce
  bool warmStart = true;
};

/// Solver rows of one contact, prepared once per step; laid out in solve order.
struct ContactConstraint {
  struct Point {
    Vec3 normal, tangent1, tangent2;               // world directions of the three rows
    Vec3 rAxn, rBxn, rAxt1, rBxt1, rAxt2, rBxt2;   // angular Jacobian parts
    Vec3 iAn, iBn, iAt1, iBt1, iAt2, iBt2;         // I^-1 times the angular parts
    float normalMass, tangentMass1, tangentMass2;  // 1 / (J M^-1 J^T) per row
    float bias;                                    // b of the normal row (velocity, m/s)
    float relaxBias;                               // b without position correction (relax pass)
    float restitutionBias;                         // b of a bounce (e times the approach speed), or 0
    float normalImpulse, tangentImpulse1, tangentImpulse2;
  };
  uint32_t a, b;               // body ids
  uint32_t contact;            // index of the Contact it came from
  float invMassA, invMassB;
  bool dynA, dynB;             // only dynamic bodies receive velocity changes
  float friction;
  int count;
  Point points[kMaxManifoldPoints];
};

/// Builds the rows of `contact` (index ci) into `cc` from the current body state.
void prepareContact(const BodyStore& bodies, const Contact& contact, uint32_t ci, const SolverParams& p,
                    ContactConstraint& cc);

/// Applies the accumulated (warm-start) impulses of the constraints to the body velocities.
void warmStart(BodyStore& bodies, const ContactConstraint* cs, size_t n);

/// One PGS sweep over the constraints; returns the largest velocity correction made (m/s),
/// the residual that early stopping compares against a tolerance. `useBias` false: the relax
/// sweep, run after positions were integrated, which removes the position-correction velocity.
float solveIteration(BodyStore& bodies, ContactConstraint* cs, size_t n, float omega, bool useBias);

/// Writes the accumulated impulses back to the persistent contacts for the next step's warm start.
void storeImpulses(const ContactConstraint* cs, size_t n, Contact* contacts);

}  // namespace haif
