// Solve order: the contacts of each island top-down, cold contacts started from the weight they
// carry, giant islands split into strips, and lane batches for the wide sweeps.
#include "haif/world_internal.h"

#include "core/sort_key.h"
#include "haif/support_balance.h"

namespace haif {

// Gauss-Seidel order matters for stacking: solving the highest contacts first carries the weight
// of a stack down to the ground within one sweep (bottom-up needs one sweep per layer). Against
// gravity, a 100-layer pyramid at 10 iterations dropped 1.6 m on average bottom-up, 0.08 m top-down.
void World::orderContactsTopDown() {
  const Vec3 up = upDirection();
  order_.contactHeight.resize(contacts_.size());
  order_.keys.resize(islands_.contacts.size());
  const uint32_t* ids = islands_.contacts.data();
  parallelFor(uint32_t(islands_.contacts.size()), kHeightGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t j = begin; j < end; ++j) {
      const ContactEdge& c = contactEdges_[ids[j]];
      float h = up.dot(bodies_.xf[c.a].p + bodies_.xf[c.b].p);
      // A pinched body's static contacts come last, its kinematic ones first: the sweep's last word
      // keeps it out of the static world, and the kinematic body passes it (haif/pinch.h; so do a
      // crushed row's ends).
      if (pinchedBodies_ > 0 && contacts_[ids[j]].pinched) {
        const bool kinematic = bodies_.kind[c.a] == BodyKind::Kinematic || bodies_.kind[c.b] == BodyKind::Kinematic;
        h = kinematic ? std::numeric_limits<float>::max() : std::numeric_limits<float>::lowest();
      }
      order_.contactHeight[ids[j]] = h;
      order_.keys[j] = descendingKey(h, ids[j]);  // top down; ties by index: deterministic
    }
  });
  // Islands own disjoint ranges: sorted concurrently. An island's contacts ascend by index
  // (IslandSet), so its keys are made in index order and sort by a few radix passes.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  order_.scratch.resize(order_.keys.size());
  order_.tail.assign(m, 0);
  // A resting pile's contacts keep their order step after step: checking last step's order costs a
  // pass, sorting again several (and the batching after it more).
  const bool before = islandBuilder_.reused() && order_.sortedStep + 1 == stepCount_ &&
                      order_.sorted.size() == islands_.contacts.size() && order_.tailBefore.size() == m;
  order_.kept.assign(m, 0);
  parallelFor(m, kIslandGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const Island& isl = islands_.islands[k];
      uint64_t* first = order_.keys.data() + isl.firstContact;
      order_.tail[k] = moveOutOfReachToTail(k, first);
      uint32_t* out = islands_.contacts.data() + isl.firstContact;
      if (before && order_.tail[k] == order_.tailBefore[k] && sortsAsLastStep(k)) {
        std::copy_n(order_.sorted.data() + isl.firstContact, isl.contactCount, out);
        order_.kept[k] = 1;
        continue;
      }
      sortKeysMadeInIndexOrder(first, order_.scratch.data() + isl.firstContact, isl.contactCount);
      for (uint32_t j = 0; j < isl.contactCount; ++j) out[j] = keyIndex(first[j]);
    }
  });
  order_.sorted = islands_.contacts;
  order_.tailBefore = order_.tail;
  order_.sortedStep = stepCount_;
}

// Whether island k's contacts, in last step's order, ascend by this step's keys (height from the top,
// then index): the keys are distinct, so that order is the one the sort gives.
bool World::sortsAsLastStep(uint32_t k) const {
  const Island& isl = islands_.islands[k];
  const uint32_t* last = order_.sorted.data() + isl.firstContact;
  auto key = [&](uint32_t ci) { return descendingKey(order_.contactHeight[ci], ci); };
  for (uint32_t j = 1; j < isl.contactCount; ++j)
    if (!(key(last[j - 1]) < key(last[j]))) return false;
  return true;
}

