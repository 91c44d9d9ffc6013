// Building a static triangle mesh with its bounding-volume hierarchy, and querying it.
#pragma once

#include "collision/shape.h"

#include <memory>
#include <string>
#include <vector>

namespace haif {

/// Most triangles in one BVH leaf.
inline constexpr uint32_t kMeshLeafTriangles = 4;
/// Depth bound of the traversal stack; median splits keep the tree far shallower than this.
inline constexpr int kMeshQueryStack = 64;

/// Builds a mesh (3 indices per triangle, CCW seen from the front) and its BVH (median split on the
/// longest axis of the triangle centroids, leaves of at most kMeshLeafTriangles triangles).
/// On bad input (no triangles, index count not a multiple of 3, index out of range, non-finite
/// vertex) returns nullptr and, if error is given, a message saying what is wrong.
std::shared_ptr<TriangleMesh> buildTriangleMesh(std::vector<Vec3> vertices, std::vector<uint32_t> indices,
                                                std::string* error);

/// Calls fn(triangle) for every triangle in a leaf whose box overlaps `box` (mesh frame).
/// No allocation: the traversal stack is a fixed array.
template <class Fn>
void queryMeshTriangles(const TriangleMesh& mesh, const Aabb& box, Fn&& fn) {
  if (mesh.nodes.empty()) return;
  int32_t stack[kMeshQueryStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleMesh::Node& node = mesh.nodes[size_t(stack[--top])];
    if (!node.box.overlaps(box)) continue;
    if (node.left < 0) {
      for (uint32_t i = 0; i < node.triCount; ++i) fn(mesh.triIndex[node.firstTri + i]);
      continue;
    }
    if (top + 2 > kMeshQueryStack) continue;  // cannot happen for trees built by buildTriangleMesh
    stack[top++] = node.right;
    stack[top++] = node.left;
  }
}

}  // namespace haif
