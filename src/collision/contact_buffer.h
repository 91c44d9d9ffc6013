// Fixed-capacity list of candidate contact points and the reduction to the manifold's 4 points.
// Internal to the narrow phase: every pair routine collects candidates here (on the stack, never the
// heap) and hands them to writeManifold, so all pairs share one reduction policy.
#pragma once

#include "collision/manifold.h"
#include "core/math.h"

#include <cstdint>

namespace haif {
namespace detail {

struct ContactCandidate {
  Vec3 position;  ///< world, midway between the surfaces
  Vec3 normal;    ///< world, from A to B
  float depth;    ///< > 0 penetrating
  uint32_t id;    ///< feature id
};

/// Picks at most 4 of `count` candidates: the deepest (ties broken towards the outside of the
/// patch), the one farthest from it across the normal, then the two that maximise the area of the
/// contact polygon (seen along the normal; equal spreads go to the deeper candidate).
/// Writes them to `out` and returns how many were written.
int reduceContacts(const ContactCandidate* pts, int count, ContactCandidate* out);

/// Stack buffer of candidates. When it is full it reduces itself to 4 points and goes on, so a
/// pair with very many candidates (meshes, big hulls) still never allocates nor loses its deepest point.
struct ContactBuffer {
  static constexpr int kCapacity = 64;
  ContactCandidate pts[kCapacity];
  int count = 0;

  void add(const Vec3& position, const Vec3& normal, float depth, uint32_t id) {
    if (count == kCapacity) {
      ContactCandidate keep[kMaxManifoldPoints];
      const int n = reduceContacts(pts, count, keep);
      for (int i = 0; i < n; ++i) pts[i] = keep[i];
      count = n;
    }
    pts[count++] = ContactCandidate{position, normal, depth, id};
  }
};

/// Reduces the buffer into the manifold; returns manifold.count.
int writeManifold(const ContactBuffer& buf, Manifold& m);

/// Single-point manifold helper.
inline int writeSingle(Manifold& m, const Vec3& position, const Vec3& normal, float depth, uint32_t id) {
  m.points[0] = ContactPoint{position, normal, depth, id};
  m.count = 1;
  return 1;
}

}  // namespace detail
}  // namespace haif