// A stack of thin plates (1 m wide, 2 cm thick) has, besides its chain of contacts, speculative
// ones that reach past a plate to the one below it (the 2 cm margin spans the plate). They made the
// island no chain, and its 30 layers were swept: at 4 to 8 iterations the stack sank into itself
// and sprang back for the whole minute (plates 0.45 m into each other at 4). Such contacts cannot
// act this step unless something closes them fast, so they go to the end of the order: the chain
// before them is solved exactly and they are swept after it, each sweep. Only an island that has
// more contacts than bodies (no chain) and would not without them is reordered.
uint32_t World::moveOutOfReachToTail(uint32_t k, uint64_t* keys) {
  const Island& isl = islands_.islands[k];
  // Islands with joints are never solved as chains (World::solveIslands): their order stays.
  if (!settings_.chainSolve || pinchedBodies_ > 0 || isl.jointCount > 0 || isl.contactCount <= isl.bodyCount)
    return 0;
  const uint32_t* ids = islands_.contacts.data() + isl.firstContact;
  // A pile has more contacts in reach than bodies, and stops here.
  const float fall = fallOfAStep();
  auto apart = [&](uint32_t j) { return outOfReach(ids[j], fall); };
  uint32_t near = 0;
  for (uint32_t j = 0; j < isl.contactCount && near <= isl.bodyCount; ++j) near += apart(j) ? 0u : 1u;
  if (near > isl.bodyCount || near < 2) return 0;  // a chain has two links at least (prepareChain)
  for (uint32_t j = 0; j < isl.contactCount; ++j) {
    if (!apart(j)) continue;
    keys[j] = descendingKey(std::numeric_limits<float>::lowest(), ids[j]);
    order_.contactHeight[ids[j]] = std::numeric_limits<float>::lowest();
  }
  return isl.contactCount - near;
}

// A contact that just formed has no impulse to warm start from. In a pile created at rest every
// contact is new, and sweeps build the support up only a few layers per step: large_pyramid's upper
// half fell for tens of steps, then rebounded. Cold contacts between bodies that are nearly at rest
// relative to each other therefore start from the weight they carry: top-down, each body's own
// weight plus what rests on it is divided among the points holding it up so that it balances
// (haif/support_balance.h). The sweeps correct the estimate; contacts that approach fast (a landing)
// start from zero as before.
void World::estimateColdImpulses() {
  const float g = settings_.gravity.norm();
  if (g <= 0.0f) return;
  const Vec3 up = -settings_.gravity / g;
  // Two directions across the vertical, for the moments of the loads.
  const Vec3 across1 = up.unitOrthogonal(), across2 = up.cross(across1);
  const float dt = settings_.dt;
  const float restSpeed = 2.0f * g * dt;
  const uint32_t nb = bodyCount();
  order_.carried.resize(nb);
  order_.carriedMoment.resize(nb);
  order_.supports.resize(nb);
  order_.firstSupport.resize(nb);
  order_.placed.resize(nb);
  order_.supportContacts.resize(islands_.contacts.size());
  // A support: a vertical-ish contact in reach; its upper body is the one on the normal's upward side.
  // A contact out of reach holds nothing up: counted as a support, it took a share of the load (in a
  // Jenga tower of 1.5 cm blocks the 2 cm margin reaches the block two layers down; the tower sagged
  // on its first step and fell at 10 iterations).
  const float fall = fallOfAStep();
  // The normal's cosine with the vertical: positive when the upper body is b.
  auto slopeOf = [&](uint32_t ci) { return contacts_[ci].manifold.points[0].normal.dot(up); };
  auto upper = [&](uint32_t ci, float& slope) -> int64_t {
    if (outOfReach(ci, fall)) return -1;
    const Contact& c = contacts_[ci];
    slope = slopeOf(ci);
    if (std::fabs(slope) < 0.7f) return -1;
    const uint32_t u = slope > 0.0f ? c.b : c.a;
    return bodies_.isAwakeDynamic(u) ? int64_t(u) : -1;
  };
  // Cold: just made, so no impulse to warm start from (the narrow phase noted that in the contact's
  // edge), and the bodies nearly at rest relative to each other. A contact that has been touching
  // with no load is not cold: the sweeps found it carries nothing (an uphill support of a pile on a
  // slope, where the load moved downhill). Given the weight again every step, a pyramid of 204
  // boxes under gravity tilted 15° crept 1 m in the minute (a quarter of its contacts unloaded), and
  // a wall pyramid leaned out of its plane and fell.
  auto isCold = [&](uint32_t ci) {
    if (!contactEdges_[ci].fresh) return false;
    const Contact& c = contacts_[ci];
    return std::fabs(c.manifold.points[0].normal.dot(bodies_.v[c.b] - bodies_.v[c.a])) <= restSpeed;
  };
  // The body u's load (its weight and what rests on it) divided among the points of its supports,
  // given to the cold ones and passed on, with where it acts, to the bodies below. A body held up by
  // more points than the balance takes (a plank on a bed of balls) shares its load equally.
  constexpr int kBalancedPoints = 64;
  auto carry = [&](uint32_t u, const uint32_t* supports, uint32_t count) {
    const Vec3 centre = bodies_.xf[u].p;
    const float load = bodies_.mass[u] * g * dt + order_.carried[u];
    uint32_t total = 0;
    for (uint32_t s = 0; s < count; ++s) total += uint32_t(contacts_[supports[s]].manifold.count);
    SupportPoint pts[kBalancedPoints];
    bool balanced = false;
    if (total <= uint32_t(kBalancedPoints)) {
      int n = 0;
      for (uint32_t s = 0; s < count; ++s) {
        const Manifold& mf = contacts_[supports[s]].manifold;
        for (int i = 0; i < mf.count; ++i, ++n) {
          const Vec3 d = mf.points[i].position - centre;
          pts[n].x = d.dot(across1);
          pts[n].z = d.dot(across2);
        }
      }
      const Vec2& moment = order_.carriedMoment[u];
      balanced = balanceSupportLoad(pts, n, load, moment.x(), moment.y());
    }
    int k = 0;
    for (uint32_t s = 0; s < count; ++s) {
      Contact& c = contacts_[supports[s]];
      const float slope = slopeOf(supports[s]);
      const uint32_t lower = u == c.a ? c.b : c.a;
      const bool cold = isCold(supports[s]), carries = bodies_.isAwakeDynamic(lower);
      const Vec3 below = bodies_.xf[lower].p;
      for (int i = 0; i < c.manifold.count; ++i, ++k) {
        const float share = balanced ? pts[k].load : load / float(count * uint32_t(c.manifold.count));
        if (cold) c.normalImpulse[i] = share / std::fabs(slope);
        if (!carries) continue;
        const Vec3 d = c.manifold.points[i].position - below;
        order_.carried[lower] += share;
        order_.carriedMoment[lower] += share * Vec2(d.dot(across1), d.dot(across2));
      }
    }
  };
  // Islands share no dynamic body (a static lower body receives nothing): they run concurrently.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  parallelFor(m, kIslandGrain, [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const Island& isl = islands_.islands[k];
      const uint32_t* bodies = islands_.bodies.data() + isl.firstBody;
      const uint32_t* contacts = islands_.contacts.data() + isl.firstContact;
      float slope;
      // A pile that has settled has no cold support left: its loads need not be added up (in
      // large_pyramid that was 0.4 ms a step, serial on its one island).
      bool anyCold = false;
      // Only contacts whose edge says they carry no impulse are read.
      for (uint32_t j = 0; j < isl.contactCount && !anyCold; ++j) {
        const uint32_t ci = contacts[j];
        anyCold = contactEdges_[ci].count > 0 && isCold(ci) && upper(ci, slope) >= 0;
      }
      if (!anyCold) continue;
      for (uint32_t j = 0; j < isl.bodyCount; ++j) {
        order_.carried[bodies[j]] = 0.0f;
        order_.carriedMoment[bodies[j]] = Vec2::Zero();
        order_.supports[bodies[j]] = 0;
        order_.placed[bodies[j]] = 0;
      }
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        const int64_t u = upper(contacts[j], slope);
        if (u >= 0) ++order_.supports[u];
      }
      // Each body's supports, listed together within the island's range of the list.
      uint32_t next = isl.firstContact;
      for (uint32_t j = 0; j < isl.bodyCount; ++j) {
        order_.firstSupport[bodies[j]] = next;
        next += order_.supports[bodies[j]];
      }
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        const int64_t u = upper(contacts[j], slope);
        if (u >= 0) order_.supportContacts[order_.firstSupport[u] + order_.placed[u]++] = contacts[j];
      }
      // Islands' contacts are in top-down order: a body's load is complete when its first support
      // is met, and all its supports are divided then.
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        const int64_t u = upper(contacts[j], slope);
        if (u < 0 || order_.placed[u] == 0) continue;
        order_.placed[u] = 0;  // done
        carry(uint32_t(u), order_.supportContacts.data() + order_.firstSupport[u], order_.supports[u]);
      }
    }
  });
}

