// A query-only copy of a DynamicTree in which a node holds four boxes: the boxes two levels below
// one of the tree's nodes (its children, or where a child is a leaf, the leaf), stored by coordinate
// so that one query tests all four with a few SIMD compares. A query of the binary tree spends its
// time on one unpredictable branch per node it visits; here four boxes share one step, and the walk
// is half as deep. Built afresh from the tree whenever the tree changed and many queries follow
// (a churning pile's moved bodies: BroadPhase::prepareQueries).
#pragma once

#include "collision/dynamic_tree.h"
#include "core/simd4_lanes.h"

#include <cstdint>
#include <vector>

namespace haif {

class WideTree {
 public:
  /// Copies `tree` (its boxes and leaves as they are now).
  void build(const DynamicTree& tree);

  /// Calls f(userData) for every leaf whose box overlaps `box`: the same leaves, in the same order,
  /// as tree.query(box, f) on the tree it was built from. Safe to call concurrently.
  template <class F>
  void query(const Aabb& box, F&& f) const;

 private:
  static constexpr int kLanes = 4;
  struct Node {
    // Per lane: its box (an empty lane has lo > hi, which nothing overlaps) and what it holds:
    // a node of this tree (>= 0) or a leaf (-1 - its userData).
    float lo[3][kLanes], hi[3][kLanes];
    int32_t child[kLanes];
  };
  int32_t makeNode(const DynamicTree& tree, const int32_t* lanes, int count);

  std::vector<Node> nodes_;  // nodes_[0] holds the tree's root in its first lane
};

template <class F>
void WideTree::query(const Aabb& box, F&& f) const {
  using simd4::F4;
  using simd4::I4;
  using simd4::load;
  auto splat = [](float x) { return F4{x, x, x, x}; };
  if (nodes_.empty()) return;
  const F4 loX = splat(box.lo.x()), loY = splat(box.lo.y()), loZ = splat(box.lo.z());
  const F4 hiX = splat(box.hi.x()), hiY = splat(box.hi.y()), hiZ = splat(box.hi.z());
  int32_t stack[DynamicTree::kMaxStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int32_t code = stack[--top];
    if (code < 0) {
      f(uint32_t(-1 - code));
      continue;
    }
    const Node& n = nodes_[code];
    // DynamicTree's overlap test (node.lo <= box.hi and box.lo <= node.hi on each axis), four lanes.
    const I4 in = (load(n.lo[0]) <= hiX) & (loX <= load(n.hi[0])) & (load(n.lo[1]) <= hiY) & (loY <= load(n.hi[1])) &
                  (load(n.lo[2]) <= hiZ) & (loZ <= load(n.hi[2]));
    if (top + kLanes > DynamicTree::kMaxStack) continue;  // as the tree's query: never at a real depth
    // Lanes pushed first to last, so the last is taken first: the tree's walk takes a node's second
    // child first, and the lanes hold the first child's part, then the second's.
    for (int l = 0; l < kLanes; ++l) {
      stack[top] = n.child[l];
      top += in[l] != 0;
    }
  }
}

}  // namespace haif
