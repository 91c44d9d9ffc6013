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

bool invertSymmetric3(const double a[3][3], double out[3][3], double minDetRatio) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  if (!(a[0][0] > 0.0 && a[1][1] > 0.0 && a[2][2] > 0.0 && det > minDetRatio * a[0][0] * a[1][1] * a[2][2]))
    return false;
  out[0][0] = c00 / det;
  out[1][0] = out[0][1] = c01 / det;
  out[2][0] = out[0][2] = c02 / det;
  out[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  out[2][1] = out[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
  out[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
  return true;
}

int pointBasis(const double coords[kMaxManifoldPoints][2], int count, unsigned mask, double B[kMaxManifoldPoints][3]) {
  // The span of [1, s, t] does not depend on where (s, t) are measured from, but the rank test does:
  // it takes the spread about the points' mean (the coordinates of a whole manifold already are).
  const unsigned all = (1u << count) - 1u;
  double ms = 0.0, mt = 0.0;
  int m = 0;
  for (int i = 0; i < count; ++i)
    if (mask & (1u << i)) {
      ms += coords[i][0];
      mt += coords[i][1];
      ++m;
    }
  if (m == 0) {
    for (int i = 0; i < kMaxManifoldPoints; ++i) B[i][0] = B[i][1] = B[i][2] = 0.0;
    return 0;
  }
  if ((mask & all) == all) ms = mt = 0.0;
  else ms /= m, mt /= m;
  // Every entry is written (rows of points not in the mask are zero), so no separate clearing pass:
  // called once per manifold per step, the clearing loops compiled to two memset calls.
  double css = 0.0, ctt = 0.0, cst = 0.0;
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    const bool in = i < count && (mask & (1u << i));
    const double s = in ? coords[i][0] - ms : 0.0, t = in ? coords[i][1] - mt : 0.0;
    B[i][0] = in ? 1.0 : 0.0;
    B[i][1] = s;
    B[i][2] = t;
    if (!in) continue;
    css += s * s;
    ctt += t * t;
    cst += s * t;
  }
  const double spread = css + ctt;
  const bool single = m < 2 || !(spread > 1e-12);  // all points in one place
  const bool collinear = !single && css * ctt - cst * cst <= 1e-4 * spread * spread;
  const int k = single ? 1 : m >= 3 && !collinear ? 3 : 2;
  if (k == 2 && ctt > css)
    for (int i = 0; i < count; ++i) B[i][1] = B[i][2];
  for (int i = 0; i < count; ++i)
    for (int a = k; a < 3; ++a) B[i][a] = 0.0;
  return k;
}

void planarCoords(const Manifold& mf, const Vec3& centre, const Vec3& t1, const Vec3& t2,
                  double coords[kMaxManifoldPoints][2]) {
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    if (i < mf.count) {
      const Vec3 d = mf.points[i].position - centre;
      coords[i][0] = d.dot(t1);
      coords[i][1] = d.dot(t2);
    } else {
      coords[i][0] = coords[i][1] = 0.0;
    }
  }
}

void normalCoupling(const ContactConstraint& c, float K[kMaxManifoldPoints][kMaxManifoldPoints]) {
  const float mSum = c.invMassA + c.invMassB;
  const F4 nx = load(c.normal.x), ny = load(c.normal.y), nz = load(c.normal.z);
  const F4 iAnX = load(c.iAn.x), iAnY = load(c.iAn.y), iAnZ = load(c.iAn.z);
  const F4 iBnX = load(c.iBn.x), iBnY = load(c.iBn.y), iBnZ = load(c.iBn.z);
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    const F4 row = mSum * (c.normal.x[i] * nx + c.normal.y[i] * ny + c.normal.z[i] * nz) +
                   (c.rAxn.x[i] * iAnX + c.rAxn.y[i] * iAnY + c.rAxn.z[i] * iAnZ) +
                   (c.rBxn.x[i] * iBnX + c.rBxn.y[i] * iBnY + c.rBxn.z[i] * iBnZ);
    store(K[i], row);
  }
  for (int i = 0; i < kMaxManifoldPoints; ++i)  // exactly symmetric: the solver reads rows as columns
    for (int j = i + 1; j < kMaxManifoldPoints; ++j) K[j][i] = K[i][j];
}

