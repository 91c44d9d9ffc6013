// Rest damping: the micro-motion a resting pile keeps, taken away.
//
// A warm-started solve leaves a small part of each step's load unsolved. In a resting pile that leak
// is a velocity of micrometres per second; inside the slop nothing pushes back, so it integrates into
// the poses, and where a pose change moves load onto what sank (a wall of boxes leaning out of its
// plane) it feeds itself: `large_pyramid` grew an out-of-plane lean from float noise by ~2.5 % a step
// at 10 iterations and collapsed after ~700 steps (docs/solver.md, "Rest damping").
// Real contacts at rest have no such creep, so a body that touches something and moves slower than a
// small fraction of what gravity adds in one step is slowed before its pose moves, the more the slower
// it is: v' = v (s / s₀)² for a body speed s below s₀ (continuous at s₀; the mass-normalised kinetic
// energy, rotation included, gives s). Bodies in free flight or held only by joints are left alone,
// and nothing faster than s₀ is touched, so impacts, slides and swings keep their momentum.
// Speeds are taken relative to the island's carrier, the first kinematic body it touches
// (Island::carrier), as it moves there: a pile riding a platform rests on it. Measured against the
// world such a pile was never slow, so never damped: a pyramid of 820 boxes on a platform that
// started at 0.5 m/s still swayed by ±0.1 m/s after 900 steps.
#pragma once

#include "core/body_store.h"
#include "haif/islands.h"

#include <cstdint>

namespace haif {

/// The speed s₀ (m/s) below which bodies in contact are slowed: `fraction` of |g| dt (0 off).
inline float restDampingSpeed(float fraction, const Vec3& gravity, float dt) { return fraction * gravity.norm() * dt; }

/// Slows the awake dynamic bodies in [begin, end) that belong to an island with contacts and move
/// slower than `speed` (see above). islandOfBody: each body's index in `islands`, or -1.
void dampRestingMotion(BodyStore& bodies, const int32_t* islandOfBody, const IslandSet& islands, float speed,
                       uint32_t begin, uint32_t end);

}  // namespace haif
