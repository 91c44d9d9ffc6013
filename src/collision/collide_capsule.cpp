// Capsule against capsule: closest points of the two core segments. Nearly parallel overlapping
// capsules (lying side by side) get two points at the ends of the overlap, so they do not roll.
#include "collision/collide_pairs.h"
#include "collision/contact_buffer.h"
#include "collision/geometry.h"

namespace haif {
namespace detail {

int collideCapsuleCapsule(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                          Manifold& m) {
  m.count = 0;
  const Vec3 axA = xa.rotate(Vec3(0.0f, a.halfHeight, 0.0f));
  const Vec3 axB = xb.rotate(Vec3(0.0f, b.halfHeight, 0.0f));
  const Vec3 a0 = xa.p - axA, a1 = xa.p + axA, b0 = xb.p - axB, b1 = xb.p + axB;
  const float rr = a.radius + b.radius;
  float s, t;
  closestSegmentSegment(a0, a1, b0, b1, s, t);
  const Vec3 pa = a0 + s * (a1 - a0), pb = b0 + t * (b1 - b0);
  const Vec3 d = pb - pa;
  const float dist = d.norm();
  if (dist - rr > margin) return 0;

  Vec3 n;
  if (dist > 1e-6f) {
    n = d / dist;
  } else {
    // Axes intersect: push along their common perpendicular (or any perpendicular of A).
    const Vec3 c = axA.cross(axB);
    Vec3 t1, t2;
    orthonormalBasis(safeNormalize(axA, Vec3::UnitY()), t1, t2);
    n = safeNormalize(c, t1);
    if (n.dot(xb.p - xa.p) < 0.0f) n = -n;
  }

  // Parallel case: project B's segment on A's and keep the overlap ends.
  const float lenA2 = (a1 - a0).squaredNorm(), lenB2 = (b1 - b0).squaredNorm();
  if (lenA2 > 1e-12f && lenB2 > 1e-12f && dist > 1e-6f) {
    const Vec3 ua = (a1 - a0) / std::sqrt(lenA2), ub = (b1 - b0) / std::sqrt(lenB2);
    if (std::fabs(ua.dot(ub)) > 0.995f) {
      const float lenA = std::sqrt(lenA2);
      float t0 = (b0 - a0).dot(ua), t1 = (b1 - a0).dot(ua);
      if (t0 > t1) std::swap(t0, t1);
      const float lo = std::max(0.0f, t0), hi = std::min(lenA, t1);
      if (hi - lo > 1e-3f * lenA) {
        ContactBuffer buf;
        const float ends[2] = {lo, hi};
        for (int i = 0; i < 2; ++i) {
          const Vec3 qa = a0 + ends[i] * ua;
          const Vec3 qb = closestOnSegment(qa, b0, b1);
          const float di = (qb - qa).dot(n);  // distance of the axes along the shared normal
          const float depth = rr - di;
          if (-depth > margin) continue;
          const Vec3 sa = qa + a.radius * n, sb = qb - b.radius * n;
          buf.add(0.5f * (sa + sb), n, depth, uint32_t(i + 1));
        }
        if (buf.count > 0) return writeManifold(buf, m);
      }
    }
  }
  const Vec3 sa = pa + a.radius * n, sb = pb - b.radius * n;
  return writeSingle(m, 0.5f * (sa + sb), n, rr - dist, 0);
}

}  // namespace detail
}  // namespace haif
