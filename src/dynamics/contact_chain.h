// Exact solve of the normal rows of a chain of contacts: a stack, where each body rests on one body
// and carries one. Sweeps share a landing's momentum only between the two bodies of a contact, so
// the velocity left in a stack halves per sweep instead of vanishing: at 5 sweeps a stacks_2000
// landing cascade still carried 78 J ten steps in. Over a chain the normal problem is block
// tridiagonal and solves directly in one pass.
//
// Each manifold's normal rows are reduced to its rank-k basis (ContactConstraint::blockInverse): the
// impulses Δλ = B μ, with μ ∈ R^k (a force and two torques for a face contact). Link j's virtual rows
// R_j = Bᵀ J_j couple only with the links that share one of its bodies, j − 1 and j + 1, so
//   R_j M⁻¹ Σ_l R_lᵀ μ_l = −Bᵀ (J_j v + b_j)
// is block tridiagonal with k × k blocks, factored by block Gaussian elimination down the chain.
// The links solved are those that touch or still push; one that pushes while it separates is let
// go only when the solution pulls on it. The result is kept when every point of every link still
// pushes (λ ≥ 0), the way a single manifold's exact block is kept. A link whose total comes out
// pulling is let go (λ = 0) and the rest solved again; links the result makes touch join and the
// chain is solved again from there (a landing reaching down a resting stack). A link with a lifting
// corner (a tilt) lets go of the points that pull and is solved on the basis of the others (an edge
// spans rank 2, a corner rank 1). If the rounds do not settle, the sweep solves the normal rows
// manifold by manifold as usual. Friction rows are swept as usual before the chain solve.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"
#include "dynamics/contact_solver.h"

#include <cstdint>

