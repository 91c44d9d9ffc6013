// A persistent contact between two bodies: the latest manifold plus the impulses accumulated by
// the solver, carried from step to step (matched by feature id) for warm starting.
#pragma once

#include "collision/manifold.h"
#include "collision/manifold_cache.h"
#include "core/growing_array.h"

#include <cstdint>

namespace haif {

struct Contact {
  uint32_t a = 0, b = 0;           ///< body ids; the narrow phase sees shape a first
  float friction = 0.6f;
  float restitution = 0.0f;
  Manifold manifold;
  float normalImpulse[kMaxManifoldPoints] = {};  ///< accumulated along each point's normal (N s)
  Vec3 frictionImpulse = Vec3::Zero();  ///< accumulated tangential impulse at the manifold centre, world (N s)
  float twistImpulse = 0.0f;            ///< accumulated friction impulse about frictionNormal (N m s)
  Vec3 frictionNormal = Vec3::Zero();   ///< the axis twistImpulse was accumulated about
  ManifoldCache cache;                  ///< the manifold as last made, for reuse while the bodies keep still
  /// Static friction anchor: one material point in each body, at the manifold's centre when the pair
  /// last started sticking (body frames). Friction pulls their tangential drift back (prepareContact).
  Vec3 anchorA = Vec3::Zero(), anchorB = Vec3::Zero();
  bool anchored = false;
  /// The dynamic body of this contact is pressed from opposite sides by bodies that cannot move
  /// (static or kinematic; haif/pinch.h): no push-out, no impulse carried between steps.
  bool pinched = false;
  /// The pair was placed at rest with every point apart by less than the contact skin
  /// (SolverParams::skin), and has stayed so: it counts as touching, so no gap is closed
  /// (World::narrowPhase sets it, prepareContact reads it).
  bool hovering = false;
  /// Steps its island is still solved exactly after a landing in it (World::solveIslands): the
  /// landing's impulses are no warm start for sweeps at a mass ratio until the island has settled.
  uint8_t exactSteps = 0;
  // Rolling resistance, last: the fields above keep the offsets the narrow phase and the solver's
  // stages read them at (placed among them, those stages took 8-20 % more samples in many_pyramids).
  /// Most rolling-resistance torque per unit normal force (m): the larger coefficient of the two
  /// bodies times the larger rolling radius (BodyStore::rollingRadius). 0: no rolling row.
  float rollingLever = 0.0f;
  Vec3 rollingImpulse = Vec3::Zero();  ///< accumulated rolling-resistance impulse on b, world (N m s)
  /// The pair's factor on the contact tolerances (slop, margins, manifold reuse): its thinner body's
  /// (haif/small_bodies.h), 1 for bodies of ordinary size. Set when the pair is made.
  float toleranceScale = 1.0f;
  bool touching() const { return manifold.count > 0; }
};

/// The world's contacts: one array, grown in place as pairs are found (core/growing_array.h).
using ContactList = GrowingArray<Contact>;

/// Contacts a loop over scattered contacts fetches ahead of the one it works on.
constexpr uint32_t kPrefetchAhead = 6;

/// Asks for every cache line of a contact (a hint only: nothing changes if it is ignored).
inline void prefetchContact(const Contact& c) {
  const char* p = reinterpret_cast<const char*>(&c);
  for (size_t at = 0; at < sizeof(Contact); at += 64) __builtin_prefetch(p + at);
}

}  // namespace haif
