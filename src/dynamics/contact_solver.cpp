// The sweeps over each manifold's rows (friction, then the normal block), the momentum step between
// them, and the warm start and impulse store at either end of a step. The rows are built in
// contact_prepare.cpp.
#include "dynamics/contact_solver.h"

#include "core/simd4.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

namespace haif {

using simd4::F4;
using simd4::load;
using simd4::store;

// Here, beside the sweep: its projected passes call it (prepareBlockInverse also, once a step).
void normalCoupling(const ContactConstraint& c, float K[kMaxManifoldPoints][kMaxManifoldPoints]) {
  const float mSum = c.invMassA + c.invMassB;
  const F4 nx = load(c.normal.x), ny = load(c.normal.y), nz = load(c.normal.z);
  const F4 iAnX = load(c.iAn.x), iAnY = load(c.iAn.y), iAnZ = load(c.iAn.z);
  const F4 iBnX = load(c.iBn.x), iBnY = load(c.iBn.y), iBnZ = load(c.iBn.z);
  F4 row[kMaxManifoldPoints];
  for (int i = 0; i < kMaxManifoldPoints; ++i)
    row[i] = mSum * (c.normal.x[i] * nx + c.normal.y[i] * ny + c.normal.z[i] * nz) +
             (c.rAxn.x[i] * iAnX + c.rAxn.y[i] * iAnY + c.rAxn.z[i] * iAnZ) +
             (c.rBxn.x[i] * iBnX + c.rBxn.y[i] * iBnY + c.rBxn.z[i] * iBnZ);
  // Exactly symmetric (the solver reads rows as columns): below the diagonal, row j takes column j
  // of the rows above it. Built in registers: rows patched by scalar stores and read back whole
  // stalled prepare (a sixth of its time in many_pyramids).
  F4 col[kMaxManifoldPoints];
  simd4::transpose(row[0], row[1], row[2], row[3], col[0], col[1], col[2], col[3]);
  for (int j = 0; j < kMaxManifoldPoints; ++j) store(K[j], simd4::I4{0, 1, 2, 3} < j ? col[j] : row[j]);
}

namespace {

// A body velocity as one vector (x, y, z, 0) while a manifold's rows are solved.
inline F4 load3(const Vec3& v) { return F4{v.x(), v.y(), v.z(), 0.0f}; }
inline void store3(Vec3& out, F4 v) { out = Vec3(v[0], v[1], v[2]); }

// Friction impulses are vectors (tangent 1, tangent 2, twist, 0), and the helpers below keep them
// in vectors: GCC assembles a vector from scalars through memory.

// Scales the tangent impulses (lanes 0 and 1) back onto the circle of radius `limit` when they lie
// outside it (the other lanes scale too; callers take only lanes 0 and 1).
inline F4 ontoFrictionCircle(F4 f, float limit) {
  const F4 sq = f * f;
  const float len2 = simd4::lane<0>(sq) + simd4::lane<1>(sq);
  if (!(len2 > limit * limit)) return f;
  return f * frictionCircleScale(len2, limit, [](float x) { return std::sqrt(x); });
}

// Lanes 0 and 1 of the tangent impulses, lane 2 of the twist impulses and lane 3 (the rolling row,
// solved on its own: rollingRow) of `rolling`.
inline F4 joinFriction(F4 tangent, F4 twist, F4 rolling) {
  return __builtin_shuffle(__builtin_shuffle(tangent, twist, simd4::I4{0, 1, 6, 7}), rolling, simd4::I4{0, 1, 2, 7});
}


// What impulses `a` on four rows apply: Σ a_i lin_i (linear) and Σ a_i (I⁻¹ J_ang)_i for each
// body, each as a vector (x, y, z, 0). Zero rows add nothing.
struct RowImpulses {
  F4 linear, angularA, angularB;
};

inline RowImpulses rowImpulses(const RowVectors& lin, const RowVectors& invA, const RowVectors& invB, F4 a) {
  const F4 zero{};
  return {simd4::laneSums(a * load(lin.x), a * load(lin.y), a * load(lin.z), zero),
          simd4::laneSums(a * load(invA.x), a * load(invA.y), a * load(invA.z), zero),
          simd4::laneSums(a * load(invB.x), a * load(invB.y), a * load(invB.z), zero)};
}

inline RowImpulses normalImpulses(const ContactConstraint& c, F4 a) { return rowImpulses(c.normal, c.iAn, c.iBn, a); }

inline RowImpulses frictionImpulses(const ContactConstraint& c, F4 a) {
  return rowImpulses(c.frictionLinear, c.frictionInverseA, c.frictionInverseB, a);
}

// Applies impulse changes of a constraint's normal rows (dn) and friction rows (df) to its bodies'
// stored velocities (the warm start and the momentum step; a sweep holds the velocities itself).
inline void applyToBodies(VelocityView bodies, const ContactConstraint& c, F4 dn, F4 df) {
  const RowImpulses r = normalImpulses(c, dn), f = frictionImpulses(c, df);
  const F4 P = r.linear + f.linear;
  if (c.dynA) {
    store3(bodies.v[c.a], load3(bodies.v[c.a]) - c.invMassA * P);
    store3(bodies.w[c.a], load3(bodies.w[c.a]) - (r.angularA + f.angularA));
  }
  if (c.dynB) {
    store3(bodies.v[c.b], load3(bodies.v[c.b]) + c.invMassB * P);
    store3(bodies.w[c.b], load3(bodies.w[c.b]) + (r.angularB + f.angularB));
  }
}

// J v of four rows at the given body velocities: lin·(vb − va) + angB·wb − angA·wa.
inline F4 rowVelocities(const RowVectors& lin, const RowVectors& angA, const RowVectors& angB, F4 va, F4 wa, F4 vb,
                        F4 wb) {
  const F4 dv = vb - va;
  using simd4::splat;
  return load(lin.x) * splat<0>(dv) + load(lin.y) * splat<1>(dv) + load(lin.z) * splat<2>(dv) +
         (load(angB.x) * splat<0>(wb) + load(angB.y) * splat<1>(wb) + load(angB.z) * splat<2>(wb)) -
         (load(angA.x) * splat<0>(wa) + load(angA.y) * splat<1>(wa) + load(angA.z) * splat<2>(wa));
}

// Adds the velocity changes of row impulses r to the bodies' velocities.
inline void applyImpulses(const ContactConstraint& c, const RowImpulses& r, F4& va, F4& wa, F4& vb, F4& wb) {
  va -= c.invMassA * r.linear;
  wa -= r.angularA;
  vb += c.invMassB * r.linear;
  wb += r.angularB;
}

// rowBias of the four rows.
inline F4 rowBiases(const ContactConstraint& c, bool useBias) {
  return useBias ? load(c.bias) : relaxBias(load(c.bias), load(c.restitutionBias), load(c.normalImpulse));
}

}  // namespace
void warmStart(VelocityView bodies, const ContactConstraint* cs, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    const ContactConstraint& c = cs[k];
    if (c.count == 0) continue;
    applyToBodies(bodies, c, load(c.normalImpulse), load(c.frictionImpulse));
  }
}

