// Convex shape against a static triangle mesh. The BVH is queried with the convex's box in the mesh
// frame (grown by the margin); each triangle is a thin two-sided polyhedron collided with the generic
// routines; all candidates go to one stack buffer and are reduced to the 4 best.
#include "collision/collide_pairs.h"
#include "collision/geometry.h"
#include "collision/polytope.h"
#include "collision/triangle_mesh.h"

namespace haif {
namespace detail {

namespace {

// Mixes the triangle index into a per-triangle feature id: still stable step to step.
uint32_t meshId(uint32_t tri, uint32_t id) { return (id * 0x9E3779B1u) ^ (tri * 0x85EBCA77u) ^ (tri >> 7); }

// An edge is inactive when the neighbour across it is coplanar or bends upwards (concave): the
// surface has no real edge there, so contacts on it must not push sideways ("internal edge" bumps).
// Neighbours are found through the BVH, matching vertex positions (meshes need not be welded).
bool edgeInactive(const TriangleMesh& mesh, uint32_t tri, const Vec3& a, const Vec3& b, const Vec3& n) {
  Aabb box;
  box.include(a);
  box.include(b);
  const float tol2 = 1e-10f * std::max(1.0f, (b - a).squaredNorm());
  bool inactive = false;
  queryMeshTriangles(mesh, box.expanded(1e-5f), [&](uint32_t o) {
    if (o == tri || inactive) return;
    int shared = 0, other = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = mesh.vertices[mesh.indices[3 * o + uint32_t(k)]];
      if ((v - a).squaredNorm() <= tol2 || (v - b).squaredNorm() <= tol2) ++shared;
      else other = k;
    }
    if (shared != 2 || other < 0) return;
    const Vec3 w = mesh.vertices[mesh.indices[3 * o + uint32_t(other)]] - a;
    if (n.dot(w) >= -1e-3f * w.norm()) inactive = true;
  });
  return inactive;
}

// Adds a candidate unless one at the same place with the same normal exists (two triangles sharing
// an edge report the same contact twice); the deeper one is kept.
void addUnique(ContactBuffer& buf, const Vec3& p, const Vec3& n, float depth, uint32_t id) {
  for (int i = 0; i < buf.count; ++i) {
    ContactCandidate& c = buf.pts[i];
    if ((c.position - p).squaredNorm() < 1e-8f && c.normal.dot(n) > 0.999f) {
      if (depth > c.depth) c = ContactCandidate{p, n, depth, id};
      return;
    }
  }
  buf.add(p, n, depth, id);
}

}  // namespace

int collideMeshConvex(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                      Manifold& m) {
  m.count = 0;
  if (b.type == ShapeType::TriangleMesh || b.type == ShapeType::Plane) return 0;
  const TriangleMesh& mesh = *a.mesh;
  const Transform rel = xa.inverseTimes(xb);  // convex in the mesh frame
  const Aabb query = computeAabb(b, rel).expanded(margin);

  // Convex-side data that does not change per triangle.
  Vec3 c0 = xb.p, c1 = xb.p;
  if (b.type == ShapeType::Capsule) {
    const Vec3 axis = xb.rotate(Vec3(0.0f, b.halfHeight, 0.0f));
    c0 = xb.p - axis;
    c1 = xb.p + axis;
  }
  const BoxPoly box(b.type == ShapeType::Box ? b.halfExtents : Vec3::Constant(0.5f));
  const PolyView convex = b.type == ShapeType::Box ? box.view()
                          : b.type == ShapeType::ConvexHull ? hullView(*b.hull)
                                                            : PolyView{};

  ContactBuffer buf;
  queryMeshTriangles(mesh, query, [&](uint32_t tri) {
    const Vec3& v0 = mesh.vertices[mesh.indices[3 * tri]];
    const Vec3& v1 = mesh.vertices[mesh.indices[3 * tri + 1]];
    const Vec3& v2 = mesh.vertices[mesh.indices[3 * tri + 2]];
    const TrianglePoly tp(v0, v1, v2);
    if (tp.degenerate()) return;
    const Vec3& tn = tp.f[0].normal;
    // One-sided: a shape whose centre is behind the triangle belongs to the other side of the surface.
    if (tn.dot(rel.p) - tp.f[0].offset < 0.0f) return;
    Manifold tm;
    switch (b.type) {
      case ShapeType::Sphere: collideCorePoly(c0, c0, b.radius, tp.view(), xa, margin, tm); break;
      case ShapeType::Capsule: collideCorePoly(c0, c1, b.radius, tp.view(), xa, margin, tm); break;
      default: collidePolyPoly(tp.view(), xa, convex, xb, margin, tm); break;
    }
    const Vec3 tnWorld = xa.rotate(tn);
    const Vec3 ev[3] = {v0, v1, v2};
    for (int i = 0; i < tm.count; ++i) {
      ContactPoint& p = tm.points[i];
      if (p.normal.dot(tnWorld) < 0.9999f) {
        // Where is the contact on the triangle? Inside the face, or on which edges (two: a vertex).
        const Vec3 onTri = xa.applyInverse(p.position + (0.5f * p.depth) * p.normal);
        bool onEdge = false, activeEdge = false;
        for (int k = 0; k < 3 && !activeEdge; ++k) {
          const Vec3& a = ev[k];
          const Vec3& b = ev[(k + 1) % 3];
          const float d = (b - a).normalized().cross(onTri - a).dot(tn);  // in-plane distance inside edge k
          if (d > 1e-3f) continue;
          onEdge = true;
          activeEdge = !edgeInactive(mesh, tri, a, b, tn);
        }
        // On an internal edge or vertex: the neighbouring triangle reports the true contact, a sideways
        // push from here would only be a bump.
        if (onEdge && !activeEdge) continue;
        if (!onEdge) {
          // Inside the face region the face normal is the true one: re-express the contact along it,
          // from the convex's surface point.
          const Vec3 pB = p.position - (0.5f * p.depth) * p.normal;
          const float depth = -(tn.dot(xa.applyInverse(pB)) - tp.f[0].offset);
          if (depth < -margin) continue;
          p.position = pB + (0.5f * depth) * tnWorld;
          p.normal = tnWorld;
          p.depth = depth;
        }
      }
      addUnique(buf, p.position, p.normal, p.depth, meshId(tri, p.id));
    }
  });
  return writeManifold(buf, m);
}

}  // namespace detail
}  // namespace haif
