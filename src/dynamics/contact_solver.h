// SOR projected Gauss-Seidel over contact constraints (docs/solver.md):
//   dλ = -ω (J v + b) / (J M^-1 J^T),  λ <- clamp(λ + dλ, lo, hi),  v += M^-1 J^T dλ_applied.
// Per manifold: one normal row per point, solved together as a small block, and friction at the
// manifold's centre (two tangent rows and one twist row) bounded by μ times the manifold's total
// normal impulse.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace haif {

/// The velocities the sweeps read and write, by the rows' body indices: the bodies' own, or the copy
/// of a split island's in strip order that the World gives them (docs/solver.md, "Giant islands").
struct VelocityView {
  Vec3* v;
  Vec3* w;
  explicit VelocityView(BodyStore& bodies) : v(bodies.v.data()), w(bodies.w.data()) {}
  VelocityView(Vec3* linear, Vec3* angular) : v(linear), w(angular) {}
};

struct SolverParams {
  float dt = 1.0f / 60.0f;
  float omega = 1.0f;                 ///< SOR relaxation factor in [1, 2)
  float beta = 0.2f;                  ///< Baumgarte factor
  float slop = 0.005f;                ///< penetration allowed before correction (m)
  float restitutionThreshold = 1.0f;  ///< approach speed (m/s) below which contacts do not bounce
  bool warmStart = true;
  /// Cap on the Baumgarte push-out speed (m/s). In a tall pile every layer's push adds up: a
  /// 100-layer pyramid compressed at 10 iterations then launched its top at 9 m/s without it.
  float maxPushVelocity = 0.2f;
  /// Friction also pulls back the slow tangential drift of a sticking contact (Contact::anchorA/B),
  /// at anchorBeta / dt, capped at maxPushVelocity. Velocity-level friction alone let a card house
  /// creep apart (0.94 m after 2400 steps at 10 iterations; 7 mm with anchors after 3600).
  /// The World pulls them only where rest damping does not act (no gravity, or rest damping off;
  /// World::solverParams): where it does, it holds that creep itself.
  bool frictionAnchors = true;
  /// The anchors' rate: drift is creep, a slow leak, and wants a gentle pull. At the Baumgarte rate
  /// (0.2) a pile set sliding became a lattice of stiff springs the sweeps did not converge: a
  /// pyramid of 820 boxes given 0.5 m/s on the ground rocked harder step after step and threw boxes
  /// at 12 m/s by step 900 (0.2 m/s: kinetic energy 16 J at the start, 55 J at step 200). At 0.01
  /// it comes to rest (by step 750; 0.2 m/s by 450), and the card house holds as before.
  float anchorBeta = 0.01f;
  /// Drift (m) an anchor leaves alone, as the slop does for penetration: a pile settling by a
  /// fraction of a millimetre is not pulled back (without it a 10-layer pyramid's solve error rose
  /// from 0.05 to 0.66); a creeping card house is (7.7 mm after 3600 steps).
  float anchorSlop = 0.0005f;
  /// Gap (m) below which a pair placed at rest counts as touching (Contact::hovering). A generator
  /// leaves gaps against overlap; closed by the speculative rule, every layer of a tower may close its
  /// own gap in the first step, so the top comes down at the sum of them and lands on a pile still
  /// settling, a cascade 10 sweeps do not converge through crossed layers (a Jenga tower with 0.1 mm
  /// gaps fell at 4 and 10 iterations). Held where it was placed, it stands.
  float skin = 0.001f;
  /// Some body has a rolling resistance (the World sets it): rolling rows are built where a contact
  /// has a lever (Contact::rollingLever). Off, no contact's rolling fields are read or written.
  bool rolling = false;
  /// Friction holds a sticking pair's material points together along their arcs where a body turns,
  /// not only their velocities (arcLag, contact_prepare.cpp): off, what rides a turntable slides out.
  bool followArcs = true;
};

static_assert(kMaxManifoldPoints == 4, "the normal rows of a manifold are one 4-wide vector");

