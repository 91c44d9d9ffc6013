// Polyhedron views of boxes, triangles and hulls (see polytope.h).
#include "collision/polytope.h"

namespace haif {
namespace detail {

namespace {
// Box topology: faces CCW seen from outside, in the order -x, +x, -y, +y, -z, +z.
constexpr uint32_t kBoxFaceVerts[24] = {0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4, 2, 6, 7, 3, 0, 2, 3, 1, 4, 5, 7, 6};
// One edge along x, y and z first (the axis edges), then the other nine.
constexpr std::pair<uint32_t, uint32_t> kBoxEdges[12] = {{0, 1}, {0, 2}, {0, 4}, {2, 3}, {4, 5}, {6, 7},
                                                         {1, 3}, {4, 6}, {5, 7}, {1, 5}, {2, 6}, {3, 7}};
// The faces beside each edge of kBoxEdges (vertex i has x, y, z from bits 0, 1, 2).
constexpr std::pair<uint32_t, uint32_t> kBoxEdgeFaces[12] = {{2, 4}, {0, 4}, {0, 2}, {3, 4}, {2, 5}, {3, 5},
                                                             {1, 4}, {0, 5}, {1, 5}, {1, 2}, {0, 3}, {1, 3}};
constexpr uint32_t kTriFaceVerts[6] = {0, 1, 2, 0, 2, 1};
constexpr std::pair<uint32_t, uint32_t> kTriEdges[3] = {{0, 1}, {1, 2}, {2, 0}};
}  // namespace

BoxPoly::BoxPoly(const Vec3& h) {
  for (int i = 0; i < 8; ++i) v[i] = Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  for (int a = 0; a < 3; ++a) {
    for (int s = 0; s < 2; ++s) {
      ConvexHull::Face& face = f[a * 2 + s];
      face.normal = (s ? 1.0f : -1.0f) * Vec3::Unit(a);
      face.offset = h[a];
      face.first = uint32_t((a * 2 + s) * 4);
      face.count = 4;
    }
  }
}

PolyView BoxPoly::view() const {
  PolyView p;
  p.verts = v;
  p.numVerts = 8;
  p.faces = f;
  p.numFaces = 6;
  p.faceVerts = kBoxFaceVerts;
  p.edges = kBoxEdges;
  p.numEdges = 12;
  p.numAxisEdges = 3;
  p.edgeFaces = kBoxEdgeFaces;
  return p;
}

TrianglePoly::TrianglePoly(const Vec3& a, const Vec3& b, const Vec3& c) {
  v[0] = a;
  v[1] = b;
  v[2] = c;
  const Vec3 n = (b - a).cross(c - a);
  const float len = n.norm();
  const Vec3 un = len > 1e-12f ? Vec3(n / len) : Vec3::Zero();
  f[0] = ConvexHull::Face{un, un.dot(a), 0, 3};
  f[1] = ConvexHull::Face{-un, -un.dot(a), 3, 3};
}

PolyView TrianglePoly::view() const {
  PolyView p;
  p.verts = v;
  p.numVerts = 3;
  p.faces = f;
  p.numFaces = 2;
  p.faceVerts = kTriFaceVerts;
  p.edges = kTriEdges;
  p.numEdges = 3;
  p.numAxisEdges = 3;
  p.flat = true;
  return p;
}

PolyView hullView(const ConvexHull& h) {
  PolyView p;
  p.verts = h.vertices.data();
  p.numVerts = int(h.vertices.size());
  p.faces = h.faces.data();
  p.numFaces = int(h.faces.size());
  p.faceVerts = h.faceVertices.data();
  p.edges = h.edges.data();
  p.numEdges = int(h.edges.size());
  p.numAxisEdges = int(h.axisEdges);
  if (h.edgeFaces.size() == h.edges.size()) p.edgeFaces = h.edgeFaces.data();
  p.parallelEdges = h.parallelEdges;
  if (h.vertexLanes.size() == 3 * size_t(ConvexHull::vertexLaneCount(h.vertices.size())))
    p.vertexLanes = h.vertexLanes.data();
  return p;
}

}  // namespace detail
}  // namespace haif
