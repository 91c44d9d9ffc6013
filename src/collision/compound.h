// Compound shape: several convex shapes fixed at poses in one body (a dumbbell, a table, a drum).
// The body frame is the compound's centre of mass, as for every shape (collision/shape.h): the parts'
// poses are re-centred when the compound is built, and CompoundShape::centroid keeps the shift.
#pragma once

#include "collision/shape.h"

#include <memory>
#include <string>
#include <vector>

namespace haif {

struct CompoundShape {
  struct Part {
    Shape shape;      ///< sphere, box, capsule or hull (its own origin at its own centre of mass)
    Transform local;  ///< the part's pose in the body frame
    Aabb box;         ///< the part's bounds in the body frame (for the narrow phase's part cull)
  };
  std::vector<Part> parts;
  Vec3 centroid = Vec3::Zero();           ///< centre of mass in the input frame (parts are shifted by -centroid)
  float volume = 0.0f;
  Mat3 inertiaPerDensity = Mat3::Zero();  ///< about the centre of mass, for density 1
  bool roundParts = false;                ///< some part is a sphere or capsule (it can roll)
};

/// The most parts one compound may have (a part index is mixed into 16 bits of a contact's feature id).
inline constexpr size_t kMaxCompoundParts = 4096;

/// Whether `t` can be a part of a compound: convex shapes with a volume (no meshes, planes, compounds).
bool compoundPartType(ShapeType t);
/// What a scene file is told when a part is of type `t` that cannot be one.
std::string notAPartMessage(ShapeType t);

/// Builds a compound from parts at poses in the body's input frame. A hull part's own re-centring
/// (ConvexHull::centroid) is folded into its pose, so a hull part sits where its points say.
/// Volume, centre of mass and inertia combine the parts (they are assumed not to overlap: overlapping
/// parts count their shared volume twice). Returns nullptr, with a message in *error when given, for
/// no parts, too many, a part of the wrong type, or non-finite poses.
std::shared_ptr<CompoundShape> buildCompound(const std::vector<Shape>& shapes, const std::vector<Transform>& poses,
                                             std::string* error);

}  // namespace haif
