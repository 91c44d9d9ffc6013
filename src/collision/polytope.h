// A read-only view of a convex polyhedron (vertices, polygon faces, edges) so that boxes, hulls and
// mesh triangles share one separating-axis and clipping implementation. Boxes and triangles build
// their few vertices and faces on the stack; hulls point at their own arrays.
#pragma once

#include "collision/contact_buffer.h"
#include "collision/manifold.h"
#include "collision/shape.h"

#include <cstdint>
#include <utility>

namespace haif {
namespace detail {

struct PolyView {
  const Vec3* verts = nullptr;
  int numVerts = 0;
  const ConvexHull::Face* faces = nullptr;
  int numFaces = 0;
  const uint32_t* faceVerts = nullptr;
  const std::pair<uint32_t, uint32_t>* edges = nullptr;
  int numEdges = 0;
  /// The first numAxisEdges edges have distinct directions and cover every edge's direction. The
  /// separating-axis test only needs them: parallel edges give the same axis (a box: 3 of 12).
  int numAxisEdges = 0;
  /// A triangle: its two faces are the same plane, so the faces alone do not bound a solid.
  bool flat = false;
  /// The two faces beside each of the numEdges edges, or null (then every edge direction is tried).
  const std::pair<uint32_t, uint32_t>* edgeFaces = nullptr;
  /// Some edge runs along another (ConvexHull::parallelEdges); a box's do.
  bool parallelEdges = true;
  /// The vertices by coordinate (ConvexHull::vertexLanes), or null: made per pair where needed.
  const float* vertexLanes = nullptr;

  /// Smallest and largest projection of the vertices on d.
  void interval(const Vec3& d, float& lo, float& hi) const {
    lo = hi = verts[0].dot(d);
    for (int i = 1; i < numVerts; ++i) {
      const float x = verts[i].dot(d);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  float minDot(const Vec3& d) const {
    float lo = verts[0].dot(d);
    for (int i = 1; i < numVerts; ++i) lo = std::min(lo, verts[i].dot(d));
    return lo;
  }
  const Vec3& faceVertex(int f, int k) const { return verts[faceVerts[faces[f].first + uint32_t(k)]]; }
};

/// Box with half extents h as a polyhedron (vertex i has +x when bit 0 is set, +y bit 1, +z bit 2).
struct BoxPoly {
  Vec3 v[8];
  ConvexHull::Face f[6];
  explicit BoxPoly(const Vec3& h);
  PolyView view() const;
};

/// Triangle (a, b, c), CCW seen from the front, as a two-sided flat polyhedron: face 0 is the front.
struct TrianglePoly {
  Vec3 v[3];
  ConvexHull::Face f[2];
  TrianglePoly(const Vec3& a, const Vec3& b, const Vec3& c);
  bool degenerate() const { return f[0].normal.squaredNorm() < 0.5f; }
  PolyView view() const;
};

PolyView hullView(const ConvexHull& h);

/// Two polyhedra, A at xa and B at xb: SAT over face normals and edge-pair cross products, then face
/// clipping or one edge-edge point. Normals from A to B. Writes the reduced manifold, returns its count.
int collidePolyPoly(const PolyView& A, const Transform& xa, const PolyView& B, const Transform& xb, float margin,
                    Manifold& m);

/// A rounded core (segment c0-c1 in world space, c0 == c1 for a sphere, radius r) against polyhedron P
/// at xp. Normals point from P towards the core. Writes the manifold, returns its count.
int collideCorePoly(const Vec3& c0, const Vec3& c1, float r, const PolyView& P, const Transform& xp, float margin,
                    Manifold& m);

inline void flipNormals(Manifold& m) {
  for (int i = 0; i < m.count; ++i) m.points[i].normal = -m.points[i].normal;
}

}  // namespace detail
}  // namespace haif
