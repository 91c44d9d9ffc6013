// Narrow phase: one entry point that dispatches on the two shape types.
#pragma once

#include "collision/manifold.h"
#include "collision/shape.h"

namespace haif {

/// Computes the contact manifold of shapes a (at xa) and b (at xb). Points with separation up to
/// `margin` (depth >= -margin) are reported, so the solver can act on contacts that are about to
/// form (speculative contacts). Normals point from a to b. Returns manifold.count.
/// Never allocates; safe to call concurrently for different pairs.
int collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
            Manifold& manifold);

}  // namespace haif
