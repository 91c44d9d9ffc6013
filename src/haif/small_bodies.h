// Small bodies: the contact tolerances are lengths (the slop, the speculative margin, the broad
// phase's fat and kept margins, how far a kept manifold may slide, the turn projection's depths),
// sized for bodies a few centimetres thick and up. Against a bead of 4 mm they are its whole size:
// 5 mm of slop let one bead sink into another and stay there, and 2 cm of margin (10 cm of fat box)
// gave a cup of 400 such beads 81000 pairs, 200 a bead, at 6-8 ms a step (7700 and 0.7-0.9 ms
// scaled). A body thinner than WorldSettings::toleranceThickness scales them down with its
// thickness, pair by pair (the thinner body decides), so a small world behaves as a scaled copy of
// a large one; bodies at or above it keep the tolerances exactly (the same state to the bit). The
// skin is not scaled: it holds the gaps a scene placed, which it chose in metres (a Jenga tower's
// 0.5 mm between 1.5 cm layers).
#pragma once

#include "collision/shape.h"

#include <algorithm>

namespace haif {

/// The lowest factor: a 1 mm body (the smallest the loader takes, haif/body_limits.h) against the
/// default 5 cm gets 0.02; this only keeps a degenerate shape's factor from reaching 0.
constexpr float kMinToleranceScale = 0.01f;

/// A body's factor on the contact tolerances: 1 for a body at least `thickness` thick (its smallest
/// extent, smallestExtent) or for `thickness` 0, else its thickness over `thickness`.
inline float toleranceScale(const Shape& shape, float thickness) {
  if (!(thickness > 0.0f)) return 1.0f;
  const float extent = smallestExtent(shape);
  return extent >= thickness ? 1.0f : std::max(extent / thickness, kMinToleranceScale);
}

/// A pair's factor from its bodies' factors: the thinner body decides (a bead on a floor keeps the
/// bead's tolerances). Every user of a pair's tolerances takes it from here.
inline float pairToleranceScale(float scaleA, float scaleB) { return std::min(scaleA, scaleB); }

}  // namespace haif
