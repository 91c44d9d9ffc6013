// Dynamic AABB tree: a binary bounding-volume hierarchy of "fat" boxes that supports insert,
// remove and move in O(log n), kept height-balanced and tight (small surface area) by rotations.
// Bodies that rest inside their fat box cost nothing to update, which is what makes large resting
// scenes cheap.
#pragma once

#include "core/aabb.h"

#include <cstdint>
#include <vector>

namespace haif {

class DynamicTree {
 public:
  static constexpr int32_t kNull = -1;

  int32_t createProxy(const Aabb& fat, uint32_t userData);
  void destroyProxy(int32_t proxy);
  /// Replaces the proxy's fat box (remove + insert).
  void moveProxy(int32_t proxy, const Aabb& fat);
  /// Replaces the proxy's fat box and leaves the tree as it is: queries may miss it until rebuild().
  /// For many moves in one step, where building afresh costs less than moving each (broad_phase.h).
  void setLeafBox(int32_t proxy, const Aabb& fat) { nodes_[proxy].box = fat; }
  /// Builds the tree over its leaves afresh, top down: each node splits its leaves at the middle of
  /// the span of their centres along the axis where they spread most. Leaves keep their proxy
  /// numbers; the result depends only on the leaves' boxes and numbers.
  void rebuild() {
    rebuild([](auto&& buildSide) {
      buildSide(0);
      buildSide(1);
    });
  }
  /// The same tree, its root's two subtrees built by runBoth(buildSide), which must call
  /// buildSide(0) and buildSide(1) once each, in either order or concurrently (they touch
  /// disjoint leaves and nodes).
  template <class RunBoth>
  void rebuild(RunBoth&& runBoth) {
    if (!beginRebuild()) return;
    const uint32_t n = uint32_t(leaves_.size()), mid = splitRange(0, n);
    int32_t side[2];
    // Inner nodes are numbered in preorder: the root, its first subtree's mid - 1, then the rest.
    runBoth([&](int k) { side[k] = k == 0 ? buildRange(0, mid, 1) : buildRange(mid, n, mid); });
    root_ = inner_[0];
    link(root_, side[0], side[1]);
    nodes_[root_].parent = kNull;
  }

  const Aabb& fatAabb(int32_t proxy) const { return nodes_[proxy].box; }
  // The nodes as query() walks them (for WideTree): fatAabb reads any node's box.
  int32_t root() const { return root_; }
  bool isLeaf(int32_t node) const { return nodes_[node].child1 == kNull; }
  int32_t child1(int32_t node) const { return nodes_[node].child1; }
  int32_t child2(int32_t node) const { return nodes_[node].child2; }
  static constexpr int kMaxStack = 256;  // a balanced tree of 2^64 leaves is < 128 deep
  uint32_t userData(int32_t proxy) const { return nodes_[proxy].userData; }
  int32_t height() const { return root_ == kNull ? 0 : nodes_[root_].height; }
  int32_t proxyCount() const { return proxyCount_; }

  /// Calls f(userData) for every proxy whose fat box overlaps `box`. Safe to call concurrently.
  template <class F>
  void query(const Aabb& box, F&& f) const {
    if (root_ == kNull) return;
    int32_t stack[kMaxStack];
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!n.box.overlaps(box)) continue;
      if (n.child1 == kNull) {
        f(n.userData);
      } else if (top + 2 <= kMaxStack) {
        stack[top++] = n.child1;
        stack[top++] = n.child2;
      }
    }
  }

  /// Sum of the internal nodes' half surface areas: what a query is expected to visit (the
  /// surface-area heuristic); for tests of the tree's quality.
  float internalArea() const;

  /// Checks the structural invariants (parents, heights, enclosing boxes); for tests.
  bool validate() const;

 private:
  static constexpr int32_t kMaxImbalance = 1;  // children's heights differ by at most this
  struct Node {
    Aabb box;
    int32_t parent = kNull;  // doubles as the free-list link for free nodes
    int32_t child1 = kNull;
    int32_t child2 = kNull;
    int32_t height = 0;      // leaf 0, free -1
    uint32_t userData = 0;
  };

  int32_t allocateNode();
  void freeNode(int32_t n);
  void insertLeaf(int32_t leaf);
  void removeLeaf(int32_t leaf);
  int32_t balance(int32_t a);
  bool rotateForArea(int32_t a);
  void refitUpwards(int32_t n);
  bool validateNode(int32_t n, int32_t parent) const;
  bool beginRebuild();  // gathers the leaves; false when there are fewer than two (then done)
  uint32_t splitRange(uint32_t begin, uint32_t end);  // partitions the leaves; returns the split
  int32_t buildRange(uint32_t begin, uint32_t end, uint32_t firstInner);
  void link(int32_t node, int32_t child1, int32_t child2);

  std::vector<Node> nodes_;
  int32_t root_ = kNull;
  int32_t freeList_ = kNull;
  int32_t proxyCount_ = 0;
  // rebuild()'s scratch, kept so that a rebuild allocates nothing once the tree has its size.
  struct BuildLeaf {
    float centre[3];
    int32_t node;
  };
  std::vector<BuildLeaf> leaves_, split_;
  std::vector<int32_t> inner_;
};

}  // namespace haif
