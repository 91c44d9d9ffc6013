// How far a convex shape reaches along a direction (its support function), and the bound on a
// pair's depth that follows from it.
//
// For convex shapes the penetration depth is the least overlap over all directions, so the overlap
// along any one direction bounds it from above. Two support queries (a few dozen dot products for a
// hull) then settle most pairs that only need to be known "not deep": a full collision of a hull
// pair is a separating-axis test over every face and edge pair and a clipped manifold (~1-3 µs).
#pragma once

#include "collision/shape.h"
#include "core/math.h"

namespace haif {

/// max over the shape's points x of d · x at transform xf (d in world space, any length). Spheres,
/// boxes, capsules, hulls and compounds of them; +inf for a plane or a mesh (no finite convex reach).
float supportAlong(const Shape& s, const Transform& xf, const Vec3& d);

/// How far a reaches past b along unit n (from a to b): a's reach along n plus b's along -n.
/// Negative: a plane across n separates them by that much. +inf where either has no support.
inline float overlapAlong(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, const Vec3& n) {
  return supportAlong(a, xa, n) + supportAlong(b, xb, -n);
}

/// A bound on the depth of the deepest point `collide` (margin 0) reports for a pair of convex shapes
/// that overlap by `overlap` along some direction. The pair routines report the least overlap over
/// their candidate axes, except that a face axis is kept over a slightly better edge axis or the
/// other shape's face (collision/axis_preference.h): at most 2 % and 1.5 mm deeper. The bound allows
/// 3 % and 2 mm. Tested over random poses of every pair of convex shapes (test_support.cpp).
inline float depthBoundFromOverlap(float overlap) {
  constexpr float kRelative = 0.03f, kAbsolute = 2e-3f;
  return overlap + kRelative * (overlap > 0.0f ? overlap : 0.0f) + kAbsolute;
}

}  // namespace haif
