// Turns a validated SceneDesc into a World.
#pragma once

#include "haif/world.h"
#include "scene/scene_desc.h"

#include <string>

namespace haif {

/// World settings from the scene's simulation settings.
WorldSettings worldSettingsFor(const SceneDesc& scene);

/// Adds every body and water volume of the scene to `world` (ids follow scene order).
/// Fails (false, `error` names the scene file and the body) when a shape cannot be built,
/// e.g. a degenerate convex hull or an empty mesh.
bool buildWorld(const SceneDesc& scene, World& world, std::string& error);

}  // namespace haif