namespace haif {

/// Per constraint of a chain: its virtual rows and its part of the factorisation.
struct ChainLink {
  int rank;                                 ///< virtual rows used (1..3); rows from rank on are zero
  unsigned points;                          ///< bit i: point i is in the basis (a lifted one is not)
  double coords[kMaxManifoldPoints][2];     ///< the points' in-plane coordinates, for rebuilding B
  float basis[kMaxManifoldPoints][3];       ///< B: weight of point i in virtual row r
  float lin[3];                             ///< Σ_i B[i][r]: the row's force along the normal
  Vec3 angA[3], angB[3];                    ///< Σ_i B[i][r] (r × n) on body A, body B
  Vec3 invAngA[3], invAngB[3];              ///< I⁻¹ times them
  double diag[3][3];                        ///< R_j M⁻¹ R_jᵀ
  double next[3][3];                        ///< R_j M⁻¹ R_{j+1}ᵀ through the body they share (0: none)
  int8_t sideToNext, sideFromPrev;          ///< the shared body: 1 body B, 0 body A of this link; -1 none
  bool coupledToNext() const { return sideToNext >= 0; }
  // Per sweep.
  bool active;                              ///< takes part in the solve
  bool factoredActive;                      ///< `active` when the factors below were made
  bool letGo;                               ///< let go of (pulling) in this sweep
  uint8_t releases;                         ///< times it was let go of in this sweep
  double pivotInverse[3][3];                ///< inverse of the eliminated diagonal block
  double lower[3][3];                       ///< nextᵀ of the previous link times its pivotInverse
  // The factors in float for the substitutions, which run every round of every sweep; they are
  // made in double, where the elimination's cancellations happen.
  float nextF[3][3], pivotInverseF[3][3], lowerF[3][3];
  float rhs[3], mu[3];
  float slack;                              ///< how far below 0 an impulse of this round counts as 0
};

/// Builds the chain of island contacts `cs[0, n)` (in solve order) into `links` when they form one:
/// consecutive constraints share at most one dynamic body and no dynamic body is in two constraints
/// that are not consecutive, and every manifold's normal rows have one normal. `mark` is per-body
/// scratch of the world's body count. False: not a chain, sweep as usual.
bool prepareChain(const Contact* contacts, const ContactConstraint* cs, uint32_t n,
                  uint32_t* mark, ChainLink* links);

/// The factor of a small island's normal rows (prepareSmallIsland): dense, at most kMaxRows rows. A
/// pivoted LDLᵀ that stops at the system's rank, and its null space, for the least-squares solution of
/// smallest norm (contact_chain.cpp). Its matrices live in storage the caller attaches, sized to the
/// island (a pool the World reuses), so that factoring allocates nothing and a pour of small islands
/// does not hold 3 × 72² doubles for each.
struct DenseNormalSystem {
  /// kMaxLinks contacts at most; islands of more than kCheapLinks need a larger mass ratio
  /// (World::wantsSmallIslandSolve): the factor's cost grows as the cube of its rows.
  static constexpr int kMaxLinks = 64, kCheapLinks = 32, kCheapRows = 72, kMaxRows = 192;
  /// How much larger: at this ratio a sweep passes under 4 % of a landing through a light body.
  static constexpr float kLargeIslandRatioFactor = 6.0f;
  /// Doubles of storage a system of up to `rows` rows needs.
  static size_t doublesFor(int rows) { return 3 * size_t(rows) * size_t(rows); }
  /// Uses `storage` (doublesFor(rowsHeld) doubles) for systems of up to rowsHeld rows.
  void attach(double* storage, int rowsHeld) {
    startSolve();
    stride = rowsHeld;
    factor = storage;
    nullBasis = factor + size_t(rowsHeld) * size_t(rowsHeld);
    nullGram = nullBasis + size_t(rowsHeld) * size_t(rowsHeld);
  }
  /// Forgets what a solve of the step kept (World::solveIslands, each time: the solve-error probe
  /// solves the step three times, and each must start where the first did).
  void startSolve() {
    rows = rank = 0;  // nothing factored: a system whose links are all let go substitutes nothing
    unsettledSweeps = factors = 0;
    jointsHeld = heldWithBias = jointsUnsound = false;
  }
  int stride = 0;                         ///< rows the attached storage holds (row length of each matrix)
  double* factor = nullptr;               ///< in pivot order: L below the diagonal, D on it
  double* nullBasis = nullptr;            ///< Tᵗ ((rows − rank) × rank): the null space is [T; I]
  double* nullGram = nullptr;             ///< Cholesky factor of I + TᵀT
  int rows = 0;                           ///< of the active links
  int rank = 0;                           ///< independent rows: the first `rank` in pivot order
  int rowOf[kMaxLinks];                   ///< first row of each active link, -1 for the others
  int order[kMaxRows];                    ///< pivot order: order[k] is the row eliminated k-th
  uint8_t linkOf[kMaxRows], partOf[kMaxRows];  ///< the link and virtual row of each row
  float asks[kMaxLinks];                  ///< per active link: its lowest point bias (pivot priority)
  double x[kMaxRows], c[kMaxRows];        ///< substitution scratch
  /// Solved through joints: the tree has held the bodies this step, in main (true) or relax sweeps.
  bool jointsHeld = false, heldWithBias = false;
  /// Solved through joints: the tree's answer to a row did not hold its joints (jointResponse).
  bool jointsUnsound = false;
  /// Sweeps of this step whose rounds did not settle (each factored the system up to kChainRounds
  /// times and then fell back on the manifolds' passes).
  int unsettledSweeps = 0;
  /// Factorisations made this step (the system's work, the cube of its rows each).
  int factors = 0;
};

/// The least-norm solution of the system as last factored: `b` per row (rows numbered as
/// system.linkOf / partOf number them), `x` in pivot order (row system.order[k] is x[k]); `scratch`
/// holds rows − rank doubles. The rounds' substitution, and the motors' reading of the contacts
/// (dynamics/joint_coupling.h).
void solveFactored(const DenseNormalSystem& system, const double* b, double* x, double* scratch);

/// Builds the links of an island's contacts `cs[0, n)` for the dense solve: at least `minLinks` and
/// at most DenseNormalSystem::kMaxLinks contacts of one normal each, no pinched body, at most
/// `rowsHeld` (≤ kMaxRows) virtual rows. False: sweep as usual.
bool prepareSmallIsland(const Contact* contacts, const ContactConstraint* cs, uint32_t n, ChainLink* links,
                        int rowsHeld = DenseNormalSystem::kMaxRows, uint32_t minLinks = 2);

struct JointCoupling;

/// One sweep of a small island: as solveChainIteration, with the normal rows of all its links
/// solved together through `system` (any links sharing a body couple). With `joints`, the rows are
/// solved through the island's joint tree (dynamics/joint_coupling.h).
SweepResult solveSmallIslandIteration(BodyStore& bodies, ContactConstraint* cs, ChainLink* links, uint32_t n,
                                      float omega, bool useBias, DenseNormalSystem& system,
                                      const JointCoupling* joints = nullptr);

/// One sweep of a chain: friction rows contact by contact, then the normal rows of the whole chain
/// solved exactly (see above). Same result fields as solveIteration.
SweepResult solveChainIteration(BodyStore& bodies, ContactConstraint* cs, ChainLink* links, uint32_t n, float omega,
                                bool useBias);

}  // namespace haif