namespace {

// The normal rows of a manifold are solved as one small problem: their velocities are read once
// (one 4-wide vector), updated through the coupling matrix while the exact block or a few projected
// passes settle the split of the load, and the caller applies the net impulse change to the bodies
// once. Returns the impulse change of each row (already added to c.normalImpulse).
inline F4 solveNormalBlock(ContactConstraint& c, F4 va, F4 wa, F4 vb, F4 wb,
                           float omega, bool useBias) {
  F4 vn = rowVelocities(c.normal, c.rAxn, c.rBxn, va, wa, vb, wb);
  const F4 bias = rowBiases(c, useBias);
  const F4 start = load(c.normalImpulse);
  if (c.blockExact) {
    // Exact block solve (2+ points); kept only when it leaves every point pushing (λ ≥ 0). G is
    // symmetric, so its rows serve as the columns of the product.
    const F4 s = vn + bias;
    using simd4::splat;
    const F4 g = load(c.blockInverse[0]) * splat<0>(s) + load(c.blockInverse[1]) * splat<1>(s) +
                 load(c.blockInverse[2]) * splat<2>(s) + load(c.blockInverse[3]) * splat<3>(s);
    const F4 next = start - omega * g;
    if (simd4::all(next >= 0.0f)) {
      store(c.normalImpulse, next);
      return next - start;
    }
  }
  alignas(16) float lambda[kMaxManifoldPoints], v[kMaxManifoldPoints], b[kMaxManifoldPoints];
  store(lambda, start);
  store(v, vn);
  store(b, bias);
  float K[kMaxManifoldPoints][kMaxManifoldPoints];
  if (c.count > 1) normalCoupling(c, K);
  projectedNormalPasses(c.count, v, b, c.normalMass, lambda, omega, [&](int i, int j) { return K[i][j]; });
  const F4 next = load(lambda);
  store(c.normalImpulse, next);
  return next - start;
}

// The twist row's constants as one vector: its coupling with tangent 1 and tangent 2, its mass and
// its lever (see ContactConstraint; they lie side by side).
static_assert(offsetof(ContactConstraint, twistMass) == offsetof(ContactConstraint, twistCoupling) + 8 &&
                  offsetof(ContactConstraint, twistRadius) == offsetof(ContactConstraint, twistCoupling) + 12,
              "the twist constants are read as one vector");
inline F4 twistConstants(const ContactConstraint& c) {
  F4 v;
  std::memcpy(&v, reinterpret_cast<const char*>(&c) + offsetof(ContactConstraint, twistCoupling), sizeof v);
  return v;
}

// The rolling row (lane 3 of the friction rows, angular only: J = [0, −a, 0, a]), after the other
// friction rows, at the velocities they leave: λ ← clamp(λ − ω m (a·(wb − wa)), ±lever Σλn), the
// bound from the normal impulses of the previous sweep, as friction's. Returns the impulse's
// change. Out of line, the velocities by value: few constraints have one, and the sweep's loop
// keeps its velocities in registers for the others.
[[gnu::noinline]] float rollingRow(ContactConstraint& c, F4 wa, F4 wb, float omega) {
  const F4 axis{c.frictionAngularA.x[3], c.frictionAngularA.y[3], c.frictionAngularA.z[3], 0.0f};
  const float speed = simd4::laneSum(axis * (wb - wa));
  const float bound = c.rollingLever * simd4::laneSum(load(c.normalImpulse));
  const float old = c.frictionImpulse[3];
  const float next = std::clamp(old - omega * c.rollingMass * speed, -bound, bound);
  c.frictionImpulse[3] = next;
  return next - old;
}

// The parts of a sweep, inlined into solveIteration's loop (the exported functions below wrap them
// for the chain solver): called out of line, large_pyramid's sweeps took 7% longer.
// `Rolling`: the world has rolling rows (SolverParams::rolling); without, lane 3 is zero throughout and
// the sweep is spared their test.
template <bool Rolling>
[[gnu::always_inline]] inline void frictionRows(ContactConstraint& c, F4& va, F4& wa, F4& vb, F4& wb,
                                                 float omega, bool useBias) {
  using simd4::splat;
  // Bounded by the normal impulses of the previous sweep.
  const F4 limit = F4{} + c.friction * simd4::laneSum(load(c.normalImpulse));
  const F4 vf = rowVelocities(c.frictionLinear, c.frictionAngularA, c.frictionAngularB, va, wa, vb, wb);
  const F4 old = load(c.frictionImpulse);
  const F4 tc = twistConstants(c);  // coupling 1, coupling 2, mass, radius
  // Twist about the normal first (lane 2).
  const F4 maxTwist = limit * splat<3>(tc);
  const F4 trial = old - omega * splat<2>(tc) * vf;
  const F4 twist = clampTwist(trial, maxTwist);
  const F4 twistApplied = splat<2>(twist - old);
  // Both tangent rows together (lanes 0 and 1), at their velocities after the twist's impulse,
  // clamped to the friction circle |λt| <= μ λn: clamping each axis alone (a box) lets friction
  // reach √2 μ λn and pushes a sliding body sideways.
  const F4 bias = load(c.frictionBias);
  const F4 vt = vf + tc * twistApplied + (useBias ? bias : __builtin_shuffle(bias, simd4::I4{2, 3, 2, 3}));
  const F4 m = load(&c.tangentMass[0][0]);  // m00, m01, m10, m11
  const F4 tangent = old - omega * (__builtin_shuffle(m, simd4::I4{0, 2, 0, 2}) * splat<0>(vt) +
                                    __builtin_shuffle(m, simd4::I4{1, 3, 1, 3}) * splat<1>(vt));
  // Lane 3, the rolling row, keeps its impulse here (its change is 0 in delta and the momentum step);
  // without rolling rows it is the twist's lane 3, which is 0.
  const F4 onCircle = ontoFrictionCircle(tangent, simd4::lane<0>(limit));
  const F4 next = Rolling ? joinFriction(onCircle, twist, old) : joinFriction(onCircle, twist, twist);
  const F4 applied = next - old;
  store(c.frictionImpulse, next);
  store(c.delta + kMaxManifoldPoints, applied);
  applyImpulses(c, frictionImpulses(c, applied), va, wa, vb, wb);
  if (Rolling && c.rollingMass > 0.0f) {
    const float change = rollingRow(c, wa, wb, omega);
    wa -= change * F4{c.frictionInverseA.x[3], c.frictionInverseA.y[3], c.frictionInverseA.z[3], 0.0f};
    wb += change * F4{c.frictionInverseB.x[3], c.frictionInverseB.y[3], c.frictionInverseB.z[3], 0.0f};
  }
}

[[gnu::always_inline]] inline float normalChange(ContactConstraint& c, F4 applied, F4& va, F4& wa, F4& vb, F4& wb) {
  store(c.delta, applied);  // the normal rows' changes; rows past the count are zero
  applyImpulses(c, normalImpulses(c, applied), va, wa, vb, wb);
  // |Δλ| / normalMass: the velocity correction of each row (K_ii = 1 / normalMass); rows without
  // a mass (degenerate, or past the count) do not count.
  const F4 mass = load(c.normalMass);
  return simd4::laneMax(mass > 0.0f ? simd4::abs(applied) / mass : F4{});
}

[[gnu::always_inline]] inline float normalRows(ContactConstraint& c, F4& va, F4& wa, F4& vb, F4& wb,
                                               float omega, bool useBias) {
  return normalChange(c, solveNormalBlock(c, va, wa, vb, wb, omega, useBias), va, wa, vb, wb);
}

[[gnu::always_inline]] inline float rowsChange(const ContactConstraint& c) {
  const F4 dn = load(c.delta), df = load(c.delta + kMaxManifoldPoints);
  return simd4::laneSum(dn * dn + df * df);
}

}  // namespace

