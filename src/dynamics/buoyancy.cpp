#include "dynamics/buoyancy.h"

namespace haif {

void applyBuoyancy(BodyStore& b, const std::vector<float>& volume, const std::vector<Aabb>& bounds,
                   const WaterVolume& water, const Vec3& gravity, float dt) {
  const uint32_t n = static_cast<uint32_t>(b.size());
  for (uint32_t i = 0; i < n; ++i) {
    if (b.kind[i] != BodyKind::Dynamic || b.asleep[i]) continue;
    const Aabb& box = bounds[i];
    if (!box.overlaps(water.box)) continue;
    const Vec3 c = box.center();
    if (c.x() < water.box.lo.x() || c.x() > water.box.hi.x() || c.z() < water.box.lo.z() || c.z() > water.box.hi.z())
      continue;
    const float height = std::max(box.hi.y() - box.lo.y(), 1e-6f);
    const float top = std::min(box.hi.y(), water.box.hi.y());
    const float bottom = std::max(box.lo.y(), water.box.lo.y());
    const float fraction = std::clamp((top - bottom) / height, 0.0f, 1.0f);
    if (fraction <= 0.0f) continue;
    // Archimedes: the displaced water's weight, acting at the centre of the submerged slab.
    const Vec3 force = -water.density * volume[i] * fraction * gravity;
    const Vec3 centre(c.x(), 0.5f * (top + bottom), c.z());
    b.v[i] += dt * b.invMass[i] * force;
    b.w[i] += dt * (b.invInertiaWorld[i] * (centre - b.xf[i].p).cross(force));
    b.v[i] *= 1.0f / (1.0f + dt * water.linearDrag * fraction);
    b.w[i] *= 1.0f / (1.0f + dt * water.angularDrag * fraction);
  }
}

}  // namespace haif