// Giant islands without joints are cut into strips for parallel sweeps. The island's largest
// unsplittable piece of work then becomes its critical path, which is what the controller plans with.
void World::splitGiantIslands() {
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  layoutOf_.assign(m, -1);
  const Vec3 up = upDirection();
  uint32_t used = 0, largest = 0;
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    if (isl.rows >= kSplitRows && isl.jointCount == 0) {
      if (layouts_.size() <= used) layouts_.emplace_back();
      splitter_.split(bodies_, contactEdges_.data(), up, islands_, k, layouts_[used], parallelRanges());
      layoutOf_[k] = int32_t(used);
      if (!settings_.wideSolve) assignSlots(used, isl.bodyCount);
      largest = std::max(largest, layouts_[used].criticalRows());
      ++used;
    } else {
      largest = std::max(largest, isl.rows);
    }
  }
  stripResult_.resize(layouts_.size() * (kMaxStrips + 1));
  islands_.largestRows = largest;
}

// The island just split gets a slot per body in strip order (the splitter's ranks), then, from a
// cache line of its own, one per immovable body its rows name (read, never written).
void World::assignSlots(uint32_t layout, uint32_t bodies) {
  if (stripVelocities_.size() <= layout) stripVelocities_.resize(layout + 1);
  if (slotOf_.size() < bodyCount()) slotOf_.resize(bodyCount());
  StripVelocities& sv = stripVelocities_[layout];
  constexpr uint32_t kLine = 16;  // slots: 16 Vec3 are 3 cache lines
  sv.dynamic = bodies;
  sv.immovableSlot = (bodies + kLine - 1) / kLine * kLine;
  sv.immovable = splitter_.immovableBodies();
  const uint32_t slots = sv.immovableSlot + uint32_t(sv.immovable.size());
  sv.bodyOf.resize(slots);
  sv.v.resize(slots);
  sv.w.resize(slots);
  for (uint32_t r = 0; r < bodies; ++r) {
    const uint32_t body = splitter_.bodyAtRank(r);
    sv.bodyOf[r] = body;
    slotOf_[body] = r;
  }
  for (uint32_t r = bodies; r < sv.immovableSlot; ++r) sv.bodyOf[r] = sv.bodyOf[0];  // padding, never read
  std::copy(sv.immovable.begin(), sv.immovable.end(), sv.bodyOf.begin() + sv.immovableSlot);
}

