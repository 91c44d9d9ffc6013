// Reusing a contact manifold while its two bodies keep still relative to each other. A resting pile
// spends most of its collision time recomputing manifolds that come out the same: in many_pyramids
// (28k box-box pairs at rest) the narrow phase took ~9 ms a step, about 2400 instructions a pair.
// Each point of a manifold is kept as the two surface points it joins, one fixed in each body, and
// the normal in both bodies' frames. While the bodies move only together, the points move with them
// and the depth follows exactly from where the two surface points now are; the manifold is made
// again once the bodies turn against each other or slide along the contact (a corner may then
// come into contact or leave the patch).
#pragma once

#include "collision/manifold.h"
#include "core/math.h"

namespace haif {

struct ManifoldCache {
  ManifoldCache() {
    for (int i = 0; i < kMaxManifoldPoints; ++i) onA[i] = onB[i] = Vec3::Zero();
  }
  bool valid = false;
  Vec3 normalA = Vec3::UnitY(), normalB = Vec3::UnitY();  ///< the normal in A's and in B's frame
  Vec3 onA[kMaxManifoldPoints];  ///< point i's surface point on A, in A's frame
  Vec3 onB[kMaxManifoldPoints];  ///< point i's surface point on B, in B's frame
};

/// How far the bodies may move against each other before a manifold is made again.
struct ManifoldReuseLimits {
  float slide = 1e-3f;       ///< m: the two surface points of a point drift apart along the contact
  float turnCos = 0.99995f;  ///< cos of the angle (0.01 rad) the normal may turn between the bodies' frames
  float margin = 0.02f;      ///< m: a point farther apart than this is made again (collide would drop it)
};

/// Keeps `m`, just made for the bodies at xa and xb, in `cache`.
void rememberManifold(const Manifold& m, const Transform& xa, const Transform& xb, ManifoldCache& cache);

/// The cached manifold moved with the bodies now at xa and xb: into `m` (ids kept), with each point's
/// depth from its two surface points. False, and `m` untouched, when the cache is empty or the
/// bodies moved against each other beyond `limits`.
bool refreshManifold(const ManifoldCache& cache, const Transform& xa, const Transform& xb,
                     const ManifoldReuseLimits& limits, Manifold& m);

}  // namespace haif
