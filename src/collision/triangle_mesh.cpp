// Triangle mesh construction: validation and a median-split BVH over the triangle centroids.
// Median splits keep the tree balanced (depth ~log2(n/4)), which bounds the query stack.
#include "collision/triangle_mesh.h"

#include <algorithm>

namespace haif {

namespace {

struct Builder {
  TriangleMesh& mesh;
  std::vector<Vec3> centroid;

  Aabb triBox(uint32_t t) const {
    Aabb b;
    for (int k = 0; k < 3; ++k) b.include(mesh.vertices[mesh.indices[3 * t + uint32_t(k)]]);
    return b;
  }

  int32_t build(uint32_t first, uint32_t count) {
    const int32_t index = int32_t(mesh.nodes.size());
    mesh.nodes.emplace_back();
    Aabb box, cbox;
    for (uint32_t i = first; i < first + count; ++i) {
      box = box.merged(triBox(mesh.triIndex[i]));
      cbox.include(centroid[mesh.triIndex[i]]);
    }
    mesh.nodes[size_t(index)].box = box;
    if (count <= kMeshLeafTriangles) {
      mesh.nodes[size_t(index)].firstTri = first;
      mesh.nodes[size_t(index)].triCount = count;
      return index;
    }
    int axis = 0;
    const Vec3 e = cbox.extent();
    if (e.y() > e[axis]) axis = 1;
    if (e.z() > e[axis]) axis = 2;
    const uint32_t half = count / 2;
    auto begin = mesh.triIndex.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](uint32_t x, uint32_t y) {
      return centroid[x][axis] < centroid[y][axis];
    });
    const int32_t left = build(first, half);
    const int32_t right = build(first + half, count - half);
    mesh.nodes[size_t(index)].left = left;
    mesh.nodes[size_t(index)].right = right;
    return index;
  }
};

bool fail(std::string* error, const std::string& msg) {
  if (error) *error = msg;
  return false;
}

}  // namespace

std::shared_ptr<TriangleMesh> buildTriangleMesh(std::vector<Vec3> vertices, std::vector<uint32_t> indices,
                                                std::string* error) {
  auto check = [&]() -> bool {
    if (indices.empty()) return fail(error, "triangle mesh has no triangles");
    if (indices.size() % 3 != 0)
      return fail(error, "triangle mesh index count " + std::to_string(indices.size()) + " is not a multiple of 3");
    for (size_t i = 0; i < vertices.size(); ++i)
      if (!isFinite(vertices[i])) return fail(error, "triangle mesh vertex " + std::to_string(i) + " is not finite");
    for (size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= vertices.size())
        return fail(error, "triangle mesh index " + std::to_string(i) + " = " + std::to_string(indices[i]) +
                               " is out of range (" + std::to_string(vertices.size()) + " vertices)");
    return true;
  };
  if (!check()) return nullptr;

  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = std::move(vertices);
  mesh->indices = std::move(indices);
  const uint32_t triCount = uint32_t(mesh->indices.size() / 3);
  mesh->triIndex.resize(triCount);
  Builder b{*mesh, std::vector<Vec3>(triCount)};
  for (uint32_t t = 0; t < triCount; ++t) {
    mesh->triIndex[t] = t;
    b.centroid[t] = (mesh->vertices[mesh->indices[3 * t]] + mesh->vertices[mesh->indices[3 * t + 1]] +
                     mesh->vertices[mesh->indices[3 * t + 2]]) / 3.0f;
  }
  mesh->nodes.reserve(2 * size_t(triCount));
  b.build(0, triCount);
  return mesh;
}

}  // namespace haif
