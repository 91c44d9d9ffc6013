// Broad phase: two dynamic AABB trees (static bodies; moving bodies) holding fat boxes. A body is
// re-inserted only when its tight box leaves its fat box, and only re-inserted bodies look for new
// pairs, so resting bodies cost one containment test per step. Static bodies are never tested
// against each other: they live in their own tree and do not query it.
#pragma once

#include "collision/dynamic_tree.h"
#include "collision/wide_tree.h"

#include <cstdint>
#include <vector>

namespace haif {

class BroadPhase {
 public:
  /// Margin added around a tight box when a body is (re-)inserted.
  float fatMargin = 0.1f;
  /// Margin a body's box keeps inside its fat box before it is re-inserted: every pair within it
  /// of each other exists. A body struck within the step moves past its swept box (a hull falling
  /// at 3.6 m/s, hit from above, left at 9 m/s); with no margin it met the ground it was 7 cm over
  /// with no pair, and sank 7.6 cm into it.
  float keptMargin = 0.05f;

  /// `marginScale`: the factor on both margins for this body (a small body's, haif/small_bodies.h).
  void addBody(uint32_t body, const Aabb& tight, bool isStatic, float marginScale = 1.0f);
  /// Updates a moving body's box; returns true when the body left its fat box (re-inserted). A
  /// re-inserted box also reaches `lead` (m) further along the body's path: a body in free flight
  /// then leaves its fat box every few steps instead of every step.
  bool update(uint32_t body, const Aabb& tight, const Vec3& lead = Vec3::Zero());
  /// True when a moving body's tight box still fits its fat box (update would do nothing). Read-only:
  /// bodies may be tested concurrently.
  bool fits(uint32_t body, const Aabb& tight) const {
    return movingTree_.fatAabb(proxy_[body]).contains(tight.expanded(keptMargin * marginScale_[body]));
  }
  /// Gives a body that does not fit a new fat box (update() without its test). With `rebuildLater`
  /// the tree is left as it is: for many moves in one step, then rebuildMovingTree() before any query.
  void move(uint32_t body, const Aabb& tight, const Vec3& lead, bool rebuildLater);
  void rebuildMovingTree() {
    movingTree_.rebuild();
    wideReady_ = false;
  }
  /// The same, the root's two subtrees built by runBoth (DynamicTree::rebuild).
  template <class RunBoth>
  void rebuildMovingTree(RunBoth&& runBoth) {
    movingTree_.rebuild(runBoth);
    wideReady_ = false;
  }
  /// Copies the trees into WideTrees that queryMoved then reads until a tree next changes: the same
  /// pairs in the same order, for less; worth the copy where many bodies are to query. The static
  /// tree's copy is kept until a static body is added.
  void prepareQueries() {
    movingWide_.build(movingTree_);
    wideReady_ = true;
    if (!staticWideReady_) staticWide_.build(staticTree_);
    staticWideReady_ = true;
  }
  const Aabb& fatAabb(uint32_t body) const {
    return (isStatic_[body] ? staticTree_ : movingTree_).fatAabb(proxy_[body]);
  }
  bool fatOverlap(uint32_t a, uint32_t b) const { return fatAabb(a).overlaps(fatAabb(b)); }

  /// Bodies moved since the last clearMoved(), in the order they moved.
  const std::vector<uint32_t>& moved() const { return moved_; }
  /// Calls onPair(m, other) for each pair moved body m's query reports: their fat boxes overlap now
  /// and did not before this step's moves. A pair that overlapped before was reported then, and its
  /// owner (the World) keeps it while the boxes overlap, so asking it again would only repeat a
  /// lookup (in a churning pile most re-inserted bodies keep most of their neighbours: those lookups
  /// were a third of the broad phase). Every new pair that involves a moved body is reported by
  /// exactly one moved body's query (two moved bodies: by the lower id), so querying all of
  /// moved() finds each once. Read-only: moved bodies may be queried concurrently.
  template <class F>
  void queryMoved(uint32_t m, F&& onPair) const {
    const Aabb& box = fatAabb(m);
    const Aabb& before = previousFat_[m];
    auto visit = [&](uint32_t other) {
      if (other == m) return;
      if (movedFlag_[other] && other < m) return;  // that body's own query reports the pair
      if (before.overlaps(movedFlag_[other] ? previousFat_[other] : fatAabb(other))) return;  // not new
      onPair(m, other);
    };
    if (wideReady_) movingWide_.query(box, visit);
    else movingTree_.query(box, visit);
    if (isStatic_[m]) return;
    if (wideReady_) staticWide_.query(box, visit);
    else staticTree_.query(box, visit);
  }
  void clearMoved() {
    for (uint32_t m : moved_) movedFlag_[m] = 0;
    moved_.clear();
  }
  /// Reports the new pairs (a, b) that involve a body moved since the last call (see queryMoved), each
  /// once, in a deterministic order; then forgets the moves.
  template <class F>
  void findNewPairs(F&& onPair) {
    for (uint32_t m : moved_) queryMoved(m, onPair);
    clearMoved();
  }

  const DynamicTree& movingTree() const { return movingTree_; }
  const DynamicTree& staticTree() const { return staticTree_; }

 private:
  void markMoved(uint32_t body) {
    if (!movedFlag_[body]) {
      movedFlag_[body] = 1;
      moved_.push_back(body);
    }
  }

  DynamicTree movingTree_;
  WideTree movingWide_, staticWide_;  // the trees' copies for queries (prepareQueries)
  bool wideReady_ = false;        // both copies are the trees as they are now
  bool staticWideReady_ = false;  // staticWide_ is the static tree as it is now
  DynamicTree staticTree_;
  std::vector<int32_t> proxy_;
  std::vector<uint8_t> isStatic_;
  std::vector<float> marginScale_;
  std::vector<uint8_t> movedFlag_;
  std::vector<Aabb> previousFat_;  // a moved body's fat box before it moved (empty: new this step)
  std::vector<uint32_t> moved_;
};

}  // namespace haif