// The exported parts of a sweep, on velocities the caller holds as Vec3.
void solveFrictionRows(ContactConstraint& c, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb, float omega, bool useBias) {
  F4 a = load3(va), b = load3(wa), d = load3(vb), e = load3(wb);
  frictionRows<true>(c, a, b, d, e, omega, useBias);
  store3(va, a), store3(wa, b), store3(vb, d), store3(wb, e);
}

float applyNormalChange(ContactConstraint& c, const float* applied, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb) {
  F4 a = load3(va), b = load3(wa), d = load3(vb), e = load3(wb);
  const float residual = normalChange(c, load(applied), a, b, d, e);
  store3(va, a), store3(wa, b), store3(vb, d), store3(wb, e);
  return residual;
}

float solveNormalRows(ContactConstraint& c, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb, float omega, bool useBias) {
  F4 a = load3(va), b = load3(wa), d = load3(vb), e = load3(wb);
  const float residual = normalRows(c, a, b, d, e, omega, useBias);
  store3(va, a), store3(wa, b), store3(vb, d), store3(wb, e);
  return residual;
}

double squaredChange(const ContactConstraint& c) { return rowsChange(c); }

namespace {

// A momentum direction starts from the constraint's last change (startDirection, and a sweep that
// restarts it).
inline void restartDirectionOf(ContactConstraint& c) {
  store(c.direction, load(c.delta));
  store(c.direction + kMaxManifoldPoints, load(c.delta + kMaxManifoldPoints));
}

// One constraint of a sweep, adding to its range's residual and change.
template <bool Restart, bool MeasureChange, bool Rolling>
[[gnu::always_inline]] inline void sweepOne(VelocityView bodies, ContactConstraint& c, float omega, bool useBias,
                                            float& residual, double& change) {
  if constexpr (Restart) restartDirectionOf(c);
  if (c.count == 0) return;
  // Static and kinematic bodies are read (their velocity is given) but never written, so
  // islands that share a static body can be solved concurrently.
  F4 va = load3(bodies.v[c.a]), wa = load3(bodies.w[c.a]), vb = load3(bodies.v[c.b]), wb = load3(bodies.w[c.b]);
  // Friction first; normal rows last: non-penetration matters more than friction, so each sweep
  // ends with the normal rows satisfied (see solveNormalBlock).
  frictionRows<Rolling>(c, va, wa, vb, wb, omega, useBias);
  residual = std::max(residual, normalRows(c, va, wa, vb, wb, omega, useBias));
  if constexpr (MeasureChange) change += rowsChange(c);
  if (c.dynA) {
    store3(bodies.v[c.a], va);
    store3(bodies.w[c.a], wa);
  }
  if (c.dynB) {
    store3(bodies.v[c.b], vb);
    store3(bodies.w[c.b], wb);
  }
}

template <bool Restart, bool MeasureChange, bool Rolling>
SweepResult sweep(VelocityView bodies, ContactConstraint* cs, size_t n, float omega, bool useBias) {
  float residual = 0.0f;
  double change = 0.0;
  for (size_t k = 0; k < n; ++k) sweepOne<Restart, MeasureChange, Rolling>(bodies, cs[k], omega, useBias, residual, change);
  return {residual, change};
}

// Two ranges on disjoint bodies, a constraint of each in turn; each range's result on its own.
template <bool Restart, bool MeasureChange, bool Rolling>
void sweepPair(VelocityView bodies, ContactConstraint* cs1, size_t n1, ContactConstraint* cs2, size_t n2, float omega,
               bool useBias, SweepResult& r1, SweepResult& r2) {
  float res1 = 0.0f, res2 = 0.0f;
  double ch1 = 0.0, ch2 = 0.0;
  const size_t both = std::min(n1, n2);
  for (size_t k = 0; k < both; ++k) {
    sweepOne<Restart, MeasureChange, Rolling>(bodies, cs1[k], omega, useBias, res1, ch1);
    sweepOne<Restart, MeasureChange, Rolling>(bodies, cs2[k], omega, useBias, res2, ch2);
  }
  for (size_t k = both; k < n1; ++k) sweepOne<Restart, MeasureChange, Rolling>(bodies, cs1[k], omega, useBias, res1, ch1);
  for (size_t k = both; k < n2; ++k) sweepOne<Restart, MeasureChange, Rolling>(bodies, cs2[k], omega, useBias, res2, ch2);
  r1 = {res1, ch1};
  r2 = {res2, ch2};
}

// The sweep's variants for a call's options.
template <bool Rolling>
SweepResult sweepWith(VelocityView bodies, ContactConstraint* cs, size_t n, float omega, bool useBias,
                      bool restartDirection, bool measureChange) {
  // A restarted direction is always followed by a momentum step, which needs the change.
  if (restartDirection) return sweep<true, true, Rolling>(bodies, cs, n, omega, useBias);
  return measureChange ? sweep<false, true, Rolling>(bodies, cs, n, omega, useBias)
                       : sweep<false, false, Rolling>(bodies, cs, n, omega, useBias);
}

template <bool Rolling>
void sweepPairWith(VelocityView bodies, ContactConstraint* cs1, size_t n1, ContactConstraint* cs2, size_t n2,
                   float omega, bool useBias, bool restartDirection, bool measureChange, SweepResult& r1,
                   SweepResult& r2) {
  if (restartDirection) return sweepPair<true, true, Rolling>(bodies, cs1, n1, cs2, n2, omega, useBias, r1, r2);
  if (measureChange) return sweepPair<false, true, Rolling>(bodies, cs1, n1, cs2, n2, omega, useBias, r1, r2);
  sweepPair<false, false, Rolling>(bodies, cs1, n1, cs2, n2, omega, useBias, r1, r2);
}

}  // namespace