/// Four rows' 3-vectors stored by component (x of the four rows, then y, then z), so a sweep reads
/// one component of a manifold's four normal rows as one SIMD vector. Rows from the manifold's
/// point count on hold zeros, which make their velocities and impulse changes zero.
struct alignas(16) RowVectors {
  float x[kMaxManifoldPoints], y[kMaxManifoldPoints], z[kMaxManifoldPoints];
  Vec3 row(int i) const { return Vec3(x[i], y[i], z[i]); }
  void set(int i, const Vec3& v) {
    x[i] = v.x();
    y[i] = v.y();
    z[i] = v.z();
  }
};

/// Solver rows of one contact, prepared once per step; laid out in solve order.
struct alignas(16) ContactConstraint {
  // One normal row per manifold point, every field stored by row (structure of arrays: the sweep
  // solves the four rows with 4-wide vector operations). Rows from `count` on are zero.
  RowVectors normal;       // world direction of each row (mesh contacts may differ per point)
  RowVectors rAxn, rBxn;   // angular Jacobian parts
  RowVectors iAn, iBn;     // I^-1 times the angular parts
  alignas(16) float normalMass[kMaxManifoldPoints];       // 1 / (J M^-1 J^T)
  // b of the row in a main sweep (velocity, m/s): the speculative gap closing when positive, the
  // push-out when negative. A relax sweep keeps the positive part only (max(b, 0), no push-out).
  alignas(16) float bias[kMaxManifoldPoints];
  alignas(16) float restitutionBias[kMaxManifoldPoints];  // b of a bounce (e times the approach speed), or 0
  alignas(16) float normalImpulse[kMaxManifoldPoints];
  uint32_t a, b;               // body ids
  uint32_t contact;            // index of the Contact it came from
  float invMassA, invMassB;
  bool dynA, dynB;             // only dynamic bodies receive velocity changes
  float friction;
  int count;
  /// Exact solve of the normal block while every point stays loaded: Δλ = G (−J v − b), with
  /// G = B (BᵀKB)⁻¹ Bᵀ. When the points share one normal, each normal row is an affine function of
  /// its point's position in the contact plane, so K has rank ≤ 3 and B = [1, u, w] (u, w: the
  /// in-plane principal coordinates of the points) spans its range: G is K's pseudo-inverse there,
  /// and one product settles the block, torque split included, where passes only approach it.
  /// `blockExact` false: the points have different normals or are degenerate; passes only.
  alignas(16) float blockInverse[kMaxManifoldPoints][kMaxManifoldPoints];
  bool blockExact;
  // Rolling resistance (Contact::rollingLever > 0; docs/solver.md, "Rolling resistance"): one angular
  // row about the axis the pair rolls about, in lane 3 of the friction rows (no linear part; the
  // axis as both angular parts; its impulse in frictionImpulse[3]), solved after the other friction
  // rows and bounded by rollingLever times the normal impulses. rollingMass 0: no such row.
  // These two fill what was padding before the friction rows.
  float rollingMass;   // 1 / (a (I_A⁻¹ + I_B⁻¹) a)
  float rollingLever;  // m: the most torque per unit normal force

  // Friction at the centre of the manifold. Friction per point would make the sliding torque
  // depend on how the load happens to be split among 4 coplanar points (a split the normal rows
  // leave undetermined): a box sliding down a ramp spun about the normal. Three rows, stored by
  // component like the normal rows: tangent 1, tangent 2 and the twist about the mean normal
  // (row 3: the rolling row, or zero).
  RowVectors frictionLinear;                        // t1, t2, 0, 0: the rows' linear part
  RowVectors frictionAngularA, frictionAngularB;    // rA×t1, rA×t2, n, a and rB×t1, rB×t2, n, a
  RowVectors frictionInverseA, frictionInverseB;    // I^-1 times them
  // The sweep reads the next four floats as one vector, and the four after them as another.
  alignas(16) float tangentMass[2][2];  // inverse of the 2x2 block of the tangent rows
  float twistCoupling[2];           // K of each tangent row with the twist row
  float twistMass;                  // 1 / (n (I_A^-1 + I_B^-1) n)
  float twistRadius;                // lever (m) turning the friction limit into a twist limit
  alignas(16) float frictionImpulse[4];  // tangent 1, tangent 2, twist, rolling
  // b of the tangent rows (m/s): lanes 0 and 1 in a main sweep (the anchors' drift pulled back and
  // the points' arcs followed), lanes 2 and 3 in a relax sweep (the arcs alone; contact_prepare.cpp).
  alignas(16) float frictionBias[4];

