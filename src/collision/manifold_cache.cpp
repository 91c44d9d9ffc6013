#include "collision/manifold_cache.h"

namespace haif {

void rememberManifold(const Manifold& m, const Transform& xa, const Transform& xb, ManifoldCache& cache) {
  const Vec3& n = m.points[0].normal;
  // Points along one normal only (a mesh contact's may differ; those are made every step).
  cache.valid = m.count > 0;
  for (int i = 1; i < m.count; ++i) cache.valid &= m.points[i].normal.dot(n) > 0.99999f;
  if (!cache.valid) return;
  cache.normalA = xa.rotateInverse(n);
  cache.normalB = xb.rotateInverse(n);
  for (int i = 0; i < m.count; ++i) {
    // position is midway between the surfaces; A's surface lies depth / 2 along the normal
    // (towards B) from it when they overlap, B's the same distance back.
    const ContactPoint& p = m.points[i];
    const Vec3 half = (0.5f * p.depth) * p.normal;
    cache.onA[i] = xa.applyInverse(p.position + half);
    cache.onB[i] = xb.applyInverse(p.position - half);
  }
}

bool refreshManifold(const ManifoldCache& cache, const Transform& xa, const Transform& xb,
                     const ManifoldReuseLimits& limits, Manifold& m) {
  if (!cache.valid || m.count == 0) return false;
  // Rotation matrices: ten rotations a manifold, cheaper as 3x3 products than as quaternion ones.
  const Mat3 ra = xa.q.toRotationMatrix(), rb = xb.q.toRotationMatrix();
  const Vec3 n = ra * cache.normalA;
  if (n.dot(rb * cache.normalB) < limits.turnCos) return false;
  // Every point is checked before any is written: a refused manifold stays as it was (the caller
  // carries its impulses over from it). The new fields are written in place, not through a copy of
  // the points: a point put together field by field and copied whole stalled store forwarding.
  Vec3 position[kMaxManifoldPoints];
  float depth[kMaxManifoldPoints];
  const float slide2 = limits.slide * limits.slide;
  for (int i = 0; i < m.count; ++i) {
    const Vec3 a = ra * cache.onA[i] + xa.p, b = rb * cache.onB[i] + xb.p;
    const Vec3 gap = a - b;
    depth[i] = gap.dot(n);
    if (depth[i] < -limits.margin || (gap - depth[i] * n).squaredNorm() > slide2) return false;
    position[i] = 0.5f * (a + b);
  }
  for (int i = 0; i < m.count; ++i) {
    m.points[i].position = position[i];
    m.points[i].normal = n;
    m.points[i].depth = depth[i];
  }
  return true;
}

}  // namespace haif
