#include "dynamics/wide_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

// Without AVX, GCC notes that 32-byte vectors passed by value change the calling convention. Every
// function here that does so is internal to this file, so no two conventions ever meet.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace haif {

using wide::F8;
using wide::I8;
using wide::V3;

namespace {

constexpr int kP = kMaxManifoldPoints;

inline F8 splat(float x) { return F8{} + x; }
inline F8 dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(const F8& s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3& operator+=(V3& a, const V3& b) {
  a.x += b.x, a.y += b.y, a.z += b.z;
  return a;
}
inline V3& operator-=(V3& a, const V3& b) {
  a.x -= b.x, a.y -= b.y, a.z -= b.z;
  return a;
}
inline F8 max8(F8 a, F8 b) { return a > b ? a : b; }
inline F8 min8(F8 a, F8 b) { return a < b ? a : b; }
inline F8 sqrt8(F8 x) {
#if defined(__AVX__)
  return F8(_mm256_sqrt_ps(__m256(x)));
#else
  F8 r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(x[l]);
  return r;
#endif
}

inline unsigned laneMask(I8 m) {
#if defined(__AVX__)
  return unsigned(_mm256_movemask_ps(__m256(m)));
#else
  unsigned r = 0;
  for (int l = 0; l < kLanes; ++l) r |= m[l] ? 1u << l : 0u;
  return r;
#endif
}
inline F8 abs8(F8 a) { return a < 0.0f ? -a : a; }

inline void setLane(V3& w, int l, const Vec3& v) {
  w.x[l] = v.x();
  w.y[l] = v.y();
  w.z[l] = v.z();
}
inline Vec3 lane(const V3& w, int l) { return {w.x[l], w.y[l], w.z[l]}; }

// Body velocities of the batch's lanes. Lanes past w.lanes read lane 0's bodies (their rows are
// zero) and are never written back.
struct Velocities {
  V3 va, wa, vb, wb;
};

#if defined(__AVX2__)
// Eight 3-vectors at ptr[idx[l]] as three 8-lane vectors: 8 masked 3-float loads and a transpose.
// (Writing lanes through a buffer cost a store-forwarding stall per vector: slower than scalar.)
inline V3 gather3(const Vec3* base, const uint32_t* idx) {
  const __m128i m3 = _mm_setr_epi32(-1, -1, -1, 0);
  __m128 r[kLanes];
  for (int l = 0; l < kLanes; ++l) r[l] = _mm_maskload_ps(base[idx[l]].data(), m3);
  const __m256 t0 = _mm256_set_m128(r[4], r[0]), t1 = _mm256_set_m128(r[5], r[1]);
  const __m256 t2 = _mm256_set_m128(r[6], r[2]), t3 = _mm256_set_m128(r[7], r[3]);
  const __m256 u0 = _mm256_unpacklo_ps(t0, t1), u1 = _mm256_unpackhi_ps(t0, t1);
  const __m256 u2 = _mm256_unpacklo_ps(t2, t3), u3 = _mm256_unpackhi_ps(t2, t3);
  return {F8(_mm256_shuffle_ps(u0, u2, 0x44)), F8(_mm256_shuffle_ps(u0, u2, 0xEE)),
          F8(_mm256_shuffle_ps(u1, u3, 0x44))};
}

// The inverse: lane l of v to base[idx[l]] where bit l of `write` is set.
inline void scatter3(Vec3* base, const uint32_t* idx, unsigned write, const V3& v) {
  const __m128i m3 = _mm_setr_epi32(-1, -1, -1, 0);
  const __m256 x = __m256(v.x), y = __m256(v.y), z = __m256(v.z);
  const __m256 u0 = _mm256_unpacklo_ps(x, y), u1 = _mm256_unpackhi_ps(x, y);
  const __m256 u2 = _mm256_unpacklo_ps(z, z), u3 = _mm256_unpackhi_ps(z, z);
  const __m256 r04 = _mm256_shuffle_ps(u0, u2, 0x44), r15 = _mm256_shuffle_ps(u0, u2, 0xEE);
  const __m256 r26 = _mm256_shuffle_ps(u1, u3, 0x44), r37 = _mm256_shuffle_ps(u1, u3, 0xEE);
  const __m256 pair[4] = {r04, r15, r26, r37};
  for (int l = 0; l < 4; ++l) {
    if (write & (1u << l)) _mm_maskstore_ps(base[idx[l]].data(), m3, _mm256_castps256_ps128(pair[l]));
    if (write & (1u << (l + 4))) _mm_maskstore_ps(base[idx[l + 4]].data(), m3, _mm256_extractf128_ps(pair[l], 1));
  }
}
#else
inline V3 gather3(const Vec3* base, const uint32_t* idx) {
  V3 r;
  for (int l = 0; l < kLanes; ++l) {
    const Vec3& v = base[idx[l]];
    r.x[l] = v.x();
    r.y[l] = v.y();
    r.z[l] = v.z();
  }
  return r;
}

inline void scatter3(Vec3* base, const uint32_t* idx, unsigned write, const V3& v) {
  for (int l = 0; l < kLanes; ++l)
    if (write & (1u << l)) base[idx[l]] = Vec3(v.x[l], v.y[l], v.z[l]);
}
#endif

inline Velocities gather(const BodyStore& bodies, const WideContactBatch& w) {
  return {gather3(bodies.v.data(), w.a), gather3(bodies.w.data(), w.a), gather3(bodies.v.data(), w.b),
          gather3(bodies.w.data(), w.b)};
}

// Written back only for dynamic bodies of lanes with points: a static body is shared by lanes.
inline void scatter(BodyStore& bodies, const WideContactBatch& w, const Velocities& r) {
  const unsigned a = w.active & w.dynA, b = w.active & w.dynB;
  scatter3(bodies.v.data(), w.a, a, r.va);
  scatter3(bodies.w.data(), w.a, a, r.wa);
  scatter3(bodies.v.data(), w.b, b, r.vb);
  scatter3(bodies.w.data(), w.b, b, r.wb);
}

// Scales (n1, n2) back onto the circle of radius `limit` in the lanes where it lies outside.
inline void clampToFrictionCircle(F8& n1, F8& n2, F8 limit) {
  const F8 len2 = n1 * n1 + n2 * n2;
  const I8 outside = len2 > limit * limit;
  if (laneMask(outside) == 0) return;
  const F8 scale = frictionCircleScale(len2, limit, sqrt8);
  n1 *= scale;
  n2 *= scale;
}

}  // namespace

void packWide(const ContactConstraint* cs, int lanes, WideContactBatch& w) {
  w = WideContactBatch{};
  w.lanes = lanes;
  for (int l = 0; l < kLanes; ++l) {
    w.a[l] = w.b[l] = cs[0].a;  // never read beyond `lanes`
    w.count[l] = 0;
  }
  for (int l = 0; l < lanes; ++l) {
    const ContactConstraint& c = cs[l];
    w.a[l] = c.a;
    w.b[l] = c.b;
    w.count[l] = c.count;
    if (c.count == 0) continue;
    w.active |= 1u << l;
    if (c.dynA) w.dynA |= 1u << l;
    if (c.dynB) w.dynB |= 1u << l;
    w.invMassA[l] = c.invMassA;
    w.invMassB[l] = c.invMassB;
    w.friction[l] = c.friction;
    float K[kMaxManifoldPoints][kMaxManifoldPoints];
    normalCoupling(c, K);
    for (int i = 0; i < c.count; ++i) {
      setLane(w.normal[i], l, c.normal.row(i));
      setLane(w.rAxn[i], l, c.rAxn.row(i));
      setLane(w.rBxn[i], l, c.rBxn.row(i));
      setLane(w.iAn[i], l, c.iAn.row(i));
      setLane(w.iBn[i], l, c.iBn.row(i));
      w.normalMass[i][l] = c.normalMass[i];
      w.bias[i][l] = c.bias[i];
      w.restitutionBias[i][l] = c.restitutionBias[i];
      w.normalImpulse[i][l] = c.normalImpulse[i];
      for (int j = 0; j < c.count; ++j) {
        w.coupling[i][j][l] = K[i][j];
        w.blockInverse[i][j][l] = c.blockExact ? c.blockInverse[i][j] : 0.0f;
      }
    }
    w.blockExact[l] = c.blockExact && c.count > 1 ? -1 : 0;
    setLane(w.tangent1, l, c.tangent1());
    setLane(w.tangent2, l, c.tangent2());
    setLane(w.twistAxis, l, c.twistAxis());
    setLane(w.rAxt1, l, c.frictionAngularA.row(0));
    setLane(w.rBxt1, l, c.frictionAngularB.row(0));
    setLane(w.rAxt2, l, c.frictionAngularA.row(1));
    setLane(w.rBxt2, l, c.frictionAngularB.row(1));
    setLane(w.iAt1, l, c.frictionInverseA.row(0));
    setLane(w.iBt1, l, c.frictionInverseB.row(0));
    setLane(w.iAt2, l, c.frictionInverseA.row(1));
    setLane(w.iBt2, l, c.frictionInverseB.row(1));
    setLane(w.iAtw, l, c.frictionInverseA.row(2));
    setLane(w.iBtw, l, c.frictionInverseB.row(2));
    w.tangentMass00[l] = c.tangentMass[0][0];
    w.tangentMass01[l] = c.tangentMass[0][1];
    w.tangentMass10[l] = c.tangentMass[1][0];
    w.tangentMass11[l] = c.tangentMass[1][1];
    w.twistMass[l] = c.twistMass;
    w.twistRadius[l] = c.twistRadius;
    w.tangentBias1[l] = c.frictionBias[0];
    w.tangentBias2[l] = c.frictionBias[1];
    w.tangentLead1[l] = c.frictionBias[2];
    w.tangentLead2[l] = c.frictionBias[3];
    w.tangentImpulse1[l] = c.frictionImpulse[0];
    w.tangentImpulse2[l] = c.frictionImpulse[1];
    w.twistImpulse[l] = c.frictionImpulse[2];
    for (int r = 0; r < ContactConstraint::kRows; ++r) {
      w.delta[r][l] = c.delta[r];
      w.direction[r][l] = c.direction[r];
    }
  }
}

void unpackWideImpulses(const WideContactBatch& w, ContactConstraint* cs) {
  for (int l = 0; l < w.lanes; ++l) {
    ContactConstraint& c = cs[l];
    if (!(w.active & (1u << l))) continue;
    for (int i = 0; i < c.count; ++i) c.normalImpulse[i] = w.normalImpulse[i][l];
    c.frictionImpulse[0] = w.tangentImpulse1[l];
    c.frictionImpulse[1] = w.tangentImpulse2[l];
    c.frictionImpulse[2] = w.twistImpulse[l];
  }
}

namespace {

// The projected passes of solveNormalBlock for lane l, on the lane's velocities vn (after friction).
void normalPassesLane(WideContactBatch& w, int l, const F8* vn, const F8* bias, float omega, F8* applied) {
  const int m = w.count[l];
  float v[kP], b[kP], mass[kP], lambda[kP];
  for (int i = 0; i < m; ++i) {
    v[i] = vn[i][l];
    b[i] = bias[i][l];
    mass[i] = w.normalMass[i][l];
    lambda[i] = w.normalImpulse[i][l];
  }
  projectedNormalPasses(m, v, b, mass, lambda, omega, [&](int i, int j) { return w.coupling[i][j][l]; });
  for (int i = 0; i < m; ++i) {
    applied[i][l] = lambda[i] - w.normalImpulse[i][l];
    w.normalImpulse[i][l] = lambda[i];
  }
}

}  // namespace

SweepResult solveWide(BodyStore& bodies, WideContactBatch& w, float omega, bool useBias) {
  Velocities vel = gather(bodies, w);
  V3 &va = vel.va, &wa = vel.wa, &vb = vel.vb, &wb = vel.wb;
  const F8 om = splat(omega);

  // Friction first (bounded by the previous sweep's normal impulses), as in solveIteration.
  F8 normalTotal = w.normalImpulse[0];
  for (int i = 1; i < kP; ++i) normalTotal += w.normalImpulse[i];
  const F8 limit = w.friction * normalTotal;
  {
    const F8 vt = dot(w.twistAxis, wb - wa);
    const F8 maxTwist = limit * w.twistRadius;
    const F8 old = w.twistImpulse;
    const F8 x = clampTwist(old - om * w.twistMass * vt, maxTwist);
    w.twistImpulse = x;
    const F8 applied = x - old;
    w.delta[kP + 2] = applied;
    wa -= applied * w.iAtw;
    wb += applied * w.iBtw;
  }
  {
    const V3 dv = vb - va;
    F8 vt1 = dot(w.tangent1, dv) + dot(w.rBxt1, wb) - dot(w.rAxt1, wa);
    F8 vt2 = dot(w.tangent2, dv) + dot(w.rBxt2, wb) - dot(w.rAxt2, wa);
    vt1 += useBias ? w.tangentBias1 : w.tangentLead1;
    vt2 += useBias ? w.tangentBias2 : w.tangentLead2;
    const F8 old1 = w.tangentImpulse1, old2 = w.tangentImpulse2;
    F8 n1 = old1 - om * (w.tangentMass00 * vt1 + w.tangentMass01 * vt2);
    F8 n2 = old2 - om * (w.tangentMass10 * vt1 + w.tangentMass11 * vt2);
    clampToFrictionCircle(n1, n2, limit);
    w.tangentImpulse1 = n1;
    w.tangentImpulse2 = n2;
    const F8 a1 = n1 - old1, a2 = n2 - old2;
    w.delta[kP] = a1;
    w.delta[kP + 1] = a2;
    V3 P = a1 * w.tangent1;
    P += a2 * w.tangent2;
    va -= w.invMassA * P;
    V3 angA = a1 * w.iAt1, angB = a1 * w.iBt1;
    angA += a2 * w.iAt2;
    angB += a2 * w.iBt2;
    wa -= angA;
    vb += w.invMassB * P;
    wb += angB;
  }

  // Normal rows: the exact block where it keeps every point pushing, else the passes lane by lane.
  F8 vn[kP], bias[kP], applied[kP];
  const V3 dv = vb - va;
  for (int i = 0; i < kP; ++i) {
    vn[i] = dot(w.normal[i], dv) + dot(w.rBxn[i], wb) - dot(w.rAxn[i], wa);
    bias[i] = useBias ? w.bias[i] : relaxBias(w.bias[i], w.restitutionBias[i], w.normalImpulse[i]);
  }
  I8 loaded = w.blockExact;
  F8 next[kP];
  for (int i = 0; i < kP; ++i) {
    F8 d = F8{};
    for (int j = 0; j < kP; ++j) d -= w.blockInverse[i][j] * (vn[j] + bias[j]);
    next[i] = w.normalImpulse[i] + om * d;
    loaded &= next[i] >= 0.0f;
  }
  for (int i = 0; i < kP; ++i) {
    applied[i] = loaded ? next[i] - w.normalImpulse[i] : F8{};
    w.normalImpulse[i] = loaded ? next[i] : w.normalImpulse[i];
  }
  for (unsigned rest = w.active & ~laneMask(loaded); rest; rest &= rest - 1)
    normalPassesLane(w, __builtin_ctz(rest), vn, bias, omega, applied);

  F8 residual = F8{};
  for (int i = 0; i < kP; ++i) {
    w.delta[i] = applied[i];
    va -= (w.invMassA * applied[i]) * w.normal[i];
    wa -= applied[i] * w.iAn[i];
    vb += (w.invMassB * applied[i]) * w.normal[i];
    wb += applied[i] * w.iBn[i];
    const F8 r = abs8(applied[i]) * w.coupling[i][i];
    residual = w.normalMass[i] > 0.0f ? max8(residual, r) : residual;
  }
  F8 sq = w.delta[0] * w.delta[0];
  for (int r = 1; r < ContactConstraint::kRows; ++r) sq += w.delta[r] * w.delta[r];
  scatter(bodies, w, vel);

  SweepResult out;
  for (int l = 0; l < w.lanes; ++l) {
    out.residual = std::max(out.residual, residual[l]);
    out.change += double(sq[l]);
  }
  return out;
}

void startDirectionWide(WideContactBatch& w) {
  for (int r = 0; r < ContactConstraint::kRows; ++r) w.direction[r] = w.delta[r];
}

void accelerateWide(BodyStore& bodies, WideContactBatch& w, float beta) {
  constexpr int t1 = kP, t2 = kP + 1, tw = kP + 2;
  Velocities vel = gather(bodies, w);
  const F8 bt = splat(beta);
  F8* d = w.direction;
  V3 P{}, angA{}, angB{};
  F8 normalTotal = F8{};
  for (int i = 0; i < kP; ++i) {
    const F8 old = w.normalImpulse[i];
    w.normalImpulse[i] = max8(F8{}, old + bt * d[i]);
    const F8 applied = w.normalImpulse[i] - old;
    P += applied * w.normal[i];
    angA += applied * w.iAn[i];
    angB += applied * w.iBn[i];
    normalTotal += w.normalImpulse[i];
  }
  const F8 limit = w.friction * normalTotal;
  F8 n1 = w.tangentImpulse1 + bt * d[t1], n2 = w.tangentImpulse2 + bt * d[t2];
  clampToFrictionCircle(n1, n2, limit);
  const F8 a1 = n1 - w.tangentImpulse1, a2 = n2 - w.tangentImpulse2;
  w.tangentImpulse1 = n1;
  w.tangentImpulse2 = n2;
  P += a1 * w.tangent1;
  P += a2 * w.tangent2;
  angA += a1 * w.iAt1;
  angA += a2 * w.iAt2;
  angB += a1 * w.iBt1;
  angB += a2 * w.iBt2;
  const F8 maxTwist = limit * w.twistRadius;
  const F8 twist = clampTwist(F8(w.twistImpulse + bt * d[tw]), maxTwist);
  angA += (twist - w.twistImpulse) * w.iAtw;
  angB += (twist - w.twistImpulse) * w.iBtw;
  w.twistImpulse = twist;
  vel.va -= w.invMassA * P;
  vel.wa -= angA;
  vel.vb += w.invMassB * P;
  vel.wb += angB;
  scatter(bodies, w, vel);
  for (int r = 0; r < ContactConstraint::kRows; ++r) d[r] = bt * d[r] + w.delta[r];
}

void packLanes(const ContactConstraint* cs, size_t n, const LaneBatches& lb) {
  for (size_t j = 0; j < n; j += lb.run[j])
    if (lb.wideOf[j] >= 0) packWide(cs + j, lb.run[j], lb.wide[lb.wideOf[j]]);
}

void unpackLanes(ContactConstraint* cs, size_t n, const LaneBatches& lb) {
  for (size_t j = 0; j < n; j += lb.run[j])
    if (lb.wideOf[j] >= 0) unpackWideImpulses(lb.wide[lb.wideOf[j]], cs + j);
}

void reaimLanesForRelax(const BodyStore& bodies, const Contact* contacts, const SolverParams& p,
                        ContactConstraint* cs, size_t n, const LaneBatches& lb) {
  for (size_t j = 0; j < n; j += lb.run[j]) {
    ContactConstraint* rows = cs + j;
    const size_t run = lb.run[j];
    if (lb.wideOf[j] < 0) {
      for (size_t i = 0; i < run; ++i) reaimForRelax(bodies, bodies.v.data(), contacts[rows[i].contact], p, rows[i]);
      continue;
    }
    bool any = false;
    for (size_t i = 0; i < run && !any; ++i) any = wantsReaim(bodies.v.data(), p, rows[i]);
    if (!any) continue;  // a resting batch: its packed rows stand
    WideContactBatch& batch = lb.wide[lb.wideOf[j]];
    unpackWideImpulses(batch, rows);
    for (size_t i = 0; i < run; ++i) reaimForRelax(bodies, bodies.v.data(), contacts[rows[i].contact], p, rows[i]);
    packWide(rows, run, batch);
  }
}

SweepResult solveIterationLanes(BodyStore& bodies, ContactConstraint* cs, size_t n, const LaneBatches& lb,
                                float omega, bool useBias) {
  SweepResult total;
  for (size_t j = 0; j < n; j += lb.run[j]) {
    if (lb.wideOf[j] >= 0) total.merge(solveWide(bodies, lb.wide[lb.wideOf[j]], omega, useBias));
    else total.merge(solveIteration(bodies, cs + j, lb.run[j], omega, useBias));
  }
  return total;
}

void startDirectionLanes(ContactConstraint* cs, size_t n, const LaneBatches& lb) {
  for (size_t j = 0; j < n; j += lb.run[j]) {
    if (lb.wideOf[j] >= 0) startDirectionWide(lb.wide[lb.wideOf[j]]);
    else startDirection(cs + j, lb.run[j]);
  }
}

void accelerateLanes(BodyStore& bodies, ContactConstraint* cs, size_t n, const LaneBatches& lb, float beta) {
  for (size_t j = 0; j < n; j += lb.run[j]) {
    if (lb.wideOf[j] >= 0) accelerateWide(bodies, lb.wide[lb.wideOf[j]], beta);
    else accelerate(bodies, cs + j, lb.run[j], beta);
  }
}

}  // namespace haif