  Vec3 tangent1() const { return frictionLinear.row(0); }
  Vec3 tangent2() const { return frictionLinear.row(1); }
  Vec3 twistAxis() const { return frictionAngularA.row(2); }
  Vec3 rollingAxis() const { return frictionAngularA.row(3); }

  /// Rows in the order of `delta` and `direction`: the normal rows, then tangent 1, tangent 2, twist.
  static constexpr int kRows = kMaxManifoldPoints + 3;
  /// Impulse change of each row in the last sweep (unused rows stay 0), and the conjugate direction
  /// of the accelerated solve (see accelerate); one slot more than the rows, always 0, so each half
  /// is one 4-wide vector.
  alignas(16) float delta[kRows + 1];
  alignas(16) float direction[kRows + 1];
};
// Every sweep streams the constraints: the rolling row's constants took padding, not new bytes.
static_assert(sizeof(ContactConstraint) == 784, "a constraint's size is a sweep's memory traffic");

/// Passes of projected Gauss-Seidel over a manifold's own normal rows per sweep, when the exact
/// block solve (blockInverse) does not apply or would pull on a point. Row by row with body updates
/// in between, a manifold's 4 coplanar points end each sweep with an arbitrary split of the load,
/// and the torque error rocks tall stacks apart (a 10-box stack fell at 10 iterations); solving the
/// small 4x4 problem to near convergence inside each sweep holds it still.
constexpr int kManifoldNormalPasses = 4;

/// Those passes, written once for the scalar sweep and the wide one (which runs them lane by lane
/// where the exact block would pull): row i of m steps λ_i to max(0, λ_i − ω mass_i (v_i + bias_i)),
/// and every row's velocity v_j follows through the coupling K(i, j); a pass that changes nothing
/// ends them (separated contacts: at once). One row needs one step and no coupling.
template <class Coupling>
[[gnu::always_inline]] inline void projectedNormalPasses(int m, float* v, const float* bias, const float* mass,
                                                         float* lambda, float omega, const Coupling& K) {
  if (m == 1) {
    lambda[0] = std::max(0.0f, lambda[0] - omega * mass[0] * (v[0] + bias[0]));
    return;
  }
  for (int pass = 0; pass < kManifoldNormalPasses; ++pass) {
    bool moved = false;
    for (int i = 0; i < m; ++i) {
      const float old = lambda[i];
      lambda[i] = std::max(0.0f, old - omega * mass[i] * (v[i] + bias[i]));
      const float d = lambda[i] - old;
      if (d == 0.0f) continue;
      moved = true;
      for (int j = 0; j < m; ++j) v[j] += K(i, j) * d;
    }
    if (!moved) break;
  }
}

/// Solver rows one manifold of `points` points costs per sweep: its normal rows and 3 friction rows.
constexpr uint32_t solverRowsFor(int points) { return points > 0 ? uint32_t(points) + 3u : 0u; }

/// Builds the rows of `contact` (index ci) into `cc` from the current body state, with the manifold's
/// points moved by `shift` (see reaimForRelax).
void prepareContact(const BodyStore& bodies, const Contact& contact, uint32_t ci, const SolverParams& p,
                    ContactConstraint& cc, const Vec3& shift = Vec3::Zero());