namespace {

// G = B (Bᵀ K B)⁻¹ Bᵀ for M collinear points (a basis of rank 2: [1, the coordinate along the
// line]), with the loop bounds known at compile time so they unroll.
template <int M>
bool lineBlockInverse(const float coupling[kMaxManifoldPoints][kMaxManifoldPoints],
                      const double B[kMaxManifoldPoints][3], float G[kMaxManifoldPoints][kMaxManifoldPoints]) {
  constexpr int Kb = 2;
  // A = Bᵀ K B (2 × 2, symmetric positive definite when the bodies can respond in both ways).
  double KB[M][Kb] = {};
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < M; ++j)
      for (int a = 0; a < Kb; ++a) KB[i][a] += double(coupling[i][j]) * B[j][a];
  double A[Kb][Kb] = {};
  for (int a = 0; a < Kb; ++a)
    for (int b = a; b < Kb; ++b) {
      for (int i = 0; i < M; ++i) A[a][b] += B[i][a] * KB[i][b];
      A[b][a] = A[a][b];
    }
  // Inverse by cofactors; a determinant small against the diagonal means a direction the bodies
  // cannot respond in (e.g. no rotation): leave that block to the passes.
  const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  if (!(det > 1e-6 * A[0][0] * A[1][1])) return false;
  double inv[Kb][Kb];
  inv[0][0] = A[1][1] / det;
  inv[1][1] = A[0][0] / det;
  inv[0][1] = inv[1][0] = -A[0][1] / det;
  double C[Kb][M] = {};  // A⁻¹ Bᵀ
  for (int a = 0; a < Kb; ++a)
    for (int j = 0; j < M; ++j)
      for (int b = 0; b < Kb; ++b) C[a][j] += inv[a][b] * B[j][b];
  for (int i = 0; i < kMaxManifoldPoints; ++i)
    for (int j = i; j < kMaxManifoldPoints; ++j) {
      double g = 0.0;
      if (i < M && j < M)
        for (int a = 0; a < Kb; ++a) g += B[i][a] * C[a][j];
      G[i][j] = G[j][i] = float(g);
    }
  return true;
}

// G for a rank-3 basis (a patch of 3 or 4 points, the common case), on 4-wide double
// vectors: the same products, a column of K B or a row of A⁻¹ Bᵀ per vector. Rows of K and B past
// the point count are zero, so they drop out.
using D4 = double __attribute__((vector_size(4 * sizeof(double))));

bool patchBlockInverse(const float coupling[kMaxManifoldPoints][kMaxManifoldPoints], const D4 Bc[3],
                       float G[kMaxManifoldPoints][kMaxManifoldPoints]) {
  D4 KB[3] = {};  // columns of K B
  for (int j = 0; j < kMaxManifoldPoints; ++j) {
    const D4 Kj{coupling[j][0], coupling[j][1], coupling[j][2], coupling[j][3]};  // column j (K is symmetric)
    for (int a = 0; a < 3; ++a) KB[a] += Kj * Bc[a][j];
  }
  double A[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      const D4 p = Bc[a] * KB[b];
      A[a][b] = A[b][a] = (p[0] + p[1]) + (p[2] + p[3]);
    }
  double inv[3][3];
  if (!invertSymmetric3(A, inv, 1e-6)) return false;
  D4 C[3];  // rows of A⁻¹ Bᵀ
  for (int a = 0; a < 3; ++a) C[a] = inv[a][0] * Bc[0] + inv[a][1] * Bc[1] + inv[a][2] * Bc[2];
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    const D4 g = Bc[0][i] * C[0] + Bc[1][i] * C[1] + Bc[2][i] * C[2];
    for (int j = i; j < kMaxManifoldPoints; ++j) G[i][j] = G[j][i] = float(g[j]);
  }
  return true;
}

