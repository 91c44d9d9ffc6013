// Islands: connected components of the constraint graph over awake dynamic bodies. Static and
// kinematic bodies never join (or merge) islands: a contact with one belongs to the island of its
// dynamic body. Islands are independent, so they are solved concurrently.
#pragma once

#include "core/body_store.h"
#include "core/serial_for.h"
#include "dynamics/joint.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace haif {

struct Island {
  uint32_t firstBody = 0, bodyCount = 0;        ///< range in IslandSet::bodies
  uint32_t firstContact = 0, contactCount = 0;  ///< range in IslandSet::contacts
  uint32_t rows = 0;                            ///< solver rows (solverRowsFor per manifold): the work of one iteration
  uint32_t firstJoint = 0, jointCount = 0;      ///< range in IslandSet::joints
  /// The first kinematic body its contacts touch, or kNoCarrier: what a pile on a moving platform
  /// rests on (haif/rest_damping.h). Its velocity and position when the island was built.
  static constexpr uint32_t kNoCarrier = ~0u;
  uint32_t carrier = kNoCarrier;
  Vec3 carrierV = Vec3::Zero(), carrierW = Vec3::Zero(), carrierAt = Vec3::Zero();
  /// No contact and no joint: a body in flight, alone; the solve has nothing to do for it.
  bool unconstrained() const { return contactCount == 0 && jointCount == 0; }
};

/// What island building needs of a contact, kept by the narrow phase in a flat array: the Contact
/// itself is ~0.5 KB, and passes over those were most of the island stage's time.
struct ContactEdge {
  uint32_t a = 0, b = 0;  ///< body ids
  /// Depth of the deepest point (m; 0 when none overlaps). A pair without points: minus the
  /// distance it is known to be apart (the margin the narrow phase collided it with).
  float deepest = 0.0f;
  /// Depth of the nearest point, negative when every point is apart (by that much); a pair without
  /// points: as `deepest`.
  float nearest = 0.0f;
  uint8_t count = 0;      ///< manifold points (0: not touching)
  /// The pair has points now and had none before this step's narrow phase: a contact just made, so
  /// every point's impulse is zero (nothing to warm start from).
  bool fresh = false;
  /// Between an awake dynamic body and a static or kinematic one, overlapping, or a kinematic one
  /// closing a point's gap within the step (haif/pinch.h).
  bool pressedByImmovable = false;
  bool overlapping = false;  ///< some point is deeper than zero (crushes pass along these: haif/pinch.h)
  /// Between two dynamic bodies, every point farther apart than the pair can close within the step
  /// (World::narrowPhase): the contact holds nothing this step, so it joins no two bodies into one
  /// island.
  bool apart = false;
};

struct IslandSet {
  std::vector<Island> islands;    ///< largest (most rows) first
  std::vector<uint32_t> bodies;   ///< body ids grouped by island, ascending within an island
  std::vector<uint32_t> contacts; ///< contact indices grouped by island, ascending within an island
  std::vector<uint32_t> joints;   ///< joint indices grouped by island, ascending within an island
  uint32_t totalRows = 0;
  uint32_t largestRows = 0;
  uint32_t largestBodies = 0;
  uint32_t touchingContacts = 0;  ///< contacts with points (awake or not), counted in the same pass
  uint32_t contactPoints = 0;     ///< their points
};

/// Union-find island builder; keeps its scratch buffers between steps (no allocation once warm).
/// The unions run concurrently (lock-free, each link from a larger root to a smaller one), and every
/// component ends rooted at its smallest body whatever order they ran in: the islands, their
/// numbering and their order are the same for every thread count.
/// A step whose graph is the last build's (the same contacts in the same places with the same point
/// counts and `apart` flags, the same awake bodies and kinds, the same joints) gets the last build's
/// islands again, their carriers' motion read anew: a resting pile keeps its graph for minutes, and
/// building it again was a tenth of its step (`many_pyramids` at one iteration).
class IslandBuilder {
 public:
  /// A contact joins its bodies when it has points, both bodies are awake dynamic ones and it is not
  /// `apart`; an apart contact between two islands belongs to neither (it is not solved this step). Joints
  /// are edges like contacts: an unbroken joint between two awake dynamic bodies joins them; a joint
  /// to the world, a static or a kinematic body belongs to the island of its dynamic body.
  /// `parallelFor(n, grain, f)` runs f(begin, end) over [0, n) in ranges, possibly concurrently.
  template <class ParallelFor>
  void build(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
             const std::vector<Joint>& joints, IslandSet& out, ParallelFor&& parallelFor);
  /// Whether the last build() found the graph unchanged and gave its islands again.
  bool reused() const { return reused_; }
  /// The same on the calling thread alone.
  void build(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
             const std::vector<Joint>& joints, IslandSet& out) {
    build(bodies, contacts, contactCount, joints, out, serialFor);
  }

 private:
  static constexpr uint32_t kNoBody = ~0u;
  static constexpr uint32_t kBodyChunk = 4096, kContactChunk = 4096;

