#include "scene/procedural_mesh.h"

#include <cmath>
#include <map>

namespace haif {

TriangleSoup makeTerrain(float size, int cells) {
  TriangleSoup m;
  const int n = cells + 1;
  const float step = size / float(cells);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = -0.5f * size + step * float(i), z = -0.5f * size + step * float(j);
      // A hillside down to x = 5, then a valley floor; bumps fade out on the floor.
      const float bump = x < 5.0f ? 1.0f : std::max(0.15f, 1.0f - 0.3f * (x - 5.0f));
      const float h = 8.0f - 0.35f * std::min(x, 5.0f) +
                      bump * (0.9f * std::sin(0.35f * x + 1.0f) * std::cos(0.3f * z) +
                              0.35f * std::sin(0.9f * z + 0.5f * x) + 0.15f * std::cos(1.7f * x - 1.1f * z));
      m.vertices.emplace_back(x, h, z);
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const uint32_t v00 = uint32_t(j * n + i), v10 = v00 + 1, v01 = v00 + uint32_t(n), v11 = v01 + 1;
      m.indices.insert(m.indices.end(), {v00, v01, v10, v10, v01, v11});  // both facing +y
    }
  return m;
}

namespace {

uint64_t splitmix64(uint64_t& s) {
  uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float unit(uint64_t& s) { return float(splitmix64(s) >> 40) / float(1ull << 24) * 2.0f - 1.0f; }

}  // namespace

TriangleSoup makeRock(uint64_t seed, const Vec3& stretch, int subdivisions) {
  // Icosahedron, then split every edge at its midpoint (shared through a map) and push to the sphere.
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleSoup m;
  for (const Vec3& v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),
                        Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1),
                        Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.vertices.push_back(v.normalized());
  m.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
               3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return mid[key] = uint32_t(m.vertices.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t f = 0; f < m.indices.size(); f += 3) {
      const uint32_t a = m.indices[f], b = m.indices[f + 1], c = m.indices[f + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices.swap(next);
  }
  // Noise: a few smooth bumps along random directions, and flat cuts like fractured faces.
  uint64_t rng = seed * 0x2545f4914f6cdd1dull + 1;
  Vec3 dirs[6];
  float freq[6], amp[6];
  for (int k = 0; k < 6; ++k) {
    dirs[k] = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    freq[k] = 2.0f + 2.0f * std::fabs(unit(rng));
    amp[k] = 0.05f + 0.04f * std::fabs(unit(rng));
  }
  Vec3 cuts[3];
  for (Vec3& c : cuts) c = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
  for (Vec3& v : m.vertices) {
    float r = 1.0f;
    for (int k = 0; k < 6; ++k) r += amp[k] * std::sin(freq[k] * v.dot(dirs[k]) + float(k));
    Vec3 p = r * v;
    for (const Vec3& c : cuts) {
      const float d = p.dot(c) - 0.78f;  // flatten beyond a plane: a broken face
      if (d > 0.0f) p -= 0.85f * d * c;
    }
    v = p.cwiseProduct(stretch);
  }
  return m;
}

TriangleSoup makePillar(float height, float radius, int flutes) {
  TriangleSoup m;
  const int seg = flutes * 4;
  // Profile (height, radius scale, fluted?) from the base up; square blocks are 4-sided rings.
  struct Ring {
    float y, r;
    bool fluted, square;
  };
  const float b = 0.12f * height, y0 = -0.5f * height;
  const std::vector<Ring> rings{{0.0f, 1.5f, false, true},         {b * 0.5f, 1.5f, false, true},
                                {b * 0.5f, 1.15f, false, false},       {b, 1.0f, true, false},
                                {height - b, 0.9f, true, false},       {height - b, 1.15f, false, false},
                                {height - b * 0.5f, 1.5f, false, true}, {height, 1.5f, false, true}};
  for (const Ring& ring : rings)
    for (int k = 0; k < seg; ++k) {
      const float a = 2.0f * kPi * float(k) / float(seg);
      float r = radius * ring.r;
      if (ring.fluted) r *= 1.0f - 0.06f * (0.5f + 0.5f * std::cos(float(flutes) * a));
      Vec3 dir(std::cos(a), 0.0f, -std::sin(a));
      if (ring.square) dir /= std::max(std::fabs(dir.x()), std::fabs(dir.z()));  // onto a square
      m.vertices.push_back(Vec3(0.0f, y0 + ring.y, 0.0f) + r * dir);
    }
  const uint32_t n = uint32_t(seg);
  for (uint32_t i = 0; i + 1 < rings.size(); ++i)
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = i * n + k, b2 = i * n + (k + 1) % n, c = a + n, d = b2 + n;
      m.indices.insert(m.indices.end(), {a, b2, c, b2, d, c});
    }
  // Caps.
  const uint32_t bottom = uint32_t(m.vertices.size()), top = bottom + 1;
  m.vertices.emplace_back(0.0f, y0, 0.0f);
  m.vertices.emplace_back(0.0f, y0 + height, 0.0f);
  const uint32_t last = uint32_t(rings.size() - 1) * n;
  for (uint32_t k = 0; k < n; ++k) {
    m.indices.insert(m.indices.end(), {bottom, (k + 1) % n, k});
    m.indices.insert(m.indices.end(), {top, last + k, last + (k + 1) % n});
  }
  return m;
}

}  // namespace haif
