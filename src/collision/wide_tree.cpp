#include "collision/wide_tree.h"

#include <limits>

namespace haif {

void WideTree::build(const DynamicTree& tree) {
  nodes_.clear();
  if (tree.root() == DynamicTree::kNull) return;
  const int32_t root = tree.root();
  makeNode(tree, &root, 1);
}

int32_t WideTree::makeNode(const DynamicTree& tree, const int32_t* lanes, int count) {
  const int32_t index = int32_t(nodes_.size());
  nodes_.emplace_back();  // filled by index below: the recursion may move it
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (int l = 0; l < kLanes; ++l) {
    if (l >= count) {
      for (int k = 0; k < 3; ++k) nodes_[index].lo[k][l] = kInf, nodes_[index].hi[k][l] = -kInf;
      nodes_[index].child[l] = -1;
      continue;
    }
    const int32_t x = lanes[l];
    const Aabb& b = tree.fatAabb(x);
    for (int k = 0; k < 3; ++k) nodes_[index].lo[k][l] = b.lo[k], nodes_[index].hi[k][l] = b.hi[k];
    if (tree.isLeaf(x)) {
      nodes_[index].child[l] = -1 - int32_t(tree.userData(x));
      continue;
    }
    // The node's lanes: each child, or a child's two children (its box holds theirs, so a query
    // that reaches them finds what the tree's query finds through it).
    int32_t below[kLanes];
    int k = 0;
    for (const int32_t c : {tree.child1(x), tree.child2(x)}) {
      if (tree.isLeaf(c)) {
        below[k++] = c;
      } else {
        below[k++] = tree.child1(c);
        below[k++] = tree.child2(c);
      }
    }
    const int32_t child = makeNode(tree, below, k);
    nodes_[index].child[l] = child;
  }
  return index;
}

}  // namespace haif