  // parent_ is shared by the concurrent unions: read and swung with atomic operations only.
  uint32_t parentOf(uint32_t x) const { return __atomic_load_n(&parent_[x], __ATOMIC_RELAXED); }
  uint32_t find(uint32_t x) {
    for (;;) {
      uint32_t p = parentOf(x);
      if (p == x) return x;
      const uint32_t grand = parentOf(p);
      // Path halving. x is no root, so no union writes its parent, and any ancestor is a valid one:
      // a plain (atomic) store, even racing another halving, keeps the forest intact.
      if (grand != p) __atomic_store_n(&parent_[x], grand, __ATOMIC_RELAXED);
      x = grand;
    }
  }
  void unite(uint32_t a, uint32_t b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a > b) std::swap(a, b);  // the larger root goes under the smaller: roots end as minima
      uint32_t expected = b;
      if (__atomic_compare_exchange_n(&parent_[b], &expected, a, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) return;
    }
  }

  // What a build reads of a contact, a body and a joint: equal to the last build's, equal islands.
  struct EdgeKey {
    uint32_t a, b;
    uint8_t count;
    bool apart;
    bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b && count == o.count && apart == o.apart; }
  };
  struct JointKey {
    uint32_t a, b, rows;
    bool broken;
    bool operator==(const JointKey& o) const { return a == o.a && b == o.b && rows == o.rows && broken == o.broken; }
  };
  static uint8_t bodyKey(const BodyStore& bodies, uint32_t i) { return uint8_t(uint8_t(bodies.kind[i]) | bodies.asleep[i] << 4); }
  // Whether the graph is the last build's. The contacts' keys, the most of them, are compared in
  // ranges (possibly concurrently), each up to its first difference; after one the keys are written
  // again at the next step, not this one: a churning pile pays one pass every other step.
  template <class ParallelFor>
  bool sameGraph(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
                 const std::vector<Joint>& joints, ParallelFor&& parallelFor);
  static EdgeKey edgeKey(const ContactEdge& c) { return {c.a, c.b, c.count, c.apart}; }
  bool sameBodiesAndJoints(const BodyStore& bodies, const std::vector<Joint>& joints);
  void refreshCarriers(const BodyStore& bodies, IslandSet& out) const;

  void uniteContacts(const BodyStore& bodies, const ContactEdge* contacts, uint32_t begin, uint32_t end);
  void rootBodies(const BodyStore& bodies, uint32_t begin, uint32_t end);
  void gather(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
              const std::vector<Joint>& joints, IslandSet& out);

  std::vector<uint32_t> parent_;
  std::vector<uint32_t> root_;                         // each awake dynamic body's root, after the unions
  uint32_t touching_ = 0, points_ = 0;                 // summed by the concurrent ranges
  std::vector<int32_t> islandOfRoot_, islandOfBody_;  // island (in numbering order) of each root / body
  std::vector<uint32_t> contactBody_;                  // the awake dynamic body a contact belongs by, or kNoBody
  std::vector<uint32_t> cursorBody_, cursorContact_, cursorJoint_;
  std::vector<uint32_t> order_;
  std::vector<Island> unsorted_;
  std::vector<EdgeKey> edgeKeys_;
  std::vector<uint8_t> bodyKeys_;
  std::vector<JointKey> jointKeys_;
  bool edgesKept_ = false;  // edgeKeys_ hold the last build's contacts (else written at the next)
  bool reused_ = false;
  IslandSet kept_;  // the last build's islands, before the solve order rearranged their contacts
};

template <class ParallelFor>
bool IslandBuilder::sameGraph(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
                              const std::vector<Joint>& joints, ParallelFor&& parallelFor) {
  const bool same = sameBodiesAndJoints(bodies, joints);  // keeps theirs either way (few)
  if (!edgesKept_ || edgeKeys_.size() != contactCount) {
    edgeKeys_.resize(contactCount);
    parallelFor(contactCount, kContactChunk, [&](uint32_t b, uint32_t e) {
      for (uint32_t ci = b; ci < e; ++ci) edgeKeys_[ci] = edgeKey(contacts[ci]);
    });
    edgesKept_ = true;
    return false;
  }
  uint32_t differ = 0;  // ranges with a difference (counted concurrently)
  parallelFor(contactCount, kContactChunk, [&](uint32_t b, uint32_t e) {
    for (uint32_t ci = b; ci < e; ++ci)
      if (!(edgeKeys_[ci] == edgeKey(contacts[ci]))) {
        __atomic_fetch_add(&differ, 1u, __ATOMIC_RELAXED);
        return;
      }
  });
  edgesKept_ = differ == 0;
  return same && edgesKept_;
}

template <class ParallelFor>
void IslandBuilder::build(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
                          const std::vector<Joint>& joints, IslandSet& out, ParallelFor&& parallelFor) {
  reused_ = sameGraph(bodies, contacts, contactCount, joints, parallelFor);
  if (reused_) {
    out = kept_;
    refreshCarriers(bodies, out);
    return;
  }
  const uint32_t n = static_cast<uint32_t>(bodies.size());
  parent_.resize(n);
  root_.resize(n);
  contactBody_.resize(contactCount);
  touching_ = points_ = 0;
  parallelFor(n, kBodyChunk, [&](uint32_t b, uint32_t e) {
    for (uint32_t i = b; i < e; ++i) parent_[i] = i;
  });
  parallelFor(contactCount, kContactChunk, [&](uint32_t b, uint32_t e) { uniteContacts(bodies, contacts, b, e); });
  auto activeEnd = [&](uint32_t i) { return i != kWorldBody && bodies.isAwakeDynamic(i); };
  for (const Joint& j : joints)
    if (!j.broken && activeEnd(j.def.bodyA) && activeEnd(j.def.bodyB)) unite(j.def.bodyA, j.def.bodyB);
  parallelFor(n, kBodyChunk, [&](uint32_t b, uint32_t e) { rootBodies(bodies, b, e); });
  gather(bodies, contacts, contactCount, joints, out);
  kept_ = out;
}

}  // namespace haif
