#include "haif/rest_damping.h"

namespace haif {

void dampRestingMotion(BodyStore& bodies, const int32_t* islandOfBody, const IslandSet& islands, float speed,
                       uint32_t begin, uint32_t end) {
  const float s02 = speed * speed;
  if (!(s02 > 0.0f)) return;
  const float inv02 = 1.0f / s02;
  for (uint32_t i = begin; i < end; ++i) {
    const int32_t k = islandOfBody[i];
    if (k < 0 || islands.islands[uint32_t(k)].contactCount == 0 || !bodies.isAwakeDynamic(i)) continue;
    const Island& isl = islands.islands[uint32_t(k)];
    // The carrier's motion where the body is (none without a carrier).
    const Vec3 carriedW = isl.carrierW;
    const Vec3 carriedV = isl.carrierV + carriedW.cross(bodies.xf[i].p - isl.carrierAt);
    const Vec3 v = bodies.v[i] - carriedV, w = bodies.w[i] - carriedW;
    // Twice the kinetic energy over the mass: v² + ωᵀ I ω / m (ω taken in the body frame).
    const Vec3 wb = bodies.xf[i].q.conjugate() * w;
    const float s2 = v.squaredNorm() + wb.dot(bodies.inertiaLocal[i] * wb) * bodies.invMass[i];
    if (s2 >= s02) continue;
    const float f = s2 * inv02;  // (s / s₀)²
    bodies.v[i] = carriedV + f * v;
    bodies.w[i] = carriedW + f * w;
  }
}

}  // namespace haif
