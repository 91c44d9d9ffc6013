// Building a convex hull shape from a point cloud.
#pragma once

#include "collision/shape.h"

#include <memory>
#include <string>
#include <vector>

namespace haif {

/// Quickhull over `points` (body frame). Coplanar triangles are merged into polygon faces (CCW seen
/// from outside); vertices not on the hull are dropped. Volume, centroid and the inertia tensor per
/// unit density are computed, then the vertices are shifted by -centroid so the body origin is the
/// centre of mass (ConvexHull::centroid keeps where it was in the input frame).
/// Returns nullptr, with a message in *error when given, for fewer than 4 points, non-finite
/// coordinates, or points that are all coincident, collinear or coplanar.
std::shared_ptr<ConvexHull> buildConvexHull(const std::vector<Vec3>& points, std::string* error);

}  // namespace haif