SweepResult solveIteration(VelocityView bodies, ContactConstraint* cs, size_t n, float omega, bool useBias,
                           bool restartDirection, bool measureChange, bool rolling) {
  return rolling ? sweepWith<true>(bodies, cs, n, omega, useBias, restartDirection, measureChange)
                 : sweepWith<false>(bodies, cs, n, omega, useBias, restartDirection, measureChange);
}

void solveIterationPair(VelocityView bodies, ContactConstraint* cs1, size_t n1, ContactConstraint* cs2, size_t n2,
                        float omega, bool useBias, bool restartDirection, bool measureChange, bool rolling,
                        SweepResult& r1, SweepResult& r2) {
  if (rolling)
    sweepPairWith<true>(bodies, cs1, n1, cs2, n2, omega, useBias, restartDirection, measureChange, r1, r2);
  else
    sweepPairWith<false>(bodies, cs1, n1, cs2, n2, omega, useBias, restartDirection, measureChange, r1, r2);
}

void startDirection(ContactConstraint* cs, size_t n) {
  for (size_t k = 0; k < n; ++k) restartDirectionOf(cs[k]);
}

void accelerate(VelocityView bodies, ContactConstraint* cs, size_t n, float beta) {
  for (size_t k = 0; k < n; ++k) {
    ContactConstraint& c = cs[k];
    if (c.count == 0) continue;
    float* d = c.direction;
    const F4 dn = load(d), df = load(d + kMaxManifoldPoints);
    const F4 old = load(c.normalImpulse);
    const F4 next = simd4::clampNonNegative(old + beta * dn);
    store(c.normalImpulse, next);
    // Friction stays inside the cone of the new normal impulses.
    const float limit = c.friction * simd4::laneSum(next);
    const F4 oldFriction = load(c.frictionImpulse);
    const F4 step = oldFriction + beta * df;
    const F4 nextFriction =
        joinFriction(ontoFrictionCircle(step, limit), clampTwist(step, F4{} + limit * c.twistRadius), oldFriction);
    store(c.frictionImpulse, nextFriction);
    applyToBodies(bodies, c, next - old, nextFriction - oldFriction);
    store(d, beta * dn + load(c.delta));
    store(d + kMaxManifoldPoints, beta * df + load(c.delta + kMaxManifoldPoints));
  }
}

