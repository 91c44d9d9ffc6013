// Pair routines of the narrow phase, each for one ordered pair of shape types. collide() in
// collide.cpp dispatches to them and swaps the arguments (and flips the normals) for the reverse
// order. Same contract as collide(): normals from the first shape to the second, points with
// depth >= -margin, at most 4 points, no allocation.
#pragma once

#include "collision/manifold.h"
#include "collision/shape.h"

namespace haif {
namespace detail {

using PairFn = int (*)(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                       Manifold& m);

int collideSphereSphere(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideSphereBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideSphereCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideSphereHull(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

int collideBoxBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideBoxHull(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideHullHull(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

int collideCapsuleCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideCapsuleBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collideCapsuleHull(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

/// Plane (static) first, convex second.
int collidePlaneSphere(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collidePlaneBox(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collidePlaneCapsule(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);
int collidePlaneHull(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

/// Triangle mesh (static) first, any convex second.
int collideMeshConvex(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

/// Either shape (or both) a compound: its parts against the other's, one manifold for the pair.
int collideCompound(const Shape&, const Transform&, const Shape&, const Transform&, float, Manifold&);

}  // namespace detail
}  // namespace haif
