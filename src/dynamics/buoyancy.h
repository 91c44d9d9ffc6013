// Buoyancy and drag inside box-shaped water volumes (a scene feature; the pass is skipped when a
// scene has no water). The submerged fraction is estimated from the body's bounding box, which is
// exact for boxes resting upright and a fair estimate for other shapes.
#pragma once

#include "core/aabb.h"
#include "core/body_store.h"

#include <vector>

namespace haif {

struct WaterVolume {
  Aabb box;                  ///< world volume; the surface is box.hi.y
  float density = 1000.0f;   ///< kg/m^3
  float linearDrag = 1.0f;   ///< 1/s at full submersion
  float angularDrag = 0.5f;  ///< 1/s at full submersion
};

/// Adds buoyancy and drag to the velocities of awake dynamic bodies overlapping the volume.
/// `volume[i]` is body i's solid volume (m^3), `bounds[i]` its tight world box.
void applyBuoyancy(BodyStore& bodies, const std::vector<float>& volume, const std::vector<Aabb>& bounds,
                   const WaterVolume& water, const Vec3& gravity, float dt);

}  // namespace haif