// Tangential impulse, as a share of the friction limit, at which a contact counts as sliding.
constexpr float kAnchorRelease = 0.98f;

void storeImpulses(const ContactConstraint* cs, size_t n, Contact* contacts) {
  for (size_t k = 0; k < n; ++k) {
    const ContactConstraint& c = cs[k];
    if (k + kPrefetchAhead < n) prefetchContact(contacts[cs[k + kPrefetchAhead].contact]);  // scattered
    Contact& ct = contacts[c.contact];
    // A pinch's impulses are the conflict's, not a load: none is carried into the next step.
    if (ct.pinched) {
      for (int i = 0; i < c.count; ++i) ct.normalImpulse[i] = 0.0f;
      ct.frictionImpulse.setZero();
      ct.twistImpulse = 0.0f;
      if (c.rollingLever > 0.0f) ct.rollingImpulse.setZero();
      continue;
    }
    for (int i = 0; i < c.count; ++i) ct.normalImpulse[i] = c.normalImpulse[i];
    if (c.count == 0) continue;
    ct.frictionImpulse = c.frictionImpulse[0] * c.tangent1() + c.frictionImpulse[1] * c.tangent2();
    ct.twistImpulse = c.frictionImpulse[2];
    ct.frictionNormal = c.twistAxis();
    if (c.rollingLever > 0.0f)
      ct.rollingImpulse = c.rollingMass > 0.0f ? Vec3(c.frictionImpulse[3] * c.rollingAxis()) : Vec3::Zero();
    // Friction at its limit slides: the anchor lets go and is set anew where the pair next sticks.
    const float limit = c.friction * simd4::laneSum(load(c.normalImpulse));
    const float t1 = c.frictionImpulse[0], t2 = c.frictionImpulse[1];
    if (t1 * t1 + t2 * t2 >= kAnchorRelease * kAnchorRelease * limit * limit) ct.anchored = false;
  }
}

}  // namespace haif
