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
#include "core/serial_for.h"
#include "core/sort_key.h"
#include "dynamics/contact.h"
#include "haif/islands.h"

#include <algorithm>
#include <cmath>
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

/// A phase's strips [first, last) (counted within the phase: strip 2i + phase is its i-th) that one
/// of its tasks runs. A phase of `strips` strips on `threads` threads has stripGroups(..) tasks, one
/// per thread where there are strips enough, of contiguous strips whose counts differ by one at most:
/// no thread runs more strips than the phase needs of it.
struct StripGroup {
  uint32_t first, last;
};
inline uint32_t stripGroups(uint32_t strips, int threads) { return std::min(strips, uint32_t(std::max(1, threads))); }
inline StripGroup stripGroup(uint32_t g, uint32_t groups, uint32_t strips) {
  return {g * strips / groups, (g + 1) * strips / groups};
}

class IslandSplitter {
 public:
  /// Regroups island `k`'s contacts in `set.contacts` strip by strip (keeping their order inside a
  /// strip) and describes the result in `out`. `up` is the direction opposite gravity (any unit
  /// vector when there is none). Keeps its scratch buffers between steps. `parallelFor(n, grain, f)`
  /// runs f(begin, end) over [0, n) in ranges, possibly concurrently; the work is cut into fixed
  /// chunks, so the result does not depend on how the ranges fall.
  template <class ParallelFor>
  void split(const BodyStore& bodies, const ContactEdge* contacts, const Vec3& up, IslandSet& set, uint32_t k,
             StripLayout& out, ParallelFor&& parallelFor);
  /// The same on the calling thread alone.
  void split(const BodyStore& bodies, const ContactEdge* contacts, const Vec3& up, IslandSet& set, uint32_t k,
             StripLayout& out) {
    split(bodies, contacts, up, set, k, out, serialFor);
  }
  /// The strip of a body of the island last split (a body of no split island: meaningless).
  uint32_t stripOf(uint32_t body) const { return stripOfBody_[body]; }
  /// The island last split's bodies strip by strip: the r-th (r < its body count) lies in the strip
  /// that holds rank r, so strips' bodies are runs of r.
  uint32_t bodyAtRank(uint32_t r) const { return keyIndex(keys_[r]); }
  /// The static, kinematic and sleeping bodies the island last split touches, ascending, each once.
  const std::vector<uint32_t>& immovableBodies() const { return immovable_; }

 private:
  static constexpr uint32_t kChunk = 1024;  // bodies or contacts per chunk of concurrent work
  static uint32_t chunks(uint32_t n) { return (n + kChunk - 1) / kChunk; }

  // The first rank of strip s: ceil(s nb / strips).
  static uint32_t firstRank(uint32_t s, uint32_t nb, uint32_t strips) {
    return uint32_t((uint64_t(s) * nb + strips - 1) / strips);
  }
  // Selects the boundary between strips mid = (s0 + s1) / 2 - 1 and mid in [first(s0), first(s1)).
  void selectMiddle(uint32_t s0, uint32_t s1, uint32_t nb, uint32_t strips);
  // The stages, chunk c covering [c kChunk, (c + 1) kChunk) of the island's bodies or contacts.
  void spanBodies(const BodyStore& bodies, const uint32_t* ids, uint32_t nb, int vertical, uint32_t c);
  int cutAxis(int vertical, uint32_t bodyChunks) const;
  void keyBodies(const BodyStore& bodies, const uint32_t* ids, uint32_t nb, int axis, uint32_t c);
  void classifyContacts(const BodyStore& bodies, const ContactEdge* contacts, const uint32_t* cs, uint32_t nc,
                        uint32_t strips, uint32_t c);
  void placeContacts(StripLayout& out, uint32_t contactChunks);
  void scatterContacts(const uint32_t* cs, uint32_t nc, uint32_t c);

  std::vector<uint64_t> keys_;                    // (position along the axis, body) of the island's bodies, packed
  std::vector<uint32_t> stripOfBody_;             // per body id
  std::vector<uint32_t> stripOfContact_;          // per contact of the island, in island order
  std::vector<uint32_t> scratch_;
  std::vector<std::vector<uint32_t>> immovableOfChunk_;  // per contact chunk, may repeat
  std::vector<uint32_t> immovable_;
  std::vector<float> span_;                       // per body chunk: lo, hi along each world axis
  std::vector<uint32_t> count_, rows_, cursor_;   // per contact chunk and strip (kMaxStrips + 1 each)
};

