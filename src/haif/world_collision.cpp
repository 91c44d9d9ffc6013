// The collision stage: broad phase (moved bodies' new pairs) and narrow phase (each pair's
// manifold, impulses carried over to the matching points, anchors, what later stages read).
#include "haif/world_internal.h"

#include "collision/collide.h"
#include "collision/compound.h"
#include "dynamics/friction_patch.h"

#include <algorithm>

namespace haif {

namespace {

// Moved bodies whose broad-phase queries one task runs: a query is a few microseconds.
constexpr uint32_t kPairQueryGrain = 64;

/// An old contact point this close (m) to a new one passes on its impulse when ids do not match.
constexpr float kWarmStartMatchDistance = 0.02f;

// What the narrow phase notes of a pair for the serial pass after it (collision_.pairFlags).
constexpr uint8_t kPairWakes = 1;  // touching state changed: its bodies wake
constexpr uint8_t kPairApart = 2;  // no points and the fat boxes separated: the contact goes

}  // namespace

Contact World::newContact(uint32_t a, uint32_t b) const {
  Contact c;
  c.a = std::min(a, b);
  c.b = std::max(a, b);
  c.friction = std::sqrt(bodies_.friction[a] * bodies_.friction[b]);
  c.restitution = std::max(bodies_.restitution[a], bodies_.restitution[b]);
  // Either surface's resistance acts (a ball on carpet, a rubber ball on a floor), at the radius of
  // the one that rolls.
  c.rollingLever = std::max(bodies_.rollingResistance[a], bodies_.rollingResistance[b]) *
                   std::max(bodies_.rollingRadius[a], bodies_.rollingRadius[b]);
  c.toleranceScale = pairToleranceScale(toleranceScale_[a], toleranceScale_[b]);
  return c;
}

void World::updateBroadPhase() {
  const uint32_t n = bodyCount();
  const float dt = settings_.dt;
  // Tight boxes (kept for buoyancy, metrics and the narrow phase's quick reject), then each swept
  // by this step's motion so fast bodies find their pairs before they pass through them.
  collision_.leftFat.resize(n);
  parallelFor(n, kBoundsGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i) {
      collision_.leftFat[i] = 0;
      if (bodies_.kind[i] == BodyKind::Static || bodies_.asleep[i]) continue;
      bounds_[i] = computeAabb(shapes_[i], bodies_.xf[i]);
      collision_.leftFat[i] = !broadPhase_.fits(i, bounds_[i].swept(dt * bodies_.v[i]));
    }
  });
  // A dynamic body that touched nothing last step (alone in its island) is in flight: its fat box
  // reaches kFlightLeadSteps steps of its path ahead. A falling pile re-inserted and queried every
  // body every step (most of a 10^4-body pour's step); a churning pile keeps tight boxes (leading
  // every body's box 4 steps made the swept pit 7.6 % slower).
  const uint32_t islandCount = uint32_t(islands_.islands.size());
  auto inFlight = [&](uint32_t i) {
    const int32_t k = islandOfBody_[i];
    if (k < 0 || uint32_t(k) >= islandCount) return false;
    const Island& isl = islands_.islands[k];
    return isl.bodyCount == 1 && isl.unconstrained();
  };
  // Bodies that left their fat boxes get new ones. Moved one by one, each costs a removal and an
  // insertion with rotations (serial); when many moved (a churning pile), the tree is built afresh
  // instead, which costs less and queries faster (kRebuildShare).
  const auto left = std::count(collision_.leftFat.begin(), collision_.leftFat.end(), uint8_t(1));
  const bool rebuild = left > 0 && float(left) >= kRebuildShare * float(broadPhase_.movingTree().proxyCount());
  for (uint32_t i = 0; i < n; ++i) {
    if (!collision_.leftFat[i]) continue;
    const Vec3 d = dt * bodies_.v[i];
    const Vec3 lead = inFlight(i) ? Vec3(float(kFlightLeadSteps) * d) : Vec3::Zero();
    broadPhase_.move(i, bounds_[i].swept(d), lead, rebuild);
  }
  stats_.treeRebuilt = rebuild;
  if (rebuild) broadPhase_.rebuildMovingTree([&](auto&& buildSide) {
    parallelFor(2, 1, [&](uint32_t begin, uint32_t end) {
      for (uint32_t k = begin; k < end; ++k) buildSide(int(k));
    });
  });
  // New pairs: the moved bodies' queries run in parallel, a list per run of kPairQueryGrain of
  // them (a churning pile re-inserts most of its bodies every step, and the queries were a sixth
  // of a swept pit's step, serial); the lists are then joined in order, so the contacts are made
  // in the same order whatever the threads.
  auto wanted = [&](uint32_t a, uint32_t b) {
    const bool dynA = bodies_.kind[a] == BodyKind::Dynamic, dynB = bodies_.kind[b] == BodyKind::Dynamic;
    if (!dynA && !dynB) return false;  // static/kinematic pairs need no contact
    const uint64_t key = PairMap::key(a, b);
    if (jointPairs_.find(key) != PairMap::kNotFound) return false;  // jointed bodies do not collide
    return pairs_.find(key) == PairMap::kNotFound;
  };
  const std::vector<uint32_t>& moved = broadPhase_.moved();
  const uint32_t movedCount = uint32_t(moved.size());
  // Many queries (a churning pile): they read a four-wide copy of the trees (collision/wide_tree.h),
  // which finds the same pairs in the same order for ~60 % of the cost.
  if (float(movedCount) >= kWideQueryShare * float(broadPhase_.movingTree().proxyCount())) broadPhase_.prepareQueries();
  const uint32_t runs = (movedCount + kPairQueryGrain - 1) / kPairQueryGrain;
  if (collision_.newPairRuns.size() < runs) collision_.newPairRuns.resize(runs);
  parallelFor(runs, 1, [&](uint32_t begin, uint32_t end) {
    for (uint32_t r = begin; r < end; ++r) {
      std::vector<std::pair<uint32_t, uint32_t>>& found = collision_.newPairRuns[r];
      found.clear();
      const uint32_t last = std::min(movedCount, (r + 1) * kPairQueryGrain);
      for (uint32_t i = r * kPairQueryGrain; i < last; ++i)
        broadPhase_.queryMoved(moved[i], [&](uint32_t a, uint32_t b) {
          if (wanted(a, b)) found.emplace_back(a, b);
        });
    }
  });
  uint32_t created = 0;
  for (uint32_t r = 0; r < runs; ++r) {
    for (const auto& [a, b] : collision_.newPairRuns[r]) {
      pairs_.set(PairMap::key(a, b), static_cast<uint32_t>(contacts_.size()));
      contacts_.push_back(newContact(a, b));
      ++created;
    }
  }
  broadPhase_.clearMoved();
  stats_.newPairs = created;
}

