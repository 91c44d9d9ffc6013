// Narrow-phase entry point: a constant table maps (type a, type b) to a pair routine written for
// one order; the other order calls it with the arguments swapped and flips the normals.
#include "collision/collide.h"

#include "collision/collide_pairs.h"

namespace haif {

namespace {

using detail::PairFn;
// The table covers the single shapes; compounds are taken apart before it (collide_compound.cpp).
constexpr int kTypes = int(ShapeType::Compound);

struct Entry {
  PairFn fn;
  bool swap;  ///< routine expects (b, a)
};

// Rows: type of a; columns: type of b. Order: Sphere, Box, Capsule, ConvexHull, TriangleMesh, Plane.
constexpr Entry kTable[kTypes][kTypes] = {
    // a = Sphere
    {{detail::collideSphereSphere, false}, {detail::collideSphereBox, false},
     {detail::collideSphereCapsule, false}, {detail::collideSphereHull, false},
     {detail::collideMeshConvex, true}, {detail::collidePlaneSphere, true}},
    // a = Box
    {{detail::collideSphereBox, true}, {detail::collideBoxBox, false}, {detail::collideCapsuleBox, true},
     {detail::collideBoxHull, false}, {detail::collideMeshConvex, true}, {detail::collidePlaneBox, true}},
    // a = Capsule
    {{detail::collideSphereCapsule, true}, {detail::collideCapsuleBox, false},
     {detail::collideCapsuleCapsule, false}, {detail::collideCapsuleHull, false},
     {detail::collideMeshConvex, true}, {detail::collidePlaneCapsule, true}},
    // a = ConvexHull
    {{detail::collideSphereHull, true}, {detail::collideBoxHull, true}, {detail::collideCapsuleHull, true},
     {detail::collideHullHull, false}, {detail::collideMeshConvex, true}, {detail::collidePlaneHull, true}},
    // a = TriangleMesh: static against static gives nothing
    {{detail::collideMeshConvex, false}, {detail::collideMeshConvex, false}, {detail::collideMeshConvex, false},
     {detail::collideMeshConvex, false}, {nullptr, false}, {nullptr, false}},
    // a = Plane
    {{detail::collidePlaneSphere, false}, {detail::collidePlaneBox, false}, {detail::collidePlaneCapsule, false},
     {detail::collidePlaneHull, false}, {nullptr, false}, {nullptr, false}},
};

bool shapeUsable(const Shape& s) {
  if (s.type == ShapeType::ConvexHull) return s.hull && !s.hull->vertices.empty() && !s.hull->faces.empty();
  if (s.type == ShapeType::TriangleMesh) return s.mesh && !s.mesh->nodes.empty();
  return int(s.type) < kTypes;
}

}  // namespace

int collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
            Manifold& manifold) {
  manifold.count = 0;
  if (a.type == ShapeType::Compound || b.type == ShapeType::Compound)
    return detail::collideCompound(a, xa, b, xb, margin, manifold);
  const int ta = int(a.type), tb = int(b.type);
  if (ta < 0 || ta >= kTypes || tb < 0 || tb >= kTypes) return 0;
  const Entry& e = kTable[ta][tb];
  if (!e.fn || !shapeUsable(a) || !shapeUsable(b)) return 0;
  if (!e.swap) return e.fn(a, xa, b, xb, margin, manifold);
  const int n = e.fn(b, xb, a, xa, margin, manifold);
  for (int i = 0; i < n; ++i) manifold.points[i].normal = -manifold.points[i].normal;
  return n;
}

}  // namespace haif
