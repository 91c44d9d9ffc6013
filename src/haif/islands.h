// Islands: connected components of the constraint graph over awake dynamic bodies. Static and
// kinematic bodies never join (or merge) islands: a contact with one belongs to the island of its
// dynamic body. Islands are independent, so they are solved concurrently.
#pragma once

#include "core/body_store.h"
#include "dynamics/joint.h"

#include <cstdint>
#include <vector>

namespace haif {

struct Island {
  uint32_t firstBody = 0, bodyCount = 0;        ///< range in IslandSet::bodies
  uint32_t firstContact = 0, contactCount = 0;  ///< range in IslandSet::contacts
  uint32_t rows = 0;                            ///< solver rows (solverRowsFor per manifold): the work of one iteration
  uint32_t firstJoint = 0, jointCount = 0;      ///< range in IslandSet::joints
};

/// What island building needs of a contact, kept by the narrow phase in a flat array: the Contact
/// itself is ~0.5 KB, and passes over those were most of the island stage's time.
struct ContactEdge {
  uint32_t a = 0, b = 0;  ///< body ids
  float deepest = 0.0f;   ///< depth of the deepest point (m; 0 when none overlaps)
  uint8_t count = 0;      ///< manifold points (0: not touching)
  bool unloaded = true;   ///< every point's normal impulse is zero (nothing to warm start from)
  /// Overlapping, between an awake dynamic body and a static or kinematic one (haif/pinch.h).
  bool pressedByImmovable = false;
  bool overlapping = false;  ///< some point is deeper than zero (crushes pass along these: haif/pinch.h)
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
class IslandBuilder {
 public:
  /// A contact joins its bodies when it has points and both bodies are awake dynamic ones. Joints
  /// are edges like contacts: an unbroken joint between two awake dynamic bodies joins them; a joint
  /// to the world, a static or a kinematic body belongs to the island of its dynamic body.
  void build(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
             const std::vector<Joint>& joints, IslandSet& out);

 private:
  uint32_t find(uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];  // path halving
      x = parent_[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a > b) std::swap(a, b);  // smaller id becomes the root: deterministic
    parent_[b] = a;
  }

  static constexpr uint32_t kNoBody = ~0u;

  std::vector<uint32_t> parent_;
  std::vector<int32_t> islandOfRoot_, islandOfBody_;  // island (in numbering order) of each root / body
  std::vector<uint32_t> contactBody_;                  // the awake dynamic body a contact belongs by, or kNoBody
  std::vector<uint32_t> cursorBody_, cursorContact_, cursorJoint_;
  std::vector<uint32_t> order_;
  std::vector<Island> unsorted_;
};

}  // namespace haif
