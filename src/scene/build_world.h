// Turns a validated SceneDesc into a World.
#pragma once

#include "haif/world.h"
#include "scene/scene_desc.h"

#include <string>

namespace haif {

/// The world-side definition of one scene body: shape built (hulls re-centred on their centre of
/// mass, which moves the body there), material and motion copied. Another engine built from the same
/// scene (the Bullet baseline) starts from this too, so both see identical geometry and mass.
/// Fails (false, `error` names the scene file and the body) when the shape cannot be built.
bool bodyDefFor(const SceneDesc& scene, const BodyDesc& body, BodyDef& def, std::string& error);

/// Adds every body and water volume of the scene to `world` (ids follow scene order).
/// Fails (false, `error` names the scene file and the body) when a shape cannot be built,
/// e.g. a degenerate convex hull or an empty mesh.
bool buildWorld(const SceneDesc& scene, World& world, std::string& error);

}  // namespace haif
