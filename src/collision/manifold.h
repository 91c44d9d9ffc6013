// Contact manifold produced by the narrow phase for one pair of shapes.
#pragma once

#include "core/math.h"

#include <algorithm>
#include <cstdint>

namespace haif {

inline constexpr int kMaxManifoldPoints = 4;
/// Manifold::apartAxis when no axis is noted.
inline constexpr uint32_t kNoApartAxis = 0xFFFFFFFFu;

struct ContactPoint {
  Vec3 position = Vec3::Zero();  ///< world point midway between the two surfaces
  Vec3 normal = Vec3::UnitY();   ///< world unit normal pointing from shape A towards shape B
  float depth = 0.0f;            ///< penetration depth (> 0 overlapping, < 0 separated by -depth: speculative)
  uint32_t id = 0;               ///< feature id, stable from step to step while the same features touch
};

struct Manifold {
  int count = 0;
  ContactPoint points[kMaxManifoldPoints];
  /// The axis that last kept this pair farther apart than the margin, numbered by the pair routine
  /// that noted it (a face; for two polyhedra also an edge pair: collide_polytope.cpp), or
  /// kNoApartAxis. The routine tests it first: most pairs the broad phase keeps in a pile are apart,
  /// held apart by the same axis step after step. An axis noted wrongly only costs its test.
  uint32_t apartAxis = kNoApartAxis;
  /// Depth of the deepest point; 0 when no point overlaps.
  float deepest() const {
    float d = 0.0f;
    for (int i = 0; i < count; ++i) d = std::max(d, points[i].depth);
    return d;
  }
  /// Depth of the nearest point, negative when every point is apart; needs a point.
  float nearest() const {
    float d = points[0].depth;
    for (int i = 1; i < count; ++i) d = std::max(d, points[i].depth);
    return d;
  }
};

}  // namespace haif
