// Grouping a contact range into lane batches: for the wide (SIMD) sweep, and as the scalar sweep's
// order (neighbours that share no body overlap in the processor; docs/solver.md, "Interleaved solve
// order").
//
// A wide sweep solves up to kLanes constraints at once, so the constraints of one batch must not
// share a dynamic body. Any grouping would do that; this one also keeps the sweep's result: each
// constraint goes to the first batch after every batch that already holds one of its dynamic
// bodies. Constraints that share a body therefore keep their relative order, and two Gauss-Seidel
// orders that agree on every such pair compute the same thing (constraints on disjoint bodies
// commute). The top-down order that carries a stack's weight down in one sweep survives, which a
// graph colouring does not (see island_split.h).
//
// With solve-order keys given, contacts whose keys lie within kLevelTolerance (a row of boxes at one
// height) first form a level, coloured greedily and put colour by colour: the order between levels
// stays, inside a level it changes (a row in solve order would otherwise allow one contact per batch).
//
// Batches are contiguous runs of the reordered range, described per slot in `run`: the first slot
// of a batch holds its length (1..kLanes), the others 0.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"
#include "dynamics/wide_contact_solver.h"

#include <cstdint>
#include <vector>

namespace haif {

/// Smallest batch the wide sweep takes; smaller ones are swept one constraint at a time.
constexpr int kMinWideLanes = 2;
/// Contacts whose solve-order keys (up · (p_a + p_b), m) lie this close form one level.
constexpr float kLevelTolerance = 0.02f;

class LaneBatcher {
 public:
  /// Reorders contacts ids[0, n) into lane batches (see above) and writes run[0, n). Keeps its
  /// scratch buffers between calls; the result depends only on the input order and the bodies.
  /// `Pair` is any record with body ids `a` and `b` (Contact, or the World's compact ContactEdge).
  template <class Pair>
  void batch(const BodyStore& bodies, const Pair* contacts, const float* level, uint32_t* ids, uint32_t n,
             uint8_t* run);

 private:
  template <class Pair>
  void colourLevels(const BodyStore& bodies, const Pair* contacts, const float* level, uint32_t* ids, uint32_t n);
  std::vector<uint32_t> colours_;    // per body id: colours its contacts have in the current level
  std::vector<uint8_t> colourOf_;    // per slot of the range
  std::vector<int32_t> lastBatch_;   // per body id: last batch that holds it (-1: none yet)
  std::vector<uint32_t> batchOf_;    // per slot of the range
  std::vector<uint8_t> fill_;        // per batch: constraints in it
  std::vector<uint32_t> nextOpen_;   // per batch: a later-or-equal batch that may have room (path halving)
  std::vector<uint32_t> start_;      // per batch: first slot after the reorder
  std::vector<uint32_t> scratch_;
};

}  // namespace haif
