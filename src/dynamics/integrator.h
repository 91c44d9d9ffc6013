// Semi-implicit (symplectic) Euler integration of body velocities and positions; free rotation by the
// implicit midpoint rule (energy and angular momentum kept).
#pragma once

#include "core/body_store.h"

#include <cstdint>

namespace haif {

/// v += dt (g + F/m), w += dt I^-1 τ, then damping; for awake dynamic bodies in [begin, end).
/// User forces and torques are consumed (zeroed).
void integrateVelocities(BodyStore& bodies, uint32_t begin, uint32_t end, const Vec3& gravity, float dt);

/// x += dt v and a rotation for awake dynamic and kinematic bodies in [begin, end).
/// A free dynamic body takes the implicit midpoint rule on Euler's equations in its frame: it turns by
/// the Cayley rotation of dt w_mid (w_mid from a few Newton steps) and its new w reads the unchanged
/// world angular momentum L in the new frame. That keeps L (hence |L|) and the rotational energy exactly
/// (to the Newton tolerance and rounding), so a spinning body precesses and flips as a real one does and
/// a body with one small moment (a thin rod) never spins up. (The former update, the same but turning by
/// the start w, kept L yet gained energy: +240 % in 20 s for a box spun about its intermediate axis.)
/// A kinematic body turns by its w (Cayley rotation of dt w).
/// A body flagged implicitGyro (one with joints) turns by its w and takes one Newton step of implicit
/// Euler on Euler's equations: it damps, where an energy-keeping update fed energy into a spinning body
/// whose rotation a joint constrains (a rod pinned at its end and spun about its axis gained 40x in 10 s).
/// Also updates the rest timers used for sleeping.
void integratePositions(BodyStore& bodies, uint32_t begin, uint32_t end, float dt, float sleepLinear,
                        float sleepAngular);

}  // namespace haif
