// Pairs the step carried into each other: by a fast turn, by a crush, by a blow within the step.
//
// A contact's rows are linear in the bodies' motion over the step, about the points the narrow
// phase found at its start. Three things carry a pair deeper than those rows can see:
// - a fast turn: a body that picks up a spin within the step (a hull landing on an edge at 14 m/s
//   spins up to 30-40 rad/s, a capsule struck off centre turns on its single point) turns 0.5-0.7
//   rad, and corners that were not among the points end up 0.2 m deep in what it landed on;
// - a crush: a heavy body landing on a light one that rests on others. Gauss-Seidel passes the
//   support up such a chain a fraction m/(m+M) a sweep, so after ten sweeps a 119 kg ball still
//   sank at 4 m/s into an 11 kg box on the ground, 0.22 m deep in three steps;
// - a blow within the step: a pair farther apart at the start than it then closed has no point (a
//   ball falling at 12 m/s was stopped by what it landed on and met by one at 13 m/s, 8 cm deep).
// So after the step, the pairs of each body that turned more than an angle, and the pairs whose
// points, read linearly with the final velocities (or, without points, whose final boxes overlap),
// end deeper than they may keep, are collided again at the poses the step ended on, and a pair
// deeper than its target is moved apart by the excess, positions only (its velocities stay the
// solver's). A pair keeps the depth it began the step with, within [keep, crushKeep]; depth it
// began with beyond that goes by crushRecover a step (bodies spawned into each other come apart
// as gently as the solver would part them). Lowest pairs first, and a pair whose normal is mostly
// along `up` moves only its upper body, so a correction is not pushed back into the support below
// (a light body under a heavy one would be driven into the ground). A body moved may now overlap
// a neighbour: its pairs are taken in the next round, those collided earlier in the step too (a
// box lifted 8 cm out of the box under it was left 0.107 m deep in the one resting on it, a pair
// the first round had found apart), for up to six rounds (a poured pile of boxes needs four).
// Resting pairs (depth under keep, no motion) are never collided again. A sphere's turn does not
// move its surface (its crushes are taken); bodies in islands with joints would have their joints
// pulled apart, a kinematic body cannot give way, and a body pinched between immovable ones
// (haif/pinch.h) goes out of one into the other: those are left out.
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
  /// Depth (m) a pair that began the step deeper is brought back to. 0 leaves such pairs alone.
  float crushKeep = 0.03f;
  /// Depth (m) such a pair loses a step beyond what the step added, positions only (1.2 m/s).
  float crushRecover = 0.02f;
};

class TurnProjection {
 public:
  /// Applies the stage to the contacts (all narrow-phase pairs of this step, their manifolds from
  /// the step's start, and `edges`, their ContactEdge per contact) with the bodies' final poses;
  /// `islandOfBody` and `islands` are the step's, `reach` each body's bounding radius about its
  /// centre, `contactMargin` the narrow phase's base margin.
  /// Reads bodies in index order and pairs in height order, so the result does not depend on
  /// threads. Returns the number of pairs moved apart.
  uint32_t apply(BodyStore& bodies, const std::vector<Shape>& shapes, const std::vector<Contact>& contacts,
                 const ContactEdge* edges, const int32_t* islandOfBody, const IslandSet& islands, const Vec3& up,
                 const float* reach, float dt, float contactMargin, const TurnProjectionSettings& settings);

 private:
  std::vector<uint8_t> active_;  // per body: turned this step (round 1), or moved by the last round
  std::vector<float> motion_;     // per body: |v| + |w| reach, the fastest any point of it moves
  std::vector<uint8_t> crushed_;  // per contact: driven deeper than its target by the step's velocities
  std::vector<uint8_t> held_;     // per body: touches a kinematic body, or pinched: not moved
  std::vector<uint32_t> movedAt_;     // per body: the move clock when it last moved (0: not this step)
  std::vector<uint32_t> collidedAt_;  // per contact: the move clock when it was last collided again
  std::vector<std::pair<float, uint32_t>> pairs_;  // (height, contact) of the pairs to collide again
};

}  // namespace haif
