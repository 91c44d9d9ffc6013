#include "render/mesh_builder.h"

#include <cmath>

#include "render/render_math.h"

namespace haif::render {
namespace {

constexpr float kPi = 3.14159265358979f;

void pushVertex(MeshData& m, Vec3 p, Vec3 n, float side) {
  m.vertices.insert(m.vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, side});
}

// Rings of a sphere from polar angle theta0 to theta1 (0 = +y). Used for spheres and capsule caps.
void appendSphereBand(MeshData& m, int slices, int stacks, float theta0, float theta1, float side) {
  const uint32_t base = static_cast<uint32_t>(m.vertices.size() / MeshData::kFloatsPerVertex);
  for (int i = 0; i <= stacks; ++i) {
    const float th = theta0 + (theta1 - theta0) * static_cast<float>(i) / stacks;
    for (int j = 0; j <= slices; ++j) {
      const float ph = 2.f * kPi * static_cast<float>(j) / slices;
      const Vec3 n{std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph)};
      pushVertex(m, n, n, side);
    }
  }
  const uint32_t row = static_cast<uint32_t>(slices + 1);
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const uint32_t a = base + i * row + j, b = a + row;
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
}

}  // namespace

MeshData makeBoxMesh() {
  MeshData m;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = -1; s <= 1; s += 2) {
      float n[3] = {0, 0, 0};
      n[axis] = static_cast<float>(s);
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t base = static_cast<uint32_t>(m.vertices.size() / MeshData::kFloatsPerVertex);
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        float p[3];
        p[axis] = static_cast<float>(s);
        p[u] = c[0];
        p[v] = c[1];
        pushVertex(m, {p[0], p[1], p[2]}, {n[0], n[1], n[2]}, 0.f);
      }
      if (s > 0)
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else
        m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  m.boundRadius = std::sqrt(3.f);
  return m;
}

MeshData makeSphereMesh(int slices, int stacks) {
  MeshData m;
  appendSphereBand(m, slices, stacks, 0.f, kPi, 0.f);
  return m;
}

MeshData makeCapsuleMesh(int slices, int capStacks) {
  MeshData m;
  // Two hemispheres whose equator rings coincide at zero half height; the shader pulls them apart
  // along y, and the triangles joining the rings become the cylinder.
  appendSphereBand(m, slices, capStacks, 0.f, kPi * 0.5f, +1.f);
  const uint32_t lowerBase = static_cast<uint32_t>(m.vertices.size() / MeshData::kFloatsPerVertex);
  appendSphereBand(m, slices, capStacks, kPi * 0.5f, kPi, -1.f);
  const uint32_t row = static_cast<uint32_t>(slices + 1);
  const uint32_t upperEquator = static_cast<uint32_t>(capStacks) * row;
  for (uint32_t j = 0; j < static_cast<uint32_t>(slices); ++j) {
    const uint32_t a = upperEquator + j, b = lowerBase + j;
    m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
  }
  m.boundRadius = 1.f;
  return m;
}

MeshData makePlaneMesh() {
  MeshData m;
  const Vec3 n{0, 1, 0};
  pushVertex(m, {-1, 0, -1}, n, 0.f);
  pushVertex(m, {-1, 0, 1}, n, 0.f);
  pushVertex(m, {1, 0, 1}, n, 0.f);
  pushVertex(m, {1, 0, -1}, n, 0.f);
  m.indices = {0, 1, 2, 0, 2, 3};
  m.boundRadius = std::sqrt(2.f);
  return m;
}

MeshData makeFlatMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices) {
  MeshData m;
  const size_t vertexCount = positions.size() / 3;
  float r2 = 0.f;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
    if (i0 >= vertexCount || i1 >= vertexCount || i2 >= vertexCount) continue;
    const Vec3 p0{positions[3 * i0], positions[3 * i0 + 1], positions[3 * i0 + 2]};
    const Vec3 p1{positions[3 * i1], positions[3 * i1 + 1], positions[3 * i1 + 2]};
    const Vec3 p2{positions[3 * i2], positions[3 * i2 + 1], positions[3 * i2 + 2]};
    const Vec3 c = cross(p1 - p0, p2 - p0);
    if (length(c) < 1e-12f) continue;
    const Vec3 n = normalize(c);
    const uint32_t base = static_cast<uint32_t>(m.vertices.size() / MeshData::kFloatsPerVertex);
    for (const Vec3& p : {p0, p1, p2}) {
      pushVertex(m, p, n, 0.f);
      r2 = std::fmax(r2, dot(p, p));
    }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  m.boundRadius = std::sqrt(r2);
  return m;
}

}  // namespace haif::render
