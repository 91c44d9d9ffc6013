// Splitting a giant island for parallel solving (docs/architecture.md, "One step", stage 8).
//
// A dense stack or a building is one island, and an island is solved by one task: the step would
// fall back to one core. The island's bodies are cut into K vertical strips by their position along
// a horizontal axis (equal body counts per strip). Each contact belongs to the lower-numbered strip
// of its two dynamic bodies, so strip s only ever writes bodies of strips s and s + 1. Then all even
// strips can be swept at once, then all odd strips: two phases per sweep, with no two tasks of a
// phase touching the same dynamic body. Contacts whose bodies lie more than one strip apart (a body
// wider than a strip) go to a short serial tail after the two phases.
//
// Why strips and not a graph colouring: Gauss-Seidel order is what carries a stack's weight down in
// one sweep (World::orderContactsTopDown). Inside a strip the top-down order is kept; a colouring
// interleaves the layers, and large_pyramid dropped twice as far at 10 iterations (0.21 m against
// 0.11 m mean after 200 steps) when solved colour by colour.
//
// The split depends on positions only, never on the thread count: every thread count runs the same
// sweeps in the same order per body, so results are bit-identical.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"
#include "haif/islands.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace haif {

/// Islands with at least this many solver rows (and no joints) are split into strips.
constexpr uint32_t kSplitRows = 4096;
/// Most strips per island: each phase has at most half of them as parallel tasks.
constexpr uint32_t kMaxStrips = 32;
/// Fewest bodies per strip: thinner strips add boundary contacts without adding useful tasks.
constexpr uint32_t kBodiesPerStrip = 128;

/// Where an island's strips lie in its contact range (offsets from Island::firstContact).
struct StripLayout {
  uint32_t strips = 0;                       ///< K; 0 when the island is not split
  uint32_t start[kMaxStrips + 2] = {};       ///< strip s: [start[s], start[s+1]); tail: [start[K], start[K+1])
  uint32_t rows[kMaxStrips + 1] = {};        ///< solver rows per strip, then of the tail
  /// Rows on the island's critical path with unlimited threads: per phase its largest strip, plus
  /// the tail. What the iteration controller plans with instead of the island's total.
  uint32_t criticalRows() const;
};

class IslandSplitter {
 public:
  /// Regroups island `k`'s contacts in `set.contacts` strip by strip (keeping their order inside a
  /// strip) and describes the result in `out`. `up` is the direction opposite gravity (any unit
  /// vector when there is none). Keeps its scratch buffers between steps.
  void split(const BodyStore& bodies, const ContactEdge* contacts, const Vec3& up, IslandSet& set, uint32_t k,
             StripLayout& out);
  /// The strip of a body of the island last split (a body of no split island: meaningless).
  uint32_t stripOf(uint32_t body) const { return stripOfBody_[body]; }

 private:
  template <class First>
  void selectBoundaries(uint32_t s0, uint32_t s1, const First& first);

  std::vector<uint64_t> keys_;                    // (position along the axis, body) of the island's bodies, packed
  std::vector<uint32_t> stripOfBody_;             // per body id
  std::vector<uint32_t> stripOfContact_;          // per contact of the island, in island order
  std::vector<uint32_t> scratch_;
};

}  // namespace haif