namespace {

// What the stages after the narrow phase need of a contact, copied while it is in cache. `apart`:
// how far apart a pair without points is known to be (the margin it was collided with).
inline void noteEdge(const Contact& c, ContactEdge& edge, float apart, bool fresh) {
  edge.fresh = fresh && c.manifold.count > 0;
  edge.count = uint8_t(c.manifold.count);
  edge.deepest = c.manifold.count > 0 ? c.manifold.deepest() : -apart;
  edge.nearest = c.manifold.count > 0 ? c.manifold.nearest() : -apart;
  edge.overlapping = edge.deepest > 0.0f;
}

// A pair placed at rest with every point apart by less than the skin hovers: it counts as touching
// (SolverParams::skin). It keeps hovering while every point stays apart within the skin; once a point
// touches, or the pair leaves the skin, it is an ordinary contact for as long as it lives.
inline void noteHovering(Contact& c, bool fresh, bool atRest, float skin) {
  if (!fresh && !c.hovering) return;
  bool within = c.manifold.count > 0 && (atRest || !fresh);
  for (int i = 0; i < c.manifold.count && within; ++i)
    within = c.manifold.points[i].depth < 0.0f && c.manifold.points[i].depth > -skin;
  c.hovering = within;
}

// Sets a touching contact's static friction anchor where its points are now, unless it holds one
// that has drifted less than kAnchorSlip along the contact; a contact without points lets go.
constexpr float kAnchorSlip = 0.02f;  // m: more is a slide, not a drift to pull back
inline void updateAnchor(Contact& c, const Transform& xa, const Transform& xb) {
  const int m = c.manifold.count;
  if (m == 0) {
    c.anchored = false;
    return;
  }
  // At the centre of the friction patch, where prepareContact's friction acts.
  const float floor = frictionPatchFloor(c.manifold.nearest(), c.toleranceScale);
  Vec3 centre = Vec3::Zero(), n = Vec3::Zero();
  int patch = 0;
  for (int i = 0; i < m; ++i) {
    n += c.manifold.points[i].normal;
    if (c.manifold.points[i].depth < floor) continue;
    centre += c.manifold.points[i].position;
    ++patch;
  }
  centre /= float(patch);
  if (c.anchored) {
    const Vec3 drift = xb.apply(c.anchorB) - xa.apply(c.anchorA);
    const float along = n.squaredNorm() > 0.0f ? drift.dot(n) / n.norm() : 0.0f;
    if (drift.squaredNorm() - along * along <= kAnchorSlip * kAnchorSlip) return;
  }
  c.anchorA = xa.applyInverse(centre);
  c.anchorB = xb.applyInverse(centre);
  c.anchored = true;
}

bool rolls(const Shape& s) {
  if (s.type == ShapeType::Compound) return s.compound->roundParts;
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule;
}

}  // namespace