/// After the positions moved, a relax sweep applied each impulse to each body at the lever arm it had
/// before: to A at its old point carried along with A, to B at its old point carried along with B,
/// two points (vA − vB) dt apart, so every impulse between two bodies that moved against each other
/// turned the pair's angular momentum (2 % through a glancing collision at 5 m/s). For such pairs
/// (both dynamic, closing or parting by more than 1 mm a step) the rows are built again about one
/// point, the old one moved by the mean of the two bodies' moves; impulses and biases are kept.
/// Pairs being pushed apart (a point beyond the slop) are left as they are.
/// `linear` holds the linear velocities cc's body indices name (the bodies' own, or a split island's
/// copy, which must then be current); the rows are built again from `bodies` by the contact's body
/// ids. Returns true when it built them (cc's indices are then body ids).
bool reaimForRelax(const BodyStore& bodies, const Vec3* linear, const Contact& contact, const SolverParams& p,
                   ContactConstraint& cc);
/// Whether reaimForRelax would build cc's rows again (it reads no impulse, so a packed copy's rows
/// need not be unpacked to ask).
bool wantsReaim(const Vec3* linear, const SolverParams& p, const ContactConstraint& cc);

/// Applies the accumulated (warm-start) impulses of the constraints to the body velocities.
void warmStart(VelocityView bodies, const ContactConstraint* cs, size_t n);
inline void warmStart(BodyStore& bodies, const ContactConstraint* cs, size_t n) {
  warmStart(VelocityView(bodies), cs, n);
}