// Builds cc.blockInverse (see ContactConstraint) from the points' in-plane coordinates (s, t) about
// their centre (zero past the count) and the coupling matrix; false when the block must be solved
// by passes alone. The basis and its rank test are pointBasis's, for all points.
bool prepareBlockInverse(F4 s, F4 t, ContactConstraint& cc) {
  const int m = cc.count;
  if (m < 2) return false;
  const F4 nx = load(cc.normal.x), ny = load(cc.normal.y), nz = load(cc.normal.z);
  const F4 dx = nx - simd4::splat<0>(nx), dy = ny - simd4::splat<0>(ny), dz = nz - simd4::splat<0>(nz);
  const simd4::I4 points = simd4::I4{0, 1, 2, 3} < m;
  if (simd4::laneMax(points ? dx * dx + dy * dy + dz * dz : F4{}) > 1e-8f) return false;
  const D4 used{1.0, 1.0, m > 2 ? 1.0 : 0.0, m > 3 ? 1.0 : 0.0};
  D4 Bc[3] = {used, D4{s[0], s[1], s[2], s[3]}, D4{t[0], t[1], t[2], t[3]}};
  const D4 ss = Bc[1] * Bc[1], tt = Bc[2] * Bc[2], st = Bc[1] * Bc[2];
  const double css = (ss[0] + ss[1]) + (ss[2] + ss[3]), ctt = (tt[0] + tt[1]) + (tt[2] + tt[3]);
  const double cst = (st[0] + st[1]) + (st[2] + st[3]);
  const double spread = css + ctt;
  if (!(spread > 1e-12)) return false;  // rank 1: all points in one place
  float K[kMaxManifoldPoints][kMaxManifoldPoints];
  normalCoupling(cc, K);
  auto& G = cc.blockInverse;
  const bool collinear = css * ctt - cst * cst <= 1e-4 * spread * spread;
  if (m >= 3 && !collinear) return patchBlockInverse(K, Bc, G);
  // Rank 2: [1, the coordinate along the line].
  const D4 along = ctt > css ? Bc[2] : Bc[1];
  double B[kMaxManifoldPoints][3];
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    B[i][0] = used[i];
    B[i][1] = along[i];
    B[i][2] = 0.0;
  }
  switch (m) {
    case 4: return lineBlockInverse<4>(K, B, G);
    case 3: return lineBlockInverse<3>(K, B, G);
    default: return lineBlockInverse<2>(K, B, G);
  }
}

}  // namespace

