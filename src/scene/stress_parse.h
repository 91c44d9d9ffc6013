// Reading the "stress" block of a scene file (docs/stress.md).
#pragma once

#include "scene/json_reader.h"
#include "scene/scene_desc.h"

namespace haif {

/// Reads `node` (place "stress") of a scene whose bodies are already read. Throws SceneError at the
/// offending value: an unknown check name, a missing limit, a body that does not exist.
StressDesc parseStress(const JsonNode& node, const SceneDesc& scene);

/// Reads one check object {"check": NAME, ...} (place e.g. "stress.checks[2]"): also what `haif suite`
/// reads for the stress checks of its run jobs. Throws SceneError like parseStress.
StressCheck parseStressCheck(const JsonNode& node, const SceneDesc& scene);

/// The check names, in the order docs/stress.md lists them.
const std::vector<std::string>& stressCheckNames();

}  // namespace haif
