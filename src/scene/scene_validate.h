// Invariants every SceneDesc must satisfy before a World is built from it, whether it came from
// a file or was assembled in code. The loader checks most things with exact file positions while
// reading; this is the final, format-independent net (and what code-built scenes should call).
#pragma once

#include "haif/body_limits.h"
#include "scene/scene_desc.h"

#include <string>

namespace haif {

/// One broken invariant.
struct SceneIssue {
  int body = -1;        ///< index into SceneDesc::bodies, or -1 for scene-level issues
  int water = -1;       ///< index into SceneDesc::water, or -1
  int joint = -1;       ///< index into SceneDesc::joints, or -1
  std::string field;    ///< scene-file key path of the value, e.g. "mass", "shape.radius", "settings.dt"
  std::string message;  ///< what is wrong, e.g. "must be > 0 (got -2)"

  /// "bodies[3].mass: must be > 0 (got -2)" (uses the body's `where`).
  std::string describe(const SceneDesc& scene) const;
};

/// Half edges (m) of a box about the body's origin that holds a movable shape in its own frame
/// (zero for static-only shapes; a compound's holds every part).
Vec3 shapeHalfBox(const ShapeDesc& s);
/// Longest edge (m) of a movable shape's bounding box in its own frame (0 for static-only shapes).
float shapeExtent(const ShapeDesc& s);
/// Mass (kg) of a dynamic body: its own, or its material's density times its volume; 0 for a hull
/// (or a compound with a hull part) without an explicit mass (its volume is known only once the hull
/// is built).
float bodyMass(const SceneDesc& scene, const BodyDesc& b);

/// Checks settings, materials, bodies, water volumes and joints. Returns false and fills `issue` with the
/// first problem.
bool validateScene(const SceneDesc& scene, SceneIssue& issue);

/// True for shapes only a static body may have (planes, triangle meshes).
bool isStaticOnlyShape(ShapeType t);

/// True when at least one triangle of the mesh has an area (its corners are not on one line).
bool hasTriangleWithArea(const std::vector<Vec3>& vertices, const std::vector<uint32_t>& indices);

/// Empty when the points span a volume; else why not (fewer than 4, or all on one plane/line).
std::string hullPointsProblem(const std::vector<Vec3>& points);

}  // namespace haif