namespace {

// Four rows' 3-vectors as vectors of their components, one lane a row (as RowVectors holds them).
struct Lanes3 {
  F4 x, y, z;
};

// m times each row's vector.
inline Lanes3 times(const Mat3& m, const Lanes3& v) {
  return {m(0, 0) * v.x + m(0, 1) * v.y + m(0, 2) * v.z, m(1, 0) * v.x + m(1, 1) * v.y + m(1, 2) * v.z,
          m(2, 0) * v.x + m(2, 1) * v.y + m(2, 2) * v.z};
}

inline F4 dot(const Lanes3& a, const Lanes3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline void storeRows(RowVectors& rows, const Lanes3& v) {
  store(rows.x, v.x);
  store(rows.y, v.y);
  store(rows.z, v.z);
}

}  // namespace

// Tangential impulse, as a share of the friction limit, at which a contact counts as sliding.
constexpr float kAnchorRelease = 0.98f;
// Relative travel (m) in a step beyond which a pair's rows are re-aimed for the relax sweeps
// (reaimForRelax): below it the two lever arms differ by less than the slop's fifth.
constexpr float kReaimTravel = 1e-3f;
void prepareContact(const BodyStore& bodies, const Contact& contact, uint32_t ci, const SolverParams& p,
                    ContactConstraint& cc, const Vec3& shift) {
  const uint32_t a = contact.a, b = contact.b;
  cc.a = a;
  cc.b = b;
  cc.contact = ci;
  cc.dynA = bodies.isAwakeDynamic(a);
  cc.dynB = bodies.isAwakeDynamic(b);
  cc.invMassA = cc.dynA ? bodies.invMass[a] : 0.0f;
  cc.invMassB = cc.dynB ? bodies.invMass[b] : 0.0f;
  const Mat3 iA = cc.dynA ? bodies.invInertiaWorld[a] : Mat3::Zero();
  const Mat3 iB = cc.dynB ? bodies.invInertiaWorld[b] : Mat3::Zero();
  cc.friction = contact.friction;
  cc.count = contact.manifold.count;
  const float mSum = cc.invMassA + cc.invMassB;

  const Vec3 pA = bodies.xf[a].p, pB = bodies.xf[b].p;
  const Vec3 vA = bodies.v[a], wA = bodies.w[a], vB = bodies.v[b], wB = bodies.w[b];
  const float invDt = 1.0f / p.dt;

  // The normal rows, all four points at once (see RowVectors). Points past the count have a zero
  // normal, which makes every field of their rows zero except the mass, masked below.
  F4 px{}, py{}, pz{}, nx{}, ny{}, nz{}, depth{}, warm{};
  for (int i = 0; i < cc.count; ++i) {
    const ContactPoint& mp = contact.manifold.points[i];
    px[i] = mp.position.x() + shift.x();
    py[i] = mp.position.y() + shift.y();
    pz[i] = mp.position.z() + shift.z();
    nx[i] = mp.normal.x();
    ny[i] = mp.normal.y();
    nz[i] = mp.normal.z();
    depth[i] = mp.depth;
    warm[i] = contact.normalImpulse[i];
  }
  const F4 ax = px - pA.x(), ay = py - pA.y(), az = pz - pA.z();
  const F4 bx = px - pB.x(), by = py - pB.y(), bz = pz - pB.z();
  const Lanes3 rAxn{ay * nz - az * ny, az * nx - ax * nz, ax * ny - ay * nx};
  const Lanes3 rBxn{by * nz - bz * ny, bz * nx - bx * nz, bx * ny - by * nx};
  const Lanes3 iAn = times(iA, rAxn), iBn = times(iB, rBxn);
  storeRows(cc.normal, {nx, ny, nz});
  storeRows(cc.rAxn, rAxn);
  storeRows(cc.rBxn, rBxn);
  storeRows(cc.iAn, iAn);
  storeRows(cc.iBn, iBn);
  const simd4::I4 used = simd4::I4{0, 1, 2, 3} < cc.count;
  const F4 k = mSum + dot(rAxn, iAn) + dot(rBxn, iBn);
  store(cc.normalMass, used & (k > 0.0f) ? 1.0f / k : F4{});

  // Main sweeps: close a speculative gap exactly, push penetration beyond the slop out
  // (Baumgarte, no faster than maxPushVelocity). Relax sweeps (after positions moved): no
  // push-out, so it does not become kinetic energy; a contact that pushed this step and was
  // approached fast enough bounces, from where it now is.
  const Vec3 dv = vB - vA;
  const F4 vn = nx * dv.x() + ny * dv.y() + nz * dv.z() + (rBxn.x * wB.x() + rBxn.y * wB.y() + rBxn.z * wB.z()) -
                (rAxn.x * wA.x() + rAxn.y * wA.y() + rAxn.z * wA.z());
  const F4 speculative = depth < 0.0f ? depth * invDt : F4{};  // approach by the gap, no faster
  const F4 excess = simd4::clampNonNegative(depth - p.slop) * (p.beta * invDt);
  const F4 push = excess < p.maxPushVelocity ? excess : F4{} + p.maxPushVelocity;
  // A pinched body's push-outs oppose each other and cannot all be met; their impulses would grow
  // sweep after sweep and, warm started, step after step, until the body left at any speed.
  store(cc.bias, depth < 0.0f ? -speculative : (contact.pinched ? F4{} : -push));
  store(cc.restitutionBias,
        contact.restitution > 0.0f ? (vn < -p.restitutionThreshold ? contact.restitution * vn : F4{}) : F4{});
  store(cc.normalImpulse, p.warmStart && !contact.pinched ? warm : F4{});

  for (int r = 0; r <= ContactConstraint::kRows; ++r) cc.delta[r] = cc.direction[r] = 0.0f;
  cc.blockExact = false;

  // Friction at the centre of the points, about the mean normal. Its three rows are built at once,
  // one lane each (tangent 1, tangent 2, twist), as the sweep reads them.
  store(cc.frictionBias, F4{});
  if (cc.count == 0) return;
  const float invCount = 1.0f / float(cc.count);
  const Vec3 centre(simd4::laneSum(px) * invCount, simd4::laneSum(py) * invCount, simd4::laneSum(pz) * invCount);
  const Vec3 normalSum(simd4::laneSum(nx), simd4::laneSum(ny), simd4::laneSum(nz));
  const Vec3 n = normalSum.squaredNorm() > 1e-12f ? Vec3(normalSum.normalized()) : contact.manifold.points[0].normal;
  Vec3 t1, t2;
  orthonormalBasis(n, t1, t2);
  const Vec3 rA = centre - pA, rB = centre - pB;
  // Static friction anchor (Contact::anchorA/B): the tangential drift of the two material points,
  // pulled back like penetration (Baumgarte, capped) in the main sweeps. Velocity-level friction
  // never undoes a slow slide, and friction-held structures crept apart over long runs.
  F4 anchorBias{};
  if (contact.anchored && p.frictionAnchors) {
    const Vec3 drift = bodies.xf[b].apply(contact.anchorB) - bodies.xf[a].apply(contact.anchorA);
    const float k = p.beta * invDt, cap = p.maxPushVelocity;
    auto pull = [&](float d) {
      return std::clamp(k * std::copysign(std::max(std::fabs(d) - p.anchorSlop, 0.0f), d), -cap, cap);
    };
    anchorBias[0] = pull(drift.dot(t1));
    anchorBias[1] = pull(drift.dot(t2));
  }
  store(cc.frictionBias, anchorBias);
  const F4 tx{t1.x(), t2.x(), 0.0f, 0.0f}, ty{t1.y(), t2.y(), 0.0f, 0.0f}, tz{t1.z(), t2.z(), 0.0f, 0.0f};
  // Angular parts: r × t for the tangent rows, the normal itself for the twist.
  const simd4::I4 twistLane = simd4::I4{0, 1, 2, 3} == 2;
  auto angular = [&](const Vec3& r) {
    return Lanes3{twistLane ? F4{} + n.x() : r.y() * tz - r.z() * ty, twistLane ? F4{} + n.y() : r.z() * tx - r.x() * tz,
                  twistLane ? F4{} + n.z() : r.x() * ty - r.y() * tx};
  };
  const Lanes3 lin{tx, ty, tz}, aA = angular(rA), aB = angular(rB);
  const Lanes3 invA = times(iA, aA), invB = times(iB, aB);
  storeRows(cc.frictionLinear, lin);
  storeRows(cc.frictionAngularA, aA);
  storeRows(cc.frictionAngularB, aB);
  storeRows(cc.frictionInverseA, invA);
  storeRows(cc.frictionInverseB, invB);
  // The rows' coupling K (the tangents are orthonormal and the twist has no linear part, so the
  // linear term adds mSum on the tangents' diagonal only): the diagonal lane by lane, and with the
  // inverse parts turned by one lane, K01 (lane 0), K12 (lane 1) and K20 (lane 2).
  const F4 diag = mSum * dot(lin, lin) + dot(aA, invA) + dot(aB, invB);
  auto turned = [](const Lanes3& v) {
    const simd4::I4 turn{1, 2, 0, 3};
    return Lanes3{__builtin_shuffle(v.x, turn), __builtin_shuffle(v.y, turn), __builtin_shuffle(v.z, turn)};
  };
  const F4 offDiag = dot(aA, turned(invA)) + dot(aB, turned(invB));
  // The two tangent rows share lever arms, so they couple: solve them as a 2x2 block.
  const float k11 = diag[0], k22 = diag[1], k12 = offDiag[0];
  const float det = k11 * k22 - k12 * k12;
  if (det > 1e-12f * std::max(1.0f, k11 * k22)) {
    const float inv = 1.0f / det;
    cc.tangentMass[0][0] = k22 * inv;
    cc.tangentMass[1][1] = k11 * inv;
    cc.tangentMass[0][1] = cc.tangentMass[1][0] = -k12 * inv;
  } else {
    cc.tangentMass[0][0] = cc.tangentMass[1][1] = cc.tangentMass[0][1] = cc.tangentMass[1][0] = 0.0f;
  }
  const float kt = diag[2];
  cc.twistMass = kt > 0.0f ? 1.0f / kt : 0.0f;
  // The sweep solves the twist first and reads all three rows' velocities before it; the tangent
  // rows then see the twist's impulse through these couplings, as if applied in between.
  cc.twistCoupling[0] = offDiag[2];  // K20 = K02 (I⁻¹ is symmetric)
  cc.twistCoupling[1] = offDiag[1];
  // The points' coordinates in the contact plane about the centre (zero past the count).
  const F4 cx = px - centre.x(), cy = py - centre.y(), cz = pz - centre.z();
  const F4 s = used ? cx * t1.x() + cy * t1.y() + cz * t1.z() : F4{};
  const F4 t = used ? cx * t2.x() + cy * t2.y() + cz * t2.z() : F4{};
  // Twist friction of a contact patch: μ·N times the mean distance from the centre of the patch
  // the points bound, pressed evenly (a square of side s: 0.383 s). The points are its corners, so
  // their own distance overstates it: a box spun flat on the floor stopped 1.85× too soon. The RMS
  // corner distance times kPatchMeanRadius[count] is exact for a square, an equilateral triangle
  // and a segment (2 points), and within 8 % for any rectangle.
  static constexpr float kPatchMeanRadius[kMaxManifoldPoints + 1] = {0.0f, 0.0f, 0.5f, 0.46f, 0.541f};
  const F4 dist2 = used ? cx * cx + cy * cy + cz * cz : F4{};
  cc.twistRadius = kPatchMeanRadius[cc.count] * std::sqrt(simd4::laneSum(dist2) * invCount);
  cc.blockExact = prepareBlockInverse(s, t, cc);

  if (p.warmStart && !contact.pinched) {
    cc.frictionImpulse[0] = contact.frictionImpulse.dot(t1);
    cc.frictionImpulse[1] = contact.frictionImpulse.dot(t2);
    cc.frictionImpulse[2] = contact.twistImpulse * std::max(0.0f, contact.frictionNormal.dot(n));
  } else {
    cc.frictionImpulse[0] = cc.frictionImpulse[1] = cc.frictionImpulse[2] = 0.0f;
  }
  cc.frictionImpulse[3] = 0.0f;
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
  return f * (len2 > 0.0f ? limit / std::sqrt(len2) : 0.0f);
}

// f clamped to [−maxTwist, maxTwist] lane by lane, as std::clamp.
inline F4 clampTwist(F4 f, F4 maxTwist) { return f > maxTwist ? maxTwist : (f < -maxTwist ? -maxTwist : f); }

// Lanes 0 and 1 of the tangent impulses, lanes 2 and 3 of the twist impulses.
inline F4 joinFriction(F4 tangent, F4 twist) { return __builtin_shuffle(tangent, twist, simd4::I4{0, 1, 6, 7}); }

}  // namespace