float World::spinReach(uint32_t body) const {
  return shapes_[body].type == ShapeType::Compound ? bodies_.w[body].norm() * speedBound_.reach(body) : 0.0f;
}

void World::narrowPhase() {
  const uint32_t n = static_cast<uint32_t>(contacts_.size());
  collision_.pairFlags.resize(n);
  collision_.reusedFlag.assign(n, 0);
  contactEdges_.resize(n);
  auto active = [&](uint32_t i) {
    return bodies_.kind[i] == BodyKind::Kinematic || (bodies_.kind[i] == BodyKind::Dynamic && !bodies_.asleep[i]);
  };
  const float fallStep = settings_.gravity.norm() * settings_.dt * settings_.dt;
  // Anchors are kept only while the solver pulls them (World::solverParams): a world where rest
  // damping holds the creep holds none (the pass was 5 % of many_pyramids' step at one sweep), and
  // sets them where its pairs stick once it pulls again.
  const bool anchors = solverParams().frictionAnchors;
  // Placed at rest: closing no faster than twice what gravity adds in a step (the cold start's rule).
  const float skin = settings_.contact.skin;
  const float atRestClosing = 2.0f * fallStep;
  // A kinematic body whose surface closes a point's gap within the step presses the dynamic body
  // as an overlapping one does: the speculative row asks it to move away. Left out, a body between
  // a paddle's tip and a wall (the tip 3 mm off, closing) was not pinched, and the two rows' fight
  // threw it at 19 m/s.
  auto closesPastItsGap = [&](const Contact& c) {
    const bool kinematicA = bodies_.kind[c.a] == BodyKind::Kinematic;
    if (!kinematicA && bodies_.kind[c.b] != BodyKind::Kinematic) return false;
    const uint32_t kinematic = kinematicA ? c.a : c.b;
    const float toward = kinematicA ? 1.0f : -1.0f;  // normals point from A into B
    for (int i = 0; i < c.manifold.count; ++i) {
      const ContactPoint& p = c.manifold.points[i];
      if (toward * p.normal.dot(bodies_.velocityAt(kinematic, p.position)) * settings_.dt > -p.depth) return true;
    }
    return false;
  };
  auto anchor = [&](Contact& c, const Transform& xa, const Transform& xb) {
    if (anchors) updateAnchor(c, xa, xb);
    else c.anchored = false;
  };
  // Apart (WorldSettings::splitApartContacts): every point farther off than the pair's reach (the
  // slop and a fall's step, as World::outOfReach) and what its two bodies can close this step, each
  // at its own speed: the solve may stop either one (a layer landing on the one below, both falling,
  // closes at the upper one's speed). Such a contact holds nothing this step, so it joins no
  // islands (IslandBuilder).
  auto apartThisStep = [&](uint32_t ci, const Contact& c) {
    if (!settings_.splitApartContacts || c.hovering) return false;  // hovering within the skin: touching
    if (!bodies_.isDynamic(c.a) || !bodies_.isDynamic(c.b)) return false;  // joins nothing either way
    const float closes = (bodies_.v[c.a].norm() + bodies_.v[c.b].norm() + spinReach(c.a) + spinReach(c.b)) * settings_.dt;
    return outOfReach(ci, fallStep + closes);  // reads the edge noteEdge has just written
  };
  // Every pair ends here: its edge written, and the removal test made (two tree nodes a pair: here,
  // in parallel, not in the serial pass).
  auto finish = [&](uint32_t ci, const Contact& c, ContactEdge& edge, bool againstImmovable, float apart,
                    bool fresh = false) {
    noteEdge(c, edge, apart, fresh);
    edge.apart = apartThisStep(ci, c);
    edge.pressedByImmovable = againstImmovable && (edge.overlapping || closesPastItsGap(c));
    if (edge.count == 0 && !broadPhase_.fatOverlap(edge.a, edge.b)) collision_.pairFlags[ci] |= kPairApart;
  };
  parallelFor(n, kPairGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t ci = begin; ci < end; ++ci) {
      // A contact spans six cache lines and a pair's work is short: the next ones are asked for
      // ahead (their first touch was a fifth of this loop's own time in the swept pit).
      if (ci + kPrefetchAhead < end) prefetchContact(contacts_[ci + kPrefetchAhead]);
      Contact& c = contacts_[ci];
      collision_.pairFlags[ci] = 0;
      c.pinched = false;  // PinchDetector::mark sets it again
      ContactEdge& edge = contactEdges_[ci];
      edge.a = c.a;
      edge.b = c.b;
      // A small body's pair has its tolerances scaled down (haif/small_bodies.h); 1 leaves them as set.
      const float margin = settings_.contactMargin * c.toleranceScale;
      if (!active(c.a) && !active(c.b)) {  // sleeping or static on both sides: keep the manifold
        finish(ci, c, edge, false, margin);
        continue;
      }
      // One side solved, the other static or kinematic: what pinches are made of (haif/pinch.h).
      const bool solvedA = bodies_.isAwakeDynamic(c.a), solvedB = bodies_.isAwakeDynamic(c.b);
      const bool againstImmovable = solvedA != solvedB && !bodies_.isDynamic(solvedA ? c.b : c.a);
      const Transform &xa = bodies_.xf[c.a], &xb = bodies_.xf[c.b];
      // Speculative margin: as far as the pair closes in one step, uncapped, so a small fast body meets a
      // thin wall the step before it would pass it (a 1 m cap let 5 cm bodies through above 60 m/s). It
      // only widens pairs the swept broad-phase boxes already found, and resting pairs keep the base margin.
      const float rel = (bodies_.v[c.b] - bodies_.v[c.a]).norm() * settings_.dt;
      // A pair that barely moves against each other keeps its manifold (a landing one may need points
      // it does not have yet, so it is made again). Gravity has just been added to the velocities, so
      // a body resting on a static one closes by g dt² a step before the solver stops it.
      // A sphere or capsule rolls: its contact stays under its centre while a point fixed in it turns
      // away, and the turned normal pushed a ball rolling at 1 cm/s up to 14 cm/s in 5 s. Those
      // pairs are cheap to collide and always made again (nor remembered).
      const bool reusable = settings_.reuseManifolds && !rolls(shapes_[c.a]) && !rolls(shapes_[c.b]);
      ManifoldReuseLimits reuseLimits;
      reuseLimits.slide *= c.toleranceScale;
      reuseLimits.margin = margin;
      const float restingClosing = reuseLimits.slide + fallStep;
      if (reusable && rel < restingClosing && refreshManifold(c.cache, xa, xb, reuseLimits, c.manifold)) {
        collision_.reusedFlag[ci] = 1;
        noteHovering(c, false, true, skin);
        anchor(c, xa, xb);
        finish(ci, c, edge, againstImmovable, margin);
        continue;  // same points and ids: the impulses stay where they are
      }
      const Manifold old = c.manifold;
      // A compound's parts sit away from its centre and sweep |ω| r a second besides its centre's
      // motion: a hammer's head turning at 8 rad/s on a 0.45 m handle went through an 8 cm table top
      // that the margin of its centre's speed missed. Single shapes keep the linear margin: on every
      // body the spin term cost the swept pit 58 % of its step and lowered no pour's penetration.
      const float spin = (spinReach(c.a) + spinReach(c.b)) * settings_.dt;
      // A pair stays while its fat boxes overlap, but two in three of a churning pile's pairs are
      // farther apart than the margin: their tight boxes, widened by it, already say no point can be.
      const float reach = margin + rel + spin;
      if (bounds_[c.a].expanded(reach).overlaps(bounds_[c.b])) collide(shapes_[c.a], xa, shapes_[c.b], xb, reach, c.manifold);
      else c.manifold.count = 0;
      if (reusable) rememberManifold(c.manifold, xa, xb, c.cache);
      // Carry accumulated normal impulses over to the points that touch the same features; when
      // the feature ids changed (a reference face switched), fall back to the nearest old point.
      // Friction lives at the manifold's centre and carries over as it is.
      float normal[kMaxManifoldPoints];
      for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint& np = c.manifold.points[i];
        int match = -1;
        float best = kWarmStartMatchDistance * kWarmStartMatchDistance;
        for (int j = 0; j < old.count; ++j) {
          if (old.points[j].id == np.id) {
            match = j;
            break;
          }
          const float d2 = (old.points[j].position - np.position).squaredNorm();
          if (d2 < best) {
            best = d2;
            match = j;
          }
        }
        normal[i] = match >= 0 ? c.normalImpulse[match] : 0.0f;
      }
      for (int i = 0; i < c.manifold.count; ++i) c.normalImpulse[i] = normal[i];
      if (c.manifold.count == 0) {
        c.frictionImpulse.setZero();
        c.twistImpulse = 0.0f;
      }
      if ((old.count > 0) != (c.manifold.count > 0)) collision_.pairFlags[ci] = kPairWakes;
      noteHovering(c, old.count == 0, rel <= atRestClosing, skin);
      anchor(c, xa, xb);
      finish(ci, c, edge, againstImmovable, reach, old.count == 0);
    }
  });

  for (const uint8_t reused : collision_.reusedFlag) stats_.manifoldsReused += reused;
  // Destroy contacts whose fat boxes separated; wake sleeping bodies whose contacts changed. It reads
  // the flags the narrow phase left, not the contacts (a pass over those took ~0.4 ms in
  // many_pyramids) nor the tree (two nodes a pair: a third of this pass in a churning drum).
  for (uint32_t ci = 0; ci < contacts_.size();) {
    const uint8_t flags = collision_.pairFlags[ci];
    if (flags == 0) {
      ++ci;
      continue;
    }
    const ContactEdge c = contactEdges_[ci];
    if (flags & kPairWakes) {
      wake(c.a);
      wake(c.b);
    }
    if (flags & kPairApart) {
      pairs_.erase(PairMap::key(c.a, c.b));
      const uint32_t last = static_cast<uint32_t>(contacts_.size() - 1);
      if (ci != last) {
        contacts_[ci] = contacts_[last];
        collision_.pairFlags[ci] = collision_.pairFlags[last];
        contactEdges_[ci] = contactEdges_[last];
        pairs_.set(PairMap::key(contacts_[ci].a, contacts_[ci].b), ci);
      }
      contacts_.pop_back();
      collision_.pairFlags.pop_back();
      contactEdges_.pop_back();
      continue;
    }
    ++ci;
  }
}

}  // namespace haif
