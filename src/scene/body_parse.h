// Reading bodies, shapes, orientations and material references from their JSON form. Shared by the
// "bodies" list and the generators (a grid repeats one shape, every generator takes a material).
#pragma once

#include "scene/json_reader.h"
#include "scene/scene_desc.h"

#include <string>
#include <vector>

namespace haif {

/// What parsing needs to know about the rest of the scene.
struct ParseContext {
  std::string sceneDir;                   ///< directory of the scene file: asset paths are relative to it
  std::vector<MaterialDesc> materials;    ///< materials[0] is "default"
  std::vector<std::string> bodyPointers;  ///< per body: JSON pointer of the entry that produced it
};

/// "static" | "dynamic" | "kinematic".
MotionType parseMotionType(const JsonNode& node);
/// A material name, resolved to its index.
uint32_t parseMaterialRef(const JsonNode& node, const ParseContext& ctx);
/// [x, y, z, w] (normalised) or {"euler_deg": [rx, ry, rz]} (about world x, then y, then z).
Quat parseOrientation(const JsonNode& node);
/// A shape object; static-only shapes are rejected unless `motion` is static.
ShapeDesc parseShape(const JsonNode& node, MotionType motion, const ParseContext& ctx);
/// Damping: one number for both, or {"linear": l, "angular": a} (1/s).
void parseDamping(const JsonNode& node, BodyDesc& body);
/// Mass in kg; only dynamic bodies may give one.
float parseMass(const JsonNode& node, MotionType motion);
/// One entry of "bodies".
BodyDesc parseBody(const JsonNode& node, const ParseContext& ctx);

}  // namespace haif
