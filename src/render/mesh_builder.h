// CPU-side geometry for the instanced shape kinds. Every vertex is 7 floats: position, normal and
// a "cap side" (+1/-1 on a capsule's upper/lower half, 0 elsewhere) that the vertex shader uses to
// stretch one unit capsule to any half height.
#pragma once

#include <cstdint>
#include <vector>

namespace haif::render {

struct MeshData {
  static constexpr int kFloatsPerVertex = 7;
  std::vector<float> vertices;    ///< kFloatsPerVertex per vertex
  std::vector<uint32_t> indices;  ///< triangles, counter-clockwise seen from outside
  float boundRadius = 1.f;        ///< radius around the local origin enclosing the (unscaled) mesh
};

/// Unit box [-1,1]^3 with flat faces (scaled by half extents per instance).
MeshData makeBoxMesh();
/// Unit sphere (scaled by radius per instance).
MeshData makeSphereMesh(int slices, int stacks);
/// Unit-radius capsule with zero half height; vertices carry the cap side for stretching.
MeshData makeCapsuleMesh(int slices, int capStacks);
/// Unit square in the local xz plane facing +y (the Plane kind).
MeshData makePlaneMesh();
/// Flat-shaded mesh from shared positions (xyz) and triangle indices: vertices are split per
/// triangle so hull faces stay crisp. Invalid indices and degenerate triangles are dropped.
MeshData makeFlatMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices);

}  // namespace haif::render
