// Reading the "joints" list of a scene file (docs/scene_format.md, Joints).
#pragma once

#include "scene/json_reader.h"
#include "scene/scene_desc.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace haif {

/// Body names of a scene, for joints that name their bodies.
struct BodyNames {
  explicit BodyNames(const SceneDesc& scene);
  std::unordered_map<std::string, std::vector<int32_t>> indices;  ///< name -> bodies with it
};

/// Reads joint `node` (place "joints[i]") of a scene whose bodies are already read: bodies are named by
/// "name", by index, or "world". Throws SceneError at the offending value.
JointDesc parseJoint(const JsonNode& node, const SceneDesc& scene, const BodyNames& names);

/// The joint type of a name: ball, hinge, fixed, distance, rope, slider, cone_twist ("rope" is a
/// distance joint that may go slack: `isRope` is set).
JointType parseJointType(const JsonNode& node, bool& isRope);

}  // namespace haif
