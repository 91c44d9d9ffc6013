// Which separating axis makes a polyhedron pair's contact (box-box, box-hull, hull-hull,
// triangle-convex): one rule for every pair routine.
//
// Face axes win over edge axes unless an edge axis separates clearly more, and A's faces over B's:
// a resting contact whose best axis flips between a face and an edge from one step to the next makes
// its manifold flicker. An edge must also win by a tenth of the margin: a pair closing fast (a hull
// falling at 14 m/s onto one at rest, margin 0.26 m) that meets face to face with a slight tilt first
// comes near at an edge, and one point there took the whole landing (both bodies spun up to
// 30 rad/s and sank 0.22 m into each other); the face's clipped points take it on several. Their
// gaps, read along the face normal, are never larger than the true ones. At rest (margin 2 cm) that
// share is 2 mm. It holds only while the edges are apart: once they overlap, the face's clipped
// points can lie where nothing touches and read the overlap as a gap (a box falling at 13 m/s onto
// another, 4 cm into it at their edges, got no point and sank 0.27 m in the next step).
#pragma once

#include <cmath>

namespace haif::detail {

constexpr float kFaceBTol = 5e-4f;  ///< B's face must beat A's by this (m) to become the reference
constexpr float kEdgeAbsTol = 1e-3f;
constexpr float kEdgeRelTol = 0.02f;
constexpr float kEdgeMarginShare = 0.1f;

/// True when the edge axis (separation sepE) makes the contact instead of the best face (faceSep).
inline bool edgeBeatsFace(float sepE, float faceSep, float margin) {
  const float share = sepE > 0.0f ? kEdgeMarginShare * margin : 0.0f;
  return sepE > faceSep + kEdgeAbsTol + kEdgeRelTol * std::fabs(faceSep) + share;
}

}  // namespace haif::detail
