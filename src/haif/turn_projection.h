// Pairs a fast turn carried into each other.
//
// A contact's rows are linear in the bodies' motion over the step, about the points the narrow
// phase found at its start. A body that picks up a fast spin within the step (a hull landing on an
// edge at 14 m/s spins up to 30-40 rad/s, a capsule struck off centre turns on its single point)
// turns 0.5-0.7 rad before the next narrow phase, and corners that were not among the points, or
// not near, end up 0.2 m deep in what it landed on: the deepest contacts of every poured pile. So
// after the step, the contacts of each body that turned more than an angle are collided again at
// the poses the step ended on, and a pair deeper than a keep depth is moved apart by the excess,
// positions only (its velocities stay the solver's). Lowest pairs first, and a pair whose normal
// is mostly along `up` moves only its upper body, so a correction is not pushed back into the
// support below (a light body under a heavy one that landed on it would be driven into the
// ground). A body moved may now overlap a neighbour whose pair was not collided again: its pairs
// are taken in the next round, for a few rounds.
// Only depth the step added is taken out: a pair already that deep when the step began (a body
// crushed in a churning pile) is the solver's to push out. Spheres turn without changing where
// their surface is; bodies in islands with joints would have their joints pulled apart, and a
// kinematic body cannot give way: all three are left out.
#pragma once

#include "collision/shape.h"
#include "core/body_store.h"
#include "dynamics/contact.h"
#include "haif/islands.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace haif {

struct TurnProjectionSettings {
  /// A body counts as turned when |ω| dt exceeds this (rad): a linearisation about the step's
  /// first points holds to a few mm below it for bodies of a metre. 0 turns the stage off.
  float angle = 0.1f;
  /// Depth (m) left in place: the solver's own push-out settles shallow overlap gently.
  float keep = 0.01f;
};

class TurnProjection {
 public:
  /// Applies the stage to the contacts (all narrow-phase pairs of this step, their manifolds from
  /// the step's start, and `edges`, their ContactEdge per contact) with the bodies' final poses;
  /// `islandOfBody` and `islands` are the step's.
  /// Reads bodies in index order and pairs in height order, so the result does not depend on
  /// threads. Returns the number of pairs moved apart.
  uint32_t apply(BodyStore& bodies, const std::vector<Shape>& shapes, const std::vector<Contact>& contacts,
                 const ContactEdge* edges, const int32_t* islandOfBody, const IslandSet& islands, const Vec3& up,
                 float dt, const TurnProjectionSettings& settings);

 private:
  std::vector<uint8_t> active_;  // per body: turned this step (round 1), or moved by the last round
  std::vector<uint8_t> done_;    // per contact: collided again already
  std::vector<uint8_t> held_;    // per body: touches a kinematic body
  std::vector<std::pair<float, uint32_t>> pairs_;  // (height, contact) of the pairs to collide again
};

}  // namespace haif