namespace {

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
inline void applyToBodies(BodyStore& bodies, const ContactConstraint& c, F4 dn, F4 df) {
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
  if (useBias) return load(c.bias);
  const F4 bounce = load(c.restitutionBias);
  return (bounce < 0.0f) & (load(c.normalImpulse) > 0.0f) ? bounce : simd4::clampNonNegative(load(c.bias));
}

}  // namespace

void reaimForRelax(const BodyStore& bodies, const Contact& contact, const SolverParams& p, ContactConstraint& cc) {
  if (cc.count == 0 || !cc.dynA || !cc.dynB) return;  // one side immovable: its lever does not matter
  const Vec3 moveA = p.dt * bodies.v[cc.a], moveB = p.dt * bodies.v[cc.b];
  if ((moveB - moveA).squaredNorm() < kReaimTravel * kReaimTravel) return;
  // A pair pushed apart (overlapping beyond the slop) moves by its push-out, not by a collision.
  for (int i = 0; i < cc.count; ++i)
    if (cc.bias[i] < 0.0f) return;
  const Vec3 shift = 0.5f * (moveA + moveB);
  alignas(16) float normal[kMaxManifoldPoints], bias[kMaxManifoldPoints], bounce[kMaxManifoldPoints], friction[4],
      frictionBias[4];
  std::copy_n(cc.normalImpulse, kMaxManifoldPoints, normal);
  std::copy_n(cc.bias, kMaxManifoldPoints, bias);
  std::copy_n(cc.restitutionBias, kMaxManifoldPoints, bounce);
  std::copy_n(cc.frictionImpulse, 4, friction);
  std::copy_n(cc.frictionBias, 4, frictionBias);
  prepareContact(bodies, contact, cc.contact, p, cc, shift);
  std::copy_n(normal, kMaxManifoldPoints, cc.normalImpulse);
  std::copy_n(bias, kMaxManifoldPoints, cc.bias);
  std::copy_n(bounce, kMaxManifoldPoints, cc.restitutionBias);
  std::copy_n(friction, 4, cc.frictionImpulse);
  std::copy_n(frictionBias, 4, cc.frictionBias);
}

