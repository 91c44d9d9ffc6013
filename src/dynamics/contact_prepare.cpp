// A contact's solver rows, built once per step from the body state (prepareContact), with the exact
// inverse of its normal block, and built again about a moved point before the relax sweeps
// (reaimForRelax).
#include "dynamics/contact_solver.h"
#include "dynamics/friction_patch.h"

#include "core/simd4.h"

#include <algorithm>
#include <cmath>

namespace haif {

using simd4::F4;
using simd4::load;
using simd4::store;

// The block inverse lives beside prepareContact, which inlines it: compiled out of line, it gave
// results different in the last bits, and other state hashes.
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
  double direction[2];
  const int rank = spreadRank(css, ctt, cst, m, singlePlaceSpread(cc), direction);
  if (rank < 2) return false;  // all points in one place
  float K[kMaxManifoldPoints][kMaxManifoldPoints];
  normalCoupling(cc, K);
  auto& G = cc.blockInverse;
  if (rank == 3) return patchBlockInverse(K, Bc, G);
  // A line: [1, the coordinate along it].
  const D4 along = direction[0] * Bc[1] + direction[1] * Bc[2];
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

// The centripetal acceleration of a turning kinematic body's surface at each point, along the normal
// into the dynamic body it touches (m/s², 0 where the surface turns away or nothing turns).
F4 turningLead(const BodyStore& bodies, const ContactConstraint& cc, const Vec3& pA, const Vec3& pB, const F4& px,
               const F4& py, const F4& pz, const F4& nx, const F4& ny, const F4& nz) {
  auto towards = [&](uint32_t body, const Vec3& centre, float side) {
    const Vec3 w = bodies.w[body];
    if (bodies.kind[body] != BodyKind::Kinematic || w.squaredNorm() == 0.0f) return F4{};
    // ω×(ω×r) = ω (ω·r) - |ω|² r
    const F4 rx = px - centre.x(), ry = py - centre.y(), rz = pz - centre.z();
    const F4 wr = rx * w.x() + ry * w.y() + rz * w.z();
    const float w2 = w.squaredNorm();
    const F4 ax = wr * w.x() - w2 * rx, ay = wr * w.y() - w2 * ry, az = wr * w.z() - w2 * rz;
    return simd4::clampNonNegative(side * (ax * nx + ay * ny + az * nz));
  };
  // The normal points from a to b: a's surface moves into b along +n, b's into a along -n.
  if (!cc.dynA) return towards(cc.a, pA, 1.0f);
  if (!cc.dynB) return towards(cc.b, pB, -1.0f);
  return F4{};
}

// A turning body's material point at r from its centre moves on an arc over the step, while the
// solve's rows and the centre's move are straight: the point ends (R(ω dt) - I) r - (ω×r) dt away
// from where its velocity says, this over dt (the Cayley turn of the integrator, t = |ω| dt / 2):
//   e = (½ dt ω×(ω×r) - t² ω×r) / (1 + t²),
// the pull towards the centre that holds a point on its circle.
Vec3 arcLag(const Vec3& w, const Vec3& r, float dt) {
  const float t2 = 0.25f * dt * dt * w.squaredNorm();
  const Vec3 wr = w.cross(r);
  return (0.5f * dt * w.cross(wr) - t2 * wr) / (1.0f + t2);
}

// The lag of a's contact point on b's (arcLag), where the pair turns as one: a box riding a turntable,
// a stack on it. Pairs that turn against each other (a ball rolling, a body tumbling onto another)
// keep no material point in contact, and get none.
constexpr float kArcLagFloor = 1e-8f;  // (|ω| dt / 2)² below which nothing turns (0.012 rad/s at 60 Hz)
constexpr float kCoTurning = 0.1f;     // most relative turning, as a fraction of the faster body's
Vec3 pairArcLag(const Vec3& wA, const Vec3& wB, const Vec3& rA, const Vec3& rB, float dt) {
  const float most = std::max(wA.squaredNorm(), wB.squaredNorm());
  if (0.25f * dt * dt * most < kArcLagFloor || (wB - wA).squaredNorm() > kCoTurning * kCoTurning * most)
    return Vec3::Zero();
  return arcLag(wB, rB, dt) - arcLag(wA, rA, dt);
}

// Below this relative speed (rad/s of turning, m/s of sliding) a pair is not rolling that way.
constexpr float kRollingAtRest = 1e-6f;
// Shortest vector that still gives a direction (a held impulse may be small).
constexpr float kAxisMinimum = 1e-12f;

// The rolling row (see ContactConstraint::rollingMass) in lane 3 of the friction rows: about the
// in-plane part of the pair's relative turning; when it does not turn, about the axis of the impulse
// it last held (a ball held on a slope), else the axis that rolling with its slide would turn
// about (n × v: the ball at the first step on a slope). Nothing to resist: no row.
[[gnu::noinline]] void prepareRollingRow(const Contact& contact, const Vec3& n, const Vec3& rA, const Vec3& rB, const Mat3& iA,
                       const Mat3& iB, const Vec3& vA, const Vec3& wA, const Vec3& vB, const Vec3& wB,
                       const SolverParams& p, ContactConstraint& cc) {
  auto inPlane = [&](const Vec3& v) -> Vec3 { return v - v.dot(n) * n; };
  Vec3 axis = inPlane(wB - wA);
  if (axis.norm() <= kRollingAtRest) {
    const Vec3 held = inPlane(contact.rollingImpulse);
    const Vec3 slide = n.cross(inPlane((vB + wB.cross(rB)) - (vA + wA.cross(rA))));
    axis = held.norm() > kAxisMinimum ? held : (slide.norm() > kRollingAtRest ? slide : Vec3::Zero());
  }
  const float length = axis.norm();
  if (!(length > kAxisMinimum)) return;
  axis /= length;
  const Vec3 invA = iA * axis, invB = iB * axis;
  const float k = axis.dot(invA) + axis.dot(invB);
  if (!(k > 0.0f)) return;
  cc.rollingMass = 1.0f / k;
  cc.frictionLinear.set(3, Vec3::Zero());
  cc.frictionAngularA.set(3, axis);
  cc.frictionAngularB.set(3, axis);
  cc.frictionInverseA.set(3, invA);
  cc.frictionInverseB.set(3, invB);
  cc.frictionImpulse[3] = p.warmStart && !contact.pinched ? contact.rollingImpulse.dot(axis) : 0.0f;
}

}  // namespace

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
  // Read as two 4 × 4 blocks (each point's first and second half) turned into lanes: gathered
  // point by point, each vector was put together from four stores and read back whole, which the
  // processor cannot forward (a tenth of prepare's time in many_pyramids).
  const simd4::I4 used = simd4::I4{0, 1, 2, 3} < cc.count;
  const ContactPoint* mp = contact.manifold.points;
  static_assert(sizeof(Vec3) == 12 && sizeof(ContactPoint) == 32, "a point is position, normal, depth, id");
  F4 px, py, pz, nx, ny, nz, depth, id;
  simd4::transpose(load(mp[0].position.data()), load(mp[1].position.data()), load(mp[2].position.data()),
                   load(mp[3].position.data()), px, py, pz, nx);
  simd4::transpose(load(mp[0].normal.data() + 1), load(mp[1].normal.data() + 1), load(mp[2].normal.data() + 1),
                   load(mp[3].normal.data() + 1), ny, nz, depth, id);
  (void)id;
  // Points past the count hold whatever an earlier manifold left there: zero, as documented above.
  px = used ? px + shift.x() : F4{};
  py = used ? py + shift.y() : F4{};
  pz = used ? pz + shift.z() : F4{};
  nx = used ? nx : F4{};
  ny = used ? ny : F4{};
  nz = used ? nz : F4{};
  depth = used ? depth : F4{};
  const F4 warm = used ? load(contact.normalImpulse) : F4{};
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
  const F4 k = mSum + dot(rAxn, iAn) + dot(rBxn, iBn);
  store(cc.normalMass, used & (k > 0.0f) ? 1.0f / k : F4{});

  // Main sweeps: close a speculative gap exactly, push penetration beyond the slop out
  // (Baumgarte, no faster than maxPushVelocity). Relax sweeps (after positions moved): no
  // push-out, so it does not become kinetic energy; a contact that pushed this step and was
  // approached fast enough bounces, from where it now is.
  const Vec3 dv = vB - vA;
  const F4 vn = nx * dv.x() + ny * dv.y() + nz * dv.z() + (rBxn.x * wB.x() + rBxn.y * wB.y() + rBxn.z * wB.z()) -
                (rAxn.x * wA.x() + rAxn.y * wA.y() + rAxn.z * wA.z());
  // approach by the gap, no faster; a pair placed hovering within the skin counts as touching
  const F4 speculative = contact.hovering ? F4{} : (depth < 0.0f ? depth * invDt : F4{});
  // A small body's slop is scaled down with it (haif/small_bodies.h): 5 mm is a bead's whole size.
  const F4 excess = simd4::clampNonNegative(depth - p.slop * contact.toleranceScale) * (p.beta * invDt);
  const F4 push = excess < p.maxPushVelocity ? excess : F4{} + p.maxPushVelocity;
  // A pinched body's push-outs oppose each other and cannot all be met; their impulses would grow
  // sweep after sweep and, warm started, step after step, until the body left at any speed.
  // A turning kinematic body's surface moves on an arc, not along its velocity: over the step it
  // comes ½ (ω×(ω×r))·n dt² further into what rests on it (2 mm a step at a drum's wall turning at
  // 6 m/s). Solved at the start of the step's normals, a pile riding the wall kept that depth every
  // step and sank through it; the lead asks the contact to open at that rate in every sweep.
  const F4 lead = turningLead(bodies, cc, pA, pB, px, py, pz, nx, ny, nz) * (0.5f * p.dt);
  store(cc.bias, (depth < 0.0f ? -speculative : (contact.pinched ? F4{} : -push)) - lead);
  const F4 bounce = contact.restitution > 0.0f ? (vn < -p.restitutionThreshold ? contact.restitution * vn : F4{}) : F4{};
  store(cc.restitutionBias, bounce < -lead ? bounce : -lead);
  store(cc.normalImpulse, p.warmStart && !contact.pinched ? warm : F4{});

  for (int r = 0; r <= ContactConstraint::kRows; ++r) cc.delta[r] = cc.direction[r] = 0.0f;
  cc.blockExact = false;
  cc.rollingMass = 0.0f;
  cc.rollingLever = p.rolling ? contact.rollingLever : 0.0f;

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
  // The friction patch: the points that touch (dynamics/friction_patch.h). Where all do, the same
  // lanes as the normals' and the same centre.
  const float nearest = simd4::laneMax(used ? depth : F4{} - 1e30f);
  const simd4::I4 patch = used & (depth >= frictionPatchFloor(nearest, contact.toleranceScale));
  const int patchCount = -(patch[0] + patch[1] + patch[2] + patch[3]);
  const F4 qx = patch ? px : F4{}, qy = patch ? py : F4{}, qz = patch ? pz : F4{};
  const float invPatch = 1.0f / float(patchCount);
  const Vec3 patchCentre = patchCount == cc.count ? centre
                                                  : Vec3(simd4::laneSum(qx) * invPatch, simd4::laneSum(qy) * invPatch,
                                                         simd4::laneSum(qz) * invPatch);
  const Vec3 rA = patchCentre - pA, rB = patchCentre - pB;
  // Static friction anchor (Contact::anchorA/B): the tangential drift of the two material points,
  // pulled back like penetration (at its own, gentler rate, capped) in the main sweeps.
  // Velocity-level friction never undoes a slow slide, and friction-held structures crept apart
  // over long runs.
  F4 anchorBias{};
  if (contact.anchored && p.frictionAnchors) {
    const Vec3 drift = bodies.xf[b].apply(contact.anchorB) - bodies.xf[a].apply(contact.anchorA);
    const float k = p.anchorBeta * invDt, cap = p.maxPushVelocity;
    auto pull = [&](float d) {
      return std::clamp(k * std::copysign(std::max(std::fabs(d) - p.anchorSlop, 0.0f), d), -cap, cap);
    };
    anchorBias[0] = pull(drift.dot(t1));
    anchorBias[1] = pull(drift.dot(t2));
  }
  // A sticking pair moves its two material points apart over the step where either body turns: its
  // velocities match, but the points' arcs do not follow them (arcLag). A box riding a turntable at
  // 1 rad/s, 3 m out, slid outwards at 0.025 m/s and off the edge within a minute. Every sweep aims
  // the friction at the points' chords instead, so positions follow the arcs. The relax sweeps keep
  // the aim too (lanes 2 and 3): what they took away the main sweeps had to pass up a stack again
  // every step, and a stack's upper boxes slid out at a fifth of the rate.
  const Vec3 lag = p.followArcs ? pairArcLag(wA, wB, rA, rB, p.dt) : Vec3::Zero();
  const float lag1 = lag.dot(t1), lag2 = lag.dot(t2);
  anchorBias[0] += lag1;
  anchorBias[1] += lag2;
  anchorBias[2] = lag1;
  anchorBias[3] = lag2;
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
  // Distances in the contact plane: a point 1 cm up the normal from another (a top's tip and its
  // axle's end above it) is not a patch 5 mm wide.
  const F4 ex = qx - patchCentre.x(), ey = qy - patchCentre.y(), ez = qz - patchCentre.z();
  const F4 es = ex * t1.x() + ey * t1.y() + ez * t1.z(), et = ex * t2.x() + ey * t2.y() + ez * t2.z();
  const F4 dist2 = patch ? es * es + et * et : F4{};
  cc.twistRadius = kPatchMeanRadius[patchCount] * std::sqrt(simd4::laneSum(dist2) * invPatch);
  cc.blockExact = prepareBlockInverse(s, t, cc);

  if (p.warmStart && !contact.pinched) {
    cc.frictionImpulse[0] = contact.frictionImpulse.dot(t1);
    cc.frictionImpulse[1] = contact.frictionImpulse.dot(t2);
    cc.frictionImpulse[2] = contact.twistImpulse * std::max(0.0f, contact.frictionNormal.dot(n));
  } else {
    cc.frictionImpulse[0] = cc.frictionImpulse[1] = cc.frictionImpulse[2] = 0.0f;
  }
  cc.frictionImpulse[3] = 0.0f;
  if (cc.rollingLever > 0.0f) prepareRollingRow(contact, n, rA, rB, iA, iB, vA, wA, vB, wB, p, cc);
}

// Relative travel (m) in a step beyond which a pair's rows are re-aimed for the relax sweeps
// (reaimForRelax): below it the two lever arms differ by less than the slop's fifth.
constexpr float kReaimTravel = 1e-3f;

bool wantsReaim(const Vec3* linear, const SolverParams& p, const ContactConstraint& cc) {
  if (cc.count == 0 || !cc.dynA || !cc.dynB) return false;  // one side immovable: its lever does not matter
  const Vec3 moveA = p.dt * linear[cc.a], moveB = p.dt * linear[cc.b];
  if ((moveB - moveA).squaredNorm() < kReaimTravel * kReaimTravel) return false;
  // A pair pushed apart (overlapping beyond the slop) moves by its push-out, not by a collision.
  for (int i = 0; i < cc.count; ++i)
    if (cc.bias[i] < 0.0f) return false;
  return true;
}

bool reaimForRelax(const BodyStore& bodies, const Vec3* linear, const Contact& contact, const SolverParams& p,
                   ContactConstraint& cc) {
  if (!wantsReaim(linear, p, cc)) return false;
  const Vec3 moveA = p.dt * linear[cc.a], moveB = p.dt * linear[cc.b];
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
  return true;
}

}  // namespace haif
