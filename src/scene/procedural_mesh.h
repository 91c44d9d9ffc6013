// Meshes made by code, for the assets in assets/ (written by `haif assets`) and for tests. Deterministic:
// the same parameters give the same mesh.
#pragma once

#include "core/math.h"

#include <cstdint>
#include <vector>

namespace haif {

struct TriangleSoup {
  std::vector<Vec3> vertices;
  std::vector<uint32_t> indices;  ///< 3 per triangle, counter-clockwise seen from outside (terrain: from above)
};

/// Terrain over [-size/2, size/2]^2 in x and z with cells x cells quads: a bumpy hillside sloping down
/// towards +x, then a nearly flat valley floor from x = 5 on.
TriangleSoup makeTerrain(float size, int cells);

/// A rock: an icosphere of radius about 1 with its surface pushed in and out by smooth noise from `seed`,
/// stretched by `stretch` (per axis). Bumpy, not quite convex: a render mesh whose hull makes the collider.
TriangleSoup makeRock(uint64_t seed, const Vec3& stretch, int subdivisions = 1);

/// A fluted column with a square base and capital, `height` tall, centred on the origin (like a box).
TriangleSoup makePillar(float height, float radius, int flutes);

}  // namespace haif
