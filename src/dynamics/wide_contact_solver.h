// The contact sweep run kLanes manifolds at a time (SIMD across manifolds).
//
// A lane batch (haif/lane_batches.h) holds up to kLanes constraints that share no dynamic body, so
// solving them together is the same as solving them one after another. Their rows are copied once
// per step, after prepareContact, into lane-major form (every field an 8-float vector, one lane per
// manifold), and the sweep, the momentum step and the direction update then run on those vectors:
// the arithmetic of solveIteration, with each operation done for 8 manifolds at once. Bodies are
// gathered and scattered by index. Lanes whose exact normal block would pull (a landing, a lifting
// corner), or whose manifold has no exact block, run the projected passes lane by lane.
//
// The vectors are GCC vector extensions: one AVX register with -march=x86-64-v3, two SSE registers
// with the portable build, scalar code elsewhere. Results equal the scalar sweep's to rounding
// (operations are grouped the same way; fused multiply-adds may be placed differently).
#pragma once

#include "core/body_store.h"
#include "dynamics/contact_solver.h"

#include <cstdint>

namespace haif {

/// Constraints one wide sweep solves at once (8 floats: one AVX2 register).
constexpr int kLanes = 8;

namespace wide {
using F8 = float __attribute__((vector_size(kLanes * sizeof(float))));
using I8 = int32_t __attribute__((vector_size(kLanes * sizeof(int32_t))));
struct V3 {
  F8 x, y, z;
};
}  // namespace wide

/// The rows of up to kLanes constraints, lane l holding constraint l of the batch. Unused lanes and
/// points hold zeros, which make every row change zero.
struct alignas(32) WideContactBatch {
  using F8 = wide::F8;
  using V3 = wide::V3;
  int lanes = 0;                 ///< constraints in the batch
  unsigned active = 0;           ///< bit l: lane l has points (an empty manifold is skipped, as in a sweep)
  uint32_t a[kLanes], b[kLanes];
  unsigned dynA = 0, dynB = 0;   ///< bit l: that body of lane l is written
  int count[kLanes];             ///< points per lane
  F8 invMassA, invMassB, friction;
  // Normal rows, per point.
  V3 normal[kMaxManifoldPoints], rAxn[kMaxManifoldPoints], rBxn[kMaxManifoldPoints];
  V3 iAn[kMaxManifoldPoints], iBn[kMaxManifoldPoints];
  F8 normalMass[kMaxManifoldPoints], bias[kMaxManifoldPoints];
  F8 restitutionBias[kMaxManifoldPoints], normalImpulse[kMaxManifoldPoints];
  F8 coupling[kMaxManifoldPoints][kMaxManifoldPoints];
  F8 blockInverse[kMaxManifoldPoints][kMaxManifoldPoints];
  wide::I8 blockExact;           ///< -1 where the exact block applies (ContactConstraint::blockExact, 2+ points)
  // Friction rows at the manifold centre.
  V3 tangent1, tangent2, twistAxis, rAxt1, rBxt1, rAxt2, rBxt2, iAt1, iBt1, iAt2, iBt2, iAtw, iBtw;
  F8 tangentMass00, tangentMass01, tangentMass10, tangentMass11, twistMass, twistRadius;
  F8 tangentImpulse1, tangentImpulse2, twistImpulse;
  F8 tangentBias1, tangentBias2;  // ContactConstraint::frictionBias, main sweeps (lanes 0, 1)
  F8 tangentLead1, tangentLead2;  // ContactConstraint::frictionBias, relax sweeps (lanes 2, 3)
  F8 delta[ContactConstraint::kRows], direction[ContactConstraint::kRows];
};

/// Copies the prepared (and warm started) rows of cs[0, lanes) into w.
void packWide(const ContactConstraint* cs, int lanes, WideContactBatch& w);
/// Copies the accumulated impulses of w back to cs[0, w.lanes), for storeImpulses.
void unpackWideImpulses(const WideContactBatch& w, ContactConstraint* cs);

/// One sweep over the batch's constraints: what solveIteration does for each of them.
SweepResult solveWide(BodyStore& bodies, WideContactBatch& w, float omega, bool useBias);
/// startDirection and accelerate for the batch's constraints.
void startDirectionWide(WideContactBatch& w);
void accelerateWide(BodyStore& bodies, WideContactBatch& w, float beta);

/// A range of constraints in lane batches: run[j] is the length of the batch starting at slot j (0
/// inside a batch), wideOf[j] the index in `wide` of its packed rows, or -1 when it is solved by
/// the scalar code.
struct LaneBatches {
  const uint8_t* run;
  const int32_t* wideOf;
  WideContactBatch* wide;
  /// The same batches seen from slot `first` on (a strip of the range).
  LaneBatches from(size_t first) const { return {run + first, wideOf + first, wide}; }
};

/// Packs the range's wide batches (after prepare and warm start).
void packLanes(const ContactConstraint* cs, size_t n, const LaneBatches& lb);
/// solveIteration, startDirection, accelerate and the impulse copy-back over such a range.
SweepResult solveIterationLanes(BodyStore& bodies, ContactConstraint* cs, size_t n, const LaneBatches& lb,
                                float omega, bool useBias);
void startDirectionLanes(ContactConstraint* cs, size_t n, const LaneBatches& lb);
void accelerateLanes(BodyStore& bodies, ContactConstraint* cs, size_t n, const LaneBatches& lb, float beta);
void unpackLanes(ContactConstraint* cs, size_t n, const LaneBatches& lb);
/// reaimForRelax over such a range (`contacts` indexed by each row's contact): a batch with a row to
/// re-aim has its impulses taken out, its rows built again and the batch packed again.
void reaimLanesForRelax(const BodyStore& bodies, const Contact* contacts, const SolverParams& p,
                        ContactConstraint* cs, size_t n, const LaneBatches& lb);

}  // namespace haif