// Each range a sweep runs as one piece (an island, or a strip or tail of a split one) is grouped
// into lane batches: constraints that share no dynamic body side by side. The wide sweep solves a
// batch in SIMD lanes. The scalar sweep goes through the same order, which it computes the same
// result in (the batches keep each body's constraints in order, and constraints on disjoint bodies
// commute), but faster: a constraint that shares no body with the one before it need not wait for
// its velocities, so the processor overlaps the two. In top-down order it mostly follows a row of
// boxes, each contact waiting on the last (many_pyramids' solve: 11.3 → 10.3 ms at 2 threads).
// Levels (see lane_batches.h) fill the wide sweep's lanes and change its result; the scalar order
// goes without them.
void World::batchLanes() {
  if (!settings_.wideSolve && !settings_.interleaveSolveOrder) return;
  laneRun_.resize(islands_.contacts.size());
  const float* levels = settings_.topDownOrder && settings_.wideSolve ? order_.contactHeight.data() : nullptr;
  laneRanges_.clear();
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  // An island in last step's order (order_.kept: the same contacts between the same awake bodies)
  // batches as it did: the batches depend on nothing else. Its ids and runs are last step's.
  const bool before = !settings_.wideSolve && order_.sortedStep == stepCount_ && order_.batchedStep + 1 == stepCount_ &&
                      order_.batched.size() == islands_.contacts.size();
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    const int32_t li = layoutOf_[k];
    if (li < 0 && before && order_.kept[k]) {
      std::copy_n(order_.batched.data() + isl.firstContact, isl.contactCount, islands_.contacts.data() + isl.firstContact);
      continue;
    }
    if (li < 0) {
      // The tail of contacts out of reach stays behind the chain: a range of its own.
      const uint32_t front = isl.contactCount - tailOf(k);
      laneRanges_.push_back(isl.firstContact);
      laneRanges_.push_back(isl.firstContact + front);
      if (front == isl.contactCount) continue;
      laneRanges_.push_back(isl.firstContact + front);
      laneRanges_.push_back(isl.firstContact + isl.contactCount);
      continue;
    }
    const StripLayout& layout = layouts_[li];
    for (uint32_t s = 0; s <= layout.strips; ++s) {
      laneRanges_.push_back(isl.firstContact + layout.start[s]);
      laneRanges_.push_back(isl.firstContact + layout.start[s + 1]);
    }
  }
  // Ranges share no dynamic body: batched concurrently, each thread with its own batcher.
  parallelFor(uint32_t(laneRanges_.size() / 2), kIslandGrain, [&](uint32_t begin, uint32_t end) {
    LaneBatcher& batcher = laneBatchers_[threadSlot()];
    for (uint32_t r = begin; r < end; ++r) {
      const uint32_t b = laneRanges_[2 * r], e = laneRanges_[2 * r + 1];
      batcher.batch(bodies_, contactEdges_.data(), levels, islands_.contacts.data() + b, e - b, laneRun_.data() + b);
    }
  });
  order_.batched = islands_.contacts;
  order_.batchedStep = stepCount_;
  if (!settings_.wideSolve) return;
  // Batches of at least kMinWideLanes constraints are packed for the wide sweep.
  wideOf_.resize(laneRun_.size());
  uint32_t packed = 0;
  for (size_t j = 0; j < laneRun_.size(); ++j)
    wideOf_[j] = laneRun_[j] >= kMinWideLanes ? int32_t(packed++) : -1;
  if (wide_.size() < packed) wide_.resize(packed);
}

}  // namespace haif