template <class ParallelFor>
void IslandSplitter::split(const BodyStore& bodies, const ContactEdge* contacts, const Vec3& up, IslandSet& set,
                           uint32_t k, StripLayout& out, ParallelFor&& parallelFor) {
  const Island& isl = set.islands[k];
  const uint32_t* ids = set.bodies.data() + isl.firstBody;
  const uint32_t nb = isl.bodyCount, nc = isl.contactCount;
  const uint32_t strips = std::min(kMaxStrips, std::max(2u, nb / kBodiesPerStrip));
  out.strips = strips;
  auto eachChunk = [&](uint32_t n, auto&& f) {
    parallelFor(chunks(n), 1, [&](uint32_t b, uint32_t e) {
      for (uint32_t c = b; c < e; ++c) f(c);
    });
  };

  // Cut across the widest horizontal world axis (the one least aligned with up is never the
  // vertical one): strips are then columns, and a column keeps its layers in top-down order.
  int vertical = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(up[a]) > std::fabs(up[vertical])) vertical = a;
  span_.resize(size_t(chunks(nb)) * 6);
  eachChunk(nb, [&](uint32_t c) { spanBodies(bodies, ids, nb, vertical, c); });
  const int axis = cutAxis(vertical, chunks(nb));

  // Equal body counts per strip, by rank along the axis (ties by id: deterministic), one integer key
  // per body. Strip s holds ranks [first(s), first(s + 1)), first(s) = ceil(s nb / strips): only the
  // strips' boundaries need finding, not the whole order (a selection per boundary, halving the
  // range each time: n log(strips) work instead of a sort's n log(n)).
  keys_.resize(nb);
  eachChunk(nb, [&](uint32_t c) { keyBodies(bodies, ids, nb, axis, c); });
  auto first = [&](uint32_t s) { return firstRank(s, nb, strips); };
  // Level by level: each selection splits its range of strips in two, and a level's ranges are
  // disjoint, so they run concurrently (the same selections as recursing, in another order).
  uint32_t ranges[2][kMaxStrips + 1], count = 1;
  ranges[0][0] = 0;
  ranges[0][1] = strips;
  for (int level = 0; count > 0; level ^= 1) {
    const uint32_t* cut = ranges[level];  // range r: [cut[2r], cut[2r + 1]) of strips
    parallelFor(count, 1, [&](uint32_t b, uint32_t e) {
      for (uint32_t r = b; r < e; ++r) selectMiddle(cut[2 * r], cut[2 * r + 1], nb, strips);
    });
    uint32_t* next = ranges[level ^ 1];
    uint32_t nextCount = 0;
    for (uint32_t r = 0; r < count; ++r) {
      const uint32_t s0 = cut[2 * r], s1 = cut[2 * r + 1], mid = (s0 + s1) / 2;
      for (const auto& [lo, hi] : {std::pair{s0, mid}, std::pair{mid, s1}})
        if (hi - lo >= 2) {
          next[2 * nextCount] = lo;
          next[2 * nextCount + 1] = hi;
          ++nextCount;
        }
    }
    count = nextCount;
  }
  if (stripOfBody_.size() < bodies.size()) stripOfBody_.resize(bodies.size());
  parallelFor(strips, 1, [&](uint32_t b, uint32_t e) {
    for (uint32_t s = b; s < e; ++s)
      for (uint32_t r = first(s); r < first(s + 1); ++r) stripOfBody_[keyIndex(keys_[r])] = s;
  });

  // Each contact goes to the lower strip of its island bodies; then a stable counting sort, chunk
  // by chunk in order, keeps the top-down order inside every strip.
  uint32_t* cs = set.contacts.data() + isl.firstContact;
  stripOfContact_.resize(nc);
  scratch_.resize(nc);
  const size_t perChunk = size_t(chunks(nc)) * (kMaxStrips + 1);
  count_.assign(perChunk, 0);
  rows_.assign(perChunk, 0);
  cursor_.resize(perChunk);
  if (immovableOfChunk_.size() < chunks(nc)) immovableOfChunk_.resize(chunks(nc));
  eachChunk(nc, [&](uint32_t c) { classifyContacts(bodies, contacts, cs, nc, strips, c); });
  immovable_.clear();
  for (uint32_t c = 0; c < chunks(nc); ++c)
    immovable_.insert(immovable_.end(), immovableOfChunk_[c].begin(), immovableOfChunk_[c].end());
  std::sort(immovable_.begin(), immovable_.end());
  immovable_.erase(std::unique(immovable_.begin(), immovable_.end()), immovable_.end());
  placeContacts(out, chunks(nc));
  eachChunk(nc, [&](uint32_t c) { scatterContacts(cs, nc, c); });
  parallelFor(nc, kChunk * 4, [&](uint32_t b, uint32_t e) { std::copy(scratch_.begin() + b, scratch_.begin() + e, cs + b); });
}

}  // namespace haif
