// Collision shapes. A body owns exactly one shape, expressed in the body frame whose origin is
// the body's centre of mass (hull points and compound parts are re-centred when they are built).
// A compound (collision/compound.h) holds several convex shapes at poses: a body of many parts.
#pragma once

#include "core/aabb.h"
#include "core/math.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace haif {

enum class ShapeType : uint8_t { Sphere = 0, Box, Capsule, ConvexHull, TriangleMesh, Plane, Compound, Count };

struct CompoundShape;

const char* shapeTypeName(ShapeType t);

/// Convex polyhedron, built once from a point cloud (quickhull). Faces are planar polygons with
/// their vertex indices in counter-clockwise order seen from outside.
struct ConvexHull {
  struct Face {
    Vec3 normal;       ///< outward unit normal
    float offset;      ///< plane: dot(normal, x) = offset
    uint32_t first;    ///< first index into faceVertices
    uint32_t count;    ///< number of vertices of the polygon
  };
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::vector<uint32_t> faceVertices;
  std::vector<std::pair<uint32_t, uint32_t>> edges;  ///< unique edges (vertex index pairs)
  /// The first axisEdges edges have distinct directions and cover every edge's direction.
  uint32_t axisEdges = 0;
  /// The two faces beside each edge, in the order of `edges` (empty when some edge does not have
  /// exactly two): the separating-axis test skips edge pairs that cannot meet (collide_polytope.cpp).
  std::vector<std::pair<uint32_t, uint32_t>> edgeFaces;
  /// Some edge runs along another (alongEdge): an edge contact must then look among them for the one
  /// that supports the hull. Most hulls have none, and the edge an axis came from is that one.
  bool parallelEdges = true;
  /// The vertices by coordinate, kVertexLaneWidth to a vector: every x, then every y, then every z,
  /// each padded with vertex 0 to vertexLaneCount(vertices) (the separating-axis tests read them a
  /// vector at a time; made here once, not for every pair).
  std::vector<float> vertexLanes;
  static constexpr int kVertexLaneWidth = 8;
  static int vertexLaneCount(size_t vertices) {
    return int((vertices + kVertexLaneWidth - 1) / kVertexLaneWidth * kVertexLaneWidth);
  }
  /// Writes `count` vertices by coordinate into `out` (3 * vertexLaneCount(count) floats), the
  /// padding repeating vertex 0 so that a lane's min and max are those of the real vertices.
  static void fillVertexLanes(const Vec3* verts, size_t count, float* out) {
    const size_t lanes = size_t(vertexLaneCount(count));
    for (size_t k = 0; k < 3; ++k)
      for (size_t i = 0; i < lanes; ++i) out[k * lanes + i] = verts[i < count ? i : 0][int(k)];
  }
  Vec3 centroid = Vec3::Zero();   ///< of the solid, in the input frame (vertices are already shifted by -centroid)
  float volume = 0.0f;
  Mat3 inertiaPerDensity = Mat3::Zero();  ///< about the centroid, for density 1
};

/// Static triangle soup with a bounding-volume hierarchy for queries.
struct TriangleMesh {
  struct Node {
    Aabb box;
    int32_t left = -1;       ///< child index, or -1 for a leaf
    int32_t right = -1;
    uint32_t firstTri = 0;   ///< leaf: first entry in triIndex
    uint32_t triCount = 0;
  };
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;   ///< 3 per triangle, CCW seen from the front
  std::vector<Node> nodes;         ///< nodes[0] is the root
  std::vector<uint32_t> triIndex;  ///< triangle order referenced by leaves
};

struct Shape {
  ShapeType type = ShapeType::Sphere;
  Vec3 halfExtents = Vec3::Constant(0.5f);  ///< box
  float radius = 0.5f;                      ///< sphere, capsule
  float halfHeight = 0.5f;                  ///< capsule: core segment runs along local y from -halfHeight to +halfHeight
  Vec3 planeNormal = Vec3::UnitY();         ///< plane (static only): dot(n, x) = planeOffset in the body frame
  float planeOffset = 0.0f;
  std::shared_ptr<const ConvexHull> hull;   ///< convex hull
  std::shared_ptr<const TriangleMesh> mesh; ///< triangle mesh (static only)
  std::shared_ptr<const CompoundShape> compound;  ///< compound: its parts

  static Shape sphere(float r);
  static Shape box(const Vec3& halfExtents);
  static Shape capsule(float radius, float halfHeight);
  static Shape plane(const Vec3& normal, float offset);
  static Shape convexHull(std::shared_ptr<const ConvexHull> h);
  static Shape triangleMesh(std::shared_ptr<const TriangleMesh> m);
  static Shape compoundOf(std::shared_ptr<const CompoundShape> c);
};

/// Mass properties of a shape for a density (kg/m^3): mass and inertia tensor about the centre of mass.
struct MassProperties {
  float mass = 0.0f;
  Mat3 inertia = Mat3::Zero();
};
MassProperties computeMassProperties(const Shape& s, float density);
/// Mass properties of a dynamic body: `mass` > 0 overrides the density, and the inertia keeps the
/// shape's distribution scaled to that mass (identity times mass for a shape without volume).
MassProperties bodyMassProperties(const Shape& s, float density, float mass);

/// World-space bounding box of a shape at a transform (planes and meshes give their finite bounds;
/// a plane gives a huge box).
Aabb computeAabb(const Shape& s, const Transform& xf);

/// Smallest extent of a shape (used to express penetration as a fraction of body size); a
/// compound's is its thinnest part's.
float smallestExtent(const Shape& s);

}  // namespace haif