void warmStart(BodyStore& bodies, const ContactConstraint* cs, size_t n) {
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
  float lambda[kMaxManifoldPoints];
  store(lambda, start);
  if (c.count == 1) {
    // One row (a sphere, a vertex): one projected step, no coupling to follow.
    lambda[0] = std::max(0.0f, lambda[0] - omega * c.normalMass[0] * (vn[0] + bias[0]));
  } else {
    float K[kMaxManifoldPoints][kMaxManifoldPoints];
    normalCoupling(c, K);
    for (int pass = 0; pass < kManifoldNormalPasses; ++pass) {
      bool moved = false;
      for (int i = 0; i < c.count; ++i) {
        const float old = lambda[i];
        lambda[i] = std::max(0.0f, old - omega * c.normalMass[i] * (vn[i] + bias[i]));
        const float d = lambda[i] - old;
        if (d == 0.0f) continue;
        moved = true;
        vn += load(K[i]) * d;  // K is symmetric: row i is column i
      }
      if (!moved) break;  // a pass that changed nothing ends the block solve (separated contacts: at once)
    }
  }
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

// The parts of a sweep, inlined into solveIteration's loop (the exported functions below wrap them
// for the chain solver): called out of line, large_pyramid's sweeps took 7% longer.
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
  const F4 vt = vf + tc * twistApplied + (useBias ? load(c.frictionBias) : F4{});
  const F4 m = load(&c.tangentMass[0][0]);  // m00, m01, m10, m11
  const F4 tangent = old - omega * (__builtin_shuffle(m, simd4::I4{0, 2, 0, 2}) * splat<0>(vt) +
                                    __builtin_shuffle(m, simd4::I4{1, 3, 1, 3}) * splat<1>(vt));
  // Lane 3 is the twist's lane 3, which is 0 (row 3 is zero).
  const F4 next = joinFriction(ontoFrictionCircle(tangent, simd4::lane<0>(limit)), twist);
  const F4 applied = next - old;
  store(c.frictionImpulse, next);
  store(c.delta + kMaxManifoldPoints, applied);
  applyImpulses(c, frictionImpulses(c, applied), va, wa, vb, wb);
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
  frictionRows(c, a, b, d, e, omega, useBias);
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

template <bool Restart, bool MeasureChange>
SweepResult sweep(BodyStore& bodies, ContactConstraint* cs, size_t n, float omega, bool useBias) {
  float residual = 0.0f;
  double change = 0.0;
  for (size_t k = 0; k < n; ++k) {
    ContactConstraint& c = cs[k];
    if constexpr (Restart) restartDirectionOf(c);
    if (c.count == 0) continue;
    // Static and kinematic bodies are read (their velocity is given) but never written, so
    // islands that share a static body can be solved concurrently.
    F4 va = load3(bodies.v[c.a]), wa = load3(bodies.w[c.a]), vb = load3(bodies.v[c.b]), wb = load3(bodies.w[c.b]);
    // Friction first; normal rows last: non-penetration matters more than friction, so each sweep
    // ends with the normal rows satisfied (see solveNormalBlock).
    frictionRows(c, va, wa, vb, wb, omega, useBias);
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
  return {residual, change};
}

}  // namespace

SweepResult solveIteration(BodyStore& bodies, ContactConstraint* cs, size_t n, float omega, bool useBias,
                           bool restartDirection, bool measureChange) {
  // A restarted direction is always followed by a momentum step, which needs the change.
  if (restartDirection) return sweep<true, true>(bodies, cs, n, omega, useBias);
  return measureChange ? sweep<false, true>(bodies, cs, n, omega, useBias)
                       : sweep<false, false>(bodies, cs, n, omega, useBias);
}

void startDirection(ContactConstraint* cs, size_t n) {
  for (size_t k = 0; k < n; ++k) restartDirectionOf(cs[k]);
}

void accelerate(BodyStore& bodies, ContactConstraint* cs, size_t n, float beta) {
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
    const F4 nextFriction = joinFriction(ontoFrictionCircle(step, limit), clampTwist(step, F4{} + limit * c.twistRadius));
    store(c.frictionImpulse, nextFriction);
    applyToBodies(bodies, c, next - old, nextFriction - oldFriction);
    store(d, beta * dn + load(c.delta));
    store(d + kMaxManifoldPoints, beta * df + load(c.delta + kMaxManifoldPoints));
  }
}

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
      continue;
    }
    for (int i = 0; i < c.count; ++i) ct.normalImpulse[i] = c.normalImpulse[i];
    if (c.count == 0) continue;
    ct.frictionImpulse = c.frictionImpulse[0] * c.tangent1() + c.frictionImpulse[1] * c.tangent2();
    ct.twistImpulse = c.frictionImpulse[2];
    ct.frictionNormal = c.twistAxis();
    // Friction at its limit slides: the anchor lets go and is set anew where the pair next sticks.
    const float limit = c.friction * simd4::laneSum(load(c.normalImpulse));
    const float t1 = c.frictionImpulse[0], t2 = c.frictionImpulse[1];
    if (t1 * t1 + t2 * t2 >= kAnchorRelease * kAnchorRelease * limit * limit) ct.anchored = false;
  }
}

}  // namespace haif
