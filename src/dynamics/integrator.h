// Semi-implicit (symplectic) Euler integration of body velocities and positions.
#pragma once

#include "core/body_store.h"

#include <cstdint>

namespace haif {

/// v += dt (g + F/m), w += dt I^-1 τ, then damping; for awake dynamic bodies in [begin, end).
/// User forces and torques are consumed (zeroed).
void integrateVelocities(BodyStore& bodies, uint32_t begin, uint32_t end, const Vec3& gravity, float dt);

/// x += dt v, q += dt/2 (w ⊗ q) for awake dynamic and kinematic bodies in [begin, end).
/// The gyroscopic effect is applied by keeping the world angular momentum L = I_w w of a dynamic
/// body unchanged across its rotation: w_new = I_w(q_new)^-1 I_w(q_old) w. Free flight therefore
/// conserves L to rounding, and a spinning body precesses and flips as a real one does.
/// A body flagged implicitGyro (one with joints) takes instead one Newton step of implicit Euler on
/// Euler's equations in its frame: the explicit update feeds energy into a spinning body whose rotation a
/// joint constrains (a rod pinned at its end and spun about its axis gained 40x its energy in 10 s).
/// Also updates the rest timers used for sleeping.
void integratePositions(BodyStore& bodies, uint32_t begin, uint32_t end, float dt, float sleepLinear,
                        float sleepAngular);

}  // namespace haif
