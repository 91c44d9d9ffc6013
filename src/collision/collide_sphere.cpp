// Sphere against sphere, box and capsule: closed-form closest points, one contact each.
#include "collision/collide_pairs.h"
#include "collision/contact_buffer.h"
#include "collision/geometry.h"

namespace haif {
namespace detail {

namespace {

// Two spheres (centres ca, cb) after the closest features were reduced to points.
int spherePoint(const Vec3& ca, float ra, const Vec3& cb, float rb, float margin, const Vec3& fallback, Manifold& m) {
  const Vec3 d = cb - ca;
  const float dist2 = d.squaredNorm();
  const float reach = ra + rb + margin;
  if (dist2 > reach * reach) return 0;
  const float dist = std::sqrt(dist2);
  // Coincident centres: any direction is as good; the caller passes one that is stable.
  const Vec3 n = dist > 1e-6f ? Vec3(d / dist) : fallback;
  const float depth = ra + rb - dist;
  const Vec3 pa = ca + ra * n, pb = cb - rb * n;
  return writeSingle(m, 0.5f * (pa + pb), n, depth, 0);
}

}  // namespace

int collideSphereSphere(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                        Manifold& m) {
  return spherePoint(xa.p, a.radius, xb.p, b.radius, margin, Vec3::UnitY(), m);
}

int collideSphereCapsule(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                         Manifold& m) {
  const Vec3 axis = xb.rotate(Vec3(0.0f, b.halfHeight, 0.0f));
  const Vec3 q = closestOnSegment(xa.p, xb.p - axis, xb.p + axis);
  // Sphere centre on the capsule axis: push sideways, perpendicular to the axis.
  Vec3 t1, t2;
  orthonormalBasis(safeNormalize(axis, Vec3::UnitY()), t1, t2);
  return spherePoint(xa.p, a.radius, q, b.radius, margin, t1, m);
}

int collideSphereBox(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                     Manifold& m) {
  const Vec3 c = xb.applyInverse(xa.p);  // sphere centre in the box frame
  const Vec3& h = b.halfExtents;
  const float r = a.radius;
  const Vec3 q = c.cwiseMax(-h).cwiseMin(h);
  const Vec3 d = c - q;
  const float dist2 = d.squaredNorm();
  Vec3 nBox;     // box frame, from the box towards the sphere centre
  float sep;     // surface separation
  Vec3 qSurf;    // closest point on the box surface (box frame)
  uint32_t id;
  if (dist2 > 1e-12f) {
    if (dist2 > (r + margin) * (r + margin)) return 0;
    const float dist = std::sqrt(dist2);
    nBox = d / dist;
    sep = dist - r;
    qSurf = q;
    id = 1;
  } else {
    // Centre inside the box: leave through the nearest face.
    int axis = 0;
    float best = 1e30f;
    for (int i = 0; i < 3; ++i) {
      const float g = h[i] - std::fabs(c[i]);
      if (g < best) { best = g; axis = i; }
    }
    const float s = c[axis] >= 0.0f ? 1.0f : -1.0f;
    nBox = s * Vec3::Unit(axis);
    sep = -best - r;
    qSurf = c;
    qSurf[axis] = s * h[axis];
    id = 2 + uint32_t(axis);
  }
  // Normal from sphere (a) to box (b) is minus the outward box normal.
  const Vec3 n = xb.rotate(nBox);
  const Vec3 pBox = xb.apply(qSurf);
  const Vec3 pSphere = xa.p - r * n;
  return writeSingle(m, 0.5f * (pBox + pSphere), -n, -sep, id);
}

}  // namespace detail
}  // namespace haif
