// Pairs routed through the generic polyhedron code: anything against a hull, and capsule-box.
// The sphere or capsule is shape a here, so the normals from collideCorePoly (polyhedron to core)
// are flipped to run from a to b.
#include "collision/collide_pairs.h"
#include "collision/polytope.h"

namespace haif {
namespace detail {

namespace {

int coreAgainst(const Shape& core, const Transform& xc, const PolyView& P, const Transform& xp, float margin,
                Manifold& m) {
  Vec3 c0 = xc.p, c1 = xc.p;
  if (core.type == ShapeType::Capsule) {
    const Vec3 axis = xc.rotate(Vec3(0.0f, core.halfHeight, 0.0f));
    c0 = xc.p - axis;
    c1 = xc.p + axis;
  }
  collideCorePoly(c0, c1, core.radius, P, xp, margin, m);
  flipNormals(m);
  return m.count;
}

}  // namespace

int collideSphereHull(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                      Manifold& m) {
  return coreAgainst(a, xa, hullView(*b.hull), xb, margin, m);
}

int collideCapsuleHull(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                       Manifold& m) {
  return coreAgainst(a, xa, hullView(*b.hull), xb, margin, m);
}

int collideCapsuleBox(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                      Manifold& m) {
  const BoxPoly box(b.halfExtents);
  return coreAgainst(a, xa, box.view(), xb, margin, m);
}

int collideBoxHull(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                   Manifold& m) {
  const BoxPoly box(a.halfExtents);
  return collidePolyPoly(box.view(), xa, hullView(*b.hull), xb, margin, m);
}

int collideHullHull(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                    Manifold& m) {
  return collidePolyPoly(hullView(*a.hull), xa, hullView(*b.hull), xb, margin, m);
}

}  // namespace detail
}  // namespace haif