/// Inverse of a symmetric positive definite 3x3 block by cofactors. False when a diagonal entry is
/// not positive or the determinant is below minDetRatio times the diagonal's product: a direction
/// the bodies cannot respond in (nearly singular). In line, with one division: called out of line
/// from prepareContact it spilled every vector prepare holds, 5 % of prepare's time.
inline bool invertSymmetric3(const double a[3][3], double out[3][3], double minDetRatio) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  if (!(a[0][0] > 0.0 && a[1][1] > 0.0 && a[2][2] > 0.0 && det > minDetRatio * a[0][0] * a[1][1] * a[2][2]))
    return false;
  const double k = 1.0 / det;
  out[0][0] = c00 * k;
  out[1][0] = out[0][1] = c01 * k;
  out[2][0] = out[0][2] = c02 * k;
  out[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * k;
  out[2][1] = out[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * k;
  out[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * k;
  return true;
}

/// The points' in-plane coordinates (s, t) along t1 and t2 from `centre` (zero past the count).
void planarCoords(const Manifold& mf, const Vec3& centre, const Vec3& t1, const Vec3& t2,
                  double coords[kMaxManifoldPoints][2]);
/// The least spread of a manifold's points (m²: the sum of their squared distances from their centre)
/// at which they are more than one place to a normal block solved exactly: this fraction of the
/// largest lever (|r×n|², of a body that moves) among its points. The block's inverse reads how the
/// coupling K varies across the points, by ~|I⁻¹| spread; float keeps K to 1e-7 of |I⁻¹| lever², so
/// a sliver 0.33 mm across on 1 m bricks read rounding, and its inverse threw a whole resting bed of
/// bricks at 24 m/s in one step. Below it the points are solved by passes (and as one row by a chain).
constexpr double kSinglePlaceFraction = 1e-4;
constexpr double kSinglePlaceFloor = 1e-12;  // m², however short the levers
/// Points whose spread across their major axis is below this fraction (of the square of the whole
/// spread, as minor × major) are a line: a width under ~1 % of the length.
constexpr double kLineWidthRatio = 1e-4;
inline double singlePlaceSpread(const ContactConstraint& c) {
  float lever2 = 0.0f;
  for (int i = 0; i < c.count; ++i) {
    if (c.dynA) lever2 = std::max(lever2, c.rAxn.row(i).squaredNorm());
    if (c.dynB) lever2 = std::max(lever2, c.rBxn.row(i).squaredNorm());
  }
  return std::max(kSinglePlaceFloor, kSinglePlaceFraction * double(lever2));
}

/// How many independent ways a manifold's points can share its load (1 + the directions of the contact
/// plane they span), from their spread about their mean: css = Σs², ctt = Σt², cst = Σst (m²) over
/// `count` points. The spread is read per principal direction, each against `single`
/// (singlePlaceSpread): a patch 6 mm long and 0.1 mm wide is a line, as a point 0.3 mm across is one
/// place, since float cannot read the coupling's variation across it either (its block turned about
/// the line's own axis with a gain of 1e7 over a row's mass). A width under 1 % of the length is a
/// line too. For a line, `along` gets its direction (s, t components; unset otherwise).
int spreadRank(double css, double ctt, double cst, int count, double single, double along[2]);

/// In-plane basis of the points in `mask` (bit i: point i) of `count` points at `coords`, for a
/// normal block: B[i] = [1, s_i, t_i] (rows of the other points are zero). Returns the rank k it
/// spans (spreadRank: 3 for a patch, 2 for a line, 1 for a single place); for a line B[i][1] is the
/// coordinate along it. Columns from k on are zero.
int pointBasis(const double coords[kMaxManifoldPoints][2], int count, unsigned mask, double single,
               double B[kMaxManifoldPoints][3]);

/// J v of normal row i: the bodies' relative velocity along its normal at its point (< 0: approaching).
inline float rowVelocity(const ContactConstraint& c, int i, const Vec3& va, const Vec3& wa, const Vec3& vb,
                         const Vec3& wb) {
  return c.normal.row(i).dot(vb - va) + c.rBxn.row(i).dot(wb) - c.rAxn.row(i).dot(wa);
}

/// b of a normal row in a relax sweep, written once for every width (float, F4, F8): where the row
/// pushes, its bounce (a turning kinematic surface's lead is folded into it); elsewhere only a
/// speculative gap's allowance, no push-out. A main sweep uses the row's bias as it is.
// Always inlined, never part of an interface: GCC's note that an 8-lane vector passed by value has
// another ABI in builds without AVX does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
template <class V>
[[gnu::always_inline]] inline V relaxBias(V bias, V bounce, V impulse) {
  return ((bounce < 0.0f) & (impulse > 0.0f)) ? bounce : (bias > 0.0f ? bias : V{});
}

/// The friction circle, for every width (float, F8): the factor that brings tangent impulses of
/// squared length `len2` back onto the circle of radius `limit` (μ Σλn), 1 where they lie inside.
/// Clamping each tangent axis alone (a box) would let friction reach √2 μ λn along a diagonal.
/// `root` is the square root of that width.
template <class V, class Root>
[[gnu::always_inline]] inline V frictionCircleScale(V len2, V limit, Root root) {
  return len2 > limit * limit ? limit / root(len2) : V{} + 1.0f;
}

/// A twist impulse held to [−maxTwist, maxTwist] (maxTwist = μ Σλn times the manifold's twist lever),
/// for every width (F4 lanes, F8), in the sweeps and in the accelerated step.
template <class V>
[[gnu::always_inline]] inline V clampTwist(V x, V maxTwist) {
  return x > maxTwist ? maxTwist : (x < -maxTwist ? -maxTwist : x);
}
#pragma GCC diagnostic pop

/// b of a normal row: with position correction in a main sweep (`useBias`), else relaxBias.
inline float rowBias(const ContactConstraint& c, int i, bool useBias) {
  return useBias ? c.bias[i] : relaxBias(c.bias[i], c.restitutionBias[i], c.normalImpulse[i]);
}

/// Coupling of the normal rows: K[i][j] = J_i M^-1 J_j^T (rows and columns past the count are zero).
/// The normal rows of a manifold are solved together against it. It is computed from the rows when
/// needed rather than stored: only the projected passes use it, which a manifold of a resting pile
/// seldom runs, and its 64 bytes made every sweep over a giant island stream more memory.
void normalCoupling(const ContactConstraint& c, float K[kMaxManifoldPoints][kMaxManifoldPoints]);

/// Writes a manifold's body velocities back after solving its rows. Static and kinematic bodies are
/// read (their velocity is given) but never written, so islands that share one solve concurrently.
inline void storeVelocities(BodyStore& bodies, const ContactConstraint& c, const Vec3& va, const Vec3& wa,
                            const Vec3& vb, const Vec3& wb) {
  if (c.dynA) {
    bodies.v[c.a] = va;
    bodies.w[c.a] = wa;
  }
  if (c.dynB) {
    bodies.v[c.b] = vb;
    bodies.w[c.b] = wb;
  }
}

// The parts of a sweep over one manifold, on its bodies' velocities (va, wa, vb, wb) held by the caller:
/// Twist and tangent rows, bounded by the normal impulses of the previous sweep.
void solveFrictionRows(ContactConstraint& c, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb, float omega, bool useBias);
/// The normal block (exact, or projected passes); returns the largest velocity correction of a row.
float solveNormalRows(ContactConstraint& c, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb, float omega, bool useBias);
/// Applies normal impulse changes `applied` (already added to the points' impulses) to the
/// velocities and records them in c.delta; returns the largest velocity correction of a row.
float applyNormalChange(ContactConstraint& c, const float* applied, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb);
/// Σ of the squared impulse changes of c's rows in its last sweep.
double squaredChange(const ContactConstraint& c);

/// What one sweep did.
struct SweepResult {
  float residual = 0.0f;  ///< largest velocity correction of a normal row (m/s): what early stopping tests
  double change = 0.0;    ///< Σ over the rows of (impulse change)²: what the accelerated solve steps by
  void merge(const SweepResult& o) {
    residual = residual > o.residual ? residual : o.residual;
    change += o.change;
  }
};

/// One PGS sweep over the constraints. `useBias` false: the relax sweep, run after positions were
/// integrated, which removes the position-correction velocity. `restartDirection`: each constraint's
/// direction first takes its last sweep's change, as startDirection would, while the constraint is
/// in cache for the sweep anyway (a pass of its own cost a serial 0.85 ms of large_pyramid's 2-thread step).
/// `measureChange` false: SweepResult::change is left 0 (only the momentum step reads it).
/// `rolling`: some constraint may have a rolling row (SolverParams::rolling); false, they are not looked for.
SweepResult solveIteration(VelocityView bodies, ContactConstraint* cs, size_t n, float omega, bool useBias,
                           bool restartDirection = false, bool measureChange = true, bool rolling = false);
inline SweepResult solveIteration(BodyStore& bodies, ContactConstraint* cs, size_t n, float omega, bool useBias,
                                  bool restartDirection = false, bool measureChange = true, bool rolling = false) {
  return solveIteration(VelocityView(bodies), cs, n, omega, useBias, restartDirection, measureChange, rolling);
}

/// solveIteration over two ranges that share no dynamic body (two strips of a split island swept in
/// the same phase), a constraint of each in turn, with each range's own result in r1 and r2: the
/// same bits as two calls, but the two chains of velocity updates overlap in the processor (a thin
/// strip's neighbours mostly share a body, and each waits for the last).
void solveIterationPair(VelocityView bodies, ContactConstraint* cs1, size_t n1, ContactConstraint* cs2, size_t n2,
                        float omega, bool useBias, bool restartDirection, bool measureChange, bool rolling,
                        SweepResult& r1, SweepResult& r2);

/// Nonsmooth nonlinear conjugate gradient on top of the sweeps (after Silcowitz, Niebe and Erleben
/// 2010). A sweep's impulse change is the negative gradient of the projected problem; momentum
/// along the previous direction, scaled by β = |Δ_k|² / |Δ_{k-1}|², carries the low-frequency part
/// of the solution (the weight of a tall stack) much faster than sweeps alone. `startDirection`
/// begins a direction (first sweep, or a restart when β > 1); `accelerate` steps the impulses
/// along β times the direction, projected onto their bounds, and updates the direction.
void startDirection(ContactConstraint* cs, size_t n);
void accelerate(VelocityView bodies, ContactConstraint* cs, size_t n, float beta);
inline void accelerate(BodyStore& bodies, ContactConstraint* cs, size_t n, float beta) {
  accelerate(VelocityView(bodies), cs, n, beta);
}

/// Writes the accumulated impulses back to the persistent contacts for the next step's warm start.
void storeImpulses(const ContactConstraint* cs, size_t n, Contact* contacts);

}  // namespace haif
