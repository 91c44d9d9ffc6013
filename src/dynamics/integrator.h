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

/// A body whose only joint holds one of its points at a fixed place (BodyStore::pinned).
struct PinnedBody {
  uint32_t body = 0;
  Vec3 anchor = Vec3::Zero();  ///< the held point, in the body's frame (from its centre of mass)
  Vec3 point = Vec3::Zero();   ///< where it is held (world)
};

/// Moves a pinned body (integratePositions leaves it): a free rigid body turning about the held point,
/// by the same implicit midpoint rule with the inertia about that point, its angular momentum about
/// the point kept; its centre is then placed from the point and its velocity read from its turn, so
/// the joint holds exactly. Turning about its centre instead, a fast spinner's anchor left the point
/// by a few mm a step (a turn of 1 rad about an axis passing 4 mm from it), and the joint projection
/// that put it back tipped the spin axis without turning its momentum: a top spun at 60 rad/s sank
/// to hanging straight down in 3 s instead of precessing.
void integratePinned(BodyStore& bodies, const PinnedBody& pin, const Vec3& gravity, float dt, float sleepLinear,
                     float sleepAngular);

}  // namespace haif
