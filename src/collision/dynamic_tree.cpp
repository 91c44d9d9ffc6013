#include "collision/dynamic_tree.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>

namespace haif {

int32_t DynamicTree::allocateNode() {
  if (freeList_ == kNull) {
    nodes_.emplace_back();
    return static_cast<int32_t>(nodes_.size() - 1);
  }
  const int32_t n = freeList_;
  freeList_ = nodes_[n].parent;
  nodes_[n] = Node{};
  return n;
}

void DynamicTree::freeNode(int32_t n) {
  nodes_[n].parent = freeList_;
  nodes_[n].height = -1;
  freeList_ = n;
}

int32_t DynamicTree::createProxy(const Aabb& fat, uint32_t userData) {
  const int32_t leaf = allocateNode();
  nodes_[leaf].box = fat;
  nodes_[leaf].userData = userData;
  insertLeaf(leaf);
  ++proxyCount_;
  return leaf;
}

void DynamicTree::destroyProxy(int32_t proxy) {
  removeLeaf(proxy);
  freeNode(proxy);
  --proxyCount_;
}

void DynamicTree::moveProxy(int32_t proxy, const Aabb& fat) {
  removeLeaf(proxy);
  nodes_[proxy].box = fat;
  insertLeaf(proxy);
}

void DynamicTree::insertLeaf(int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  // Descend towards the sibling that minimises the surface-area increase (greedy SAH).
  const Aabb box = nodes_[leaf].box;
  int32_t index = root_;
  while (nodes_[index].child1 != kNull) {
    const Node& n = nodes_[index];
    const float area = n.box.perimeter();
    const float combined = n.box.merged(box).perimeter();
    const float costHere = 2.0f * combined;              // new parent of (n, leaf)
    const float inherited = 2.0f * (combined - area);    // growth pushed onto ancestors below
    auto childCost = [&](int32_t c) {
      const Aabb merged = box.merged(nodes_[c].box);
      const float grow = nodes_[c].child1 == kNull ? merged.perimeter()
                                                   : merged.perimeter() - nodes_[c].box.perimeter();
      return grow + inherited;
    };
    const float cost1 = childCost(n.child1);
    const float cost2 = childCost(n.child2);
    if (costHere < cost1 && costHere < cost2) break;
    index = cost1 < cost2 ? n.child1 : n.child2;
  }

  const int32_t sibling = index;
  const int32_t oldParent = nodes_[sibling].parent;
  const int32_t newParent = allocateNode();
  nodes_[newParent].parent = oldParent;
  nodes_[newParent].height = nodes_[sibling].height + 1;  // its box is left empty: refitUpwards sets it
  nodes_[newParent].child1 = sibling;
  nodes_[newParent].child2 = leaf;
  nodes_[sibling].parent = newParent;
  nodes_[leaf].parent = newParent;
  if (oldParent == kNull) {
    root_ = newParent;
  } else if (nodes_[oldParent].child1 == sibling) {
    nodes_[oldParent].child1 = newParent;
  } else {
    nodes_[oldParent].child2 = newParent;
  }
  refitUpwards(nodes_[leaf].parent);
}

void DynamicTree::removeLeaf(int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const int32_t parent = nodes_[leaf].parent;
  const int32_t grand = nodes_[parent].parent;
  const int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
  } else {
    if (nodes_[grand].child1 == parent) nodes_[grand].child1 = sibling;
    else nodes_[grand].child2 = sibling;
    nodes_[sibling].parent = grand;
    refitUpwards(grand);
  }
  freeNode(parent);
}

// Recomputes boxes and heights from `index` up, rotating where that balances or tightens the
// tree. It stops at the first node that comes out as it was: everything above is then unchanged
// (most moves in a pile change only the lowest few levels).
void DynamicTree::refitUpwards(int32_t index) {
  while (index != kNull) {
    const int32_t top = balance(index);
    const bool rotated = rotateForArea(top);
    Node& n = nodes_[top];
    const Aabb before = n.box;
    const int32_t heightBefore = n.height;
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    n.height = 1 + std::max(c1.height, c2.height);
    n.box = c1.box.merged(c2.box);
    if (top == index && !rotated && n.height == heightBefore && n.box.lo == before.lo && n.box.hi == before.hi) return;
    index = n.parent;
  }
}

// AVL-style rotation: if one child is more than kMaxImbalance levels taller, lift that child's
// taller child, so the depth stays logarithmic whatever the insertion order. Returns the subtree's
// new root.
int32_t DynamicTree::balance(int32_t a) {
  Node& A = nodes_[a];
  if (A.child1 == kNull || A.height < 2) return a;
  const int32_t b = A.child1, c = A.child2;
  const int32_t diff = nodes_[c].height - nodes_[b].height;
  if (diff >= -kMaxImbalance && diff <= kMaxImbalance) return a;

  // `up` is the taller child; `keep` the other one. `up` takes a's place.
  const bool rightTaller = diff > 1;
  const int32_t up = rightTaller ? c : b;
  const int32_t keep = rightTaller ? b : c;
  Node& U = nodes_[up];
  const int32_t f = U.child1, g = U.child2;
  const bool fTaller = nodes_[f].height > nodes_[g].height;
  const int32_t stays = fTaller ? f : g;   // stays under `up`
  const int32_t moves = fTaller ? g : f;   // moves under `a`

  U.child1 = a;
  U.child2 = stays;
  U.parent = A.parent;
  A.parent = up;
  if (U.parent == kNull) root_ = up;
  else if (nodes_[U.parent].child1 == a) nodes_[U.parent].child1 = up;
  else nodes_[U.parent].child2 = up;

  if (rightTaller) A.child2 = moves;
  else A.child1 = moves;
  nodes_[moves].parent = a;
  A.box = nodes_[keep].box.merged(nodes_[moves].box);
  A.height = 1 + std::max(nodes_[keep].height, nodes_[moves].height);
  U.box = A.box.merged(nodes_[stays].box);
  U.height = 1 + std::max(A.height, nodes_[stays].height);
  return up;
}

// Swaps a grandchild of `a` with its other child, or two grandchildren across, when that shrinks
// the surface area of a's children: the set of leaves under `a` (and so a's box) is unchanged.
// Greedy insertion alone left the upper boxes of a churning pile overlapping more and more (a drum
// of 2400 bodies: a query visited 500-1100 nodes to find 45 leaves; 240-310 with these swaps, 185
// in a tree built afresh top down). The swaps keep children's heights within kMaxImbalance.
bool DynamicTree::rotateForArea(int32_t a) {
  const Node& A = nodes_[a];
  const int32_t b = A.child1, c = A.child2;
  const Node& B = nodes_[b];
  const Node& C = nodes_[c];
  if (B.child1 == kNull && C.child1 == kNull) return false;
  auto area = [&](int32_t x, int32_t y) { return nodes_[x].box.merged(nodes_[y].box).perimeter(); };
  auto h = [&](int32_t x) { return nodes_[x].height; };
  auto balanced = [](int32_t hx, int32_t hy) { return std::abs(hx - hy) <= kMaxImbalance; };
  // Each option: the two nodes to swap, and the area it saves.
  int32_t swapX = kNull, swapY = kNull;
  float bestGain = 1e-6f * (B.box.perimeter() + C.box.perimeter());  // ignore gains within rounding
  auto consider = [&](int32_t x, int32_t y, float gain, bool keepsBalance) {
    if (keepsBalance && gain > bestGain) {
      bestGain = gain;
      swapX = x;
      swapY = y;
    }
  };
  // Child x of a takes the place of `up` under its sibling, beside `stays`; `up` moves beside the
  // sibling, whose area was siblingArea.
  auto lift = [&](int32_t x, int32_t up, int32_t stays, float siblingArea) {
    const bool keeps = balanced(h(x), h(stays)) && balanced(h(up), 1 + std::max(h(x), h(stays)));
    consider(x, up, siblingArea - area(x, stays), keeps);
  };
  const bool bInner = B.child1 != kNull, cInner = C.child1 != kNull;
  if (cInner) {
    lift(b, C.child1, C.child2, C.box.perimeter());
    lift(b, C.child2, C.child1, C.box.perimeter());
  }
  if (bInner) {
    lift(c, B.child1, B.child2, B.box.perimeter());
    lift(c, B.child2, B.child1, B.box.perimeter());
  }
  if (bInner && cInner) {  // a grandchild under b swaps with one under c
    const int32_t d = B.child1, e = B.child2, f = C.child1, g = C.child2;
    const float both = B.box.perimeter() + C.box.perimeter();
    auto keeps = [&](int32_t p, int32_t q, int32_t r, int32_t s) {  // children {p,q} and {r,s}
      return balanced(h(p), h(q)) && balanced(h(r), h(s)) &&
             balanced(1 + std::max(h(p), h(q)), 1 + std::max(h(r), h(s)));
    };
    consider(d, f, both - area(f, e) - area(d, g), keeps(f, e, d, g));
    consider(d, g, both - area(g, e) - area(f, d), keeps(g, e, f, d));
  }
  if (swapX == kNull) return false;
  const int32_t px = nodes_[swapX].parent, py = nodes_[swapY].parent;
  auto replaceChild = [&](int32_t parent, int32_t from, int32_t to) {
    Node& p = nodes_[parent];
    (p.child1 == from ? p.child1 : p.child2) = to;
    nodes_[to].parent = parent;
  };
  replaceChild(px, swapX, swapY);
  replaceChild(py, swapY, swapX);
  for (int32_t inner : {b, c}) {
    Node& n = nodes_[inner];
    if (n.child1 == kNull) continue;
    n.box = nodes_[n.child1].box.merged(nodes_[n.child2].box);
    n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
  }
  return true;
}

bool DynamicTree::beginRebuild() {
  leaves_.clear();
  inner_.clear();
  for (int32_t i = 0; i < int32_t(nodes_.size()); ++i) {
    const Node& n = nodes_[i];
    if (n.height == 0) {
      const Vec3 c = n.box.center();
      leaves_.push_back({{c.x(), c.y(), c.z()}, i});
    } else if (n.height > 0) {
      inner_.push_back(i);  // a tree of L leaves has L - 1 inner nodes: they are reused
    }
  }
  split_.resize(leaves_.size());
  if (leaves_.size() < 2) {
    root_ = leaves_.empty() ? kNull : leaves_[0].node;
    if (root_ != kNull) nodes_[root_].parent = kNull;
    return false;
  }
  return true;
}

uint32_t DynamicTree::splitRange(uint32_t begin, uint32_t end) {
  float lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = leaves_[begin].centre[k];
  for (uint32_t i = begin + 1; i < end; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], leaves_[i].centre[k]);
      hi[k] = std::max(hi[k], leaves_[i].centre[k]);
    }
  int axis = hi[1] - lo[1] > hi[0] - lo[0] ? 1 : 0;
  if (hi[2] - lo[2] > hi[axis] - lo[axis]) axis = 2;
  // Split at the middle of the span, not at the median: a partition is one pass without branches,
  // where finding the median took most of a rebuild (mispredicted comparisons). Left leaves fill
  // split_ from the front, right ones from the back.
  const float middle = 0.5f * (lo[axis] + hi[axis]);
  uint32_t left = begin, right = end;
  for (uint32_t i = begin; i < end; ++i) {
    const bool isLeft = leaves_[i].centre[axis] < middle;
    split_[isLeft ? left : right - 1] = leaves_[i];
    left += isLeft;
    right -= !isLeft;
  }
  if (left == begin || left == end) return begin + (end - begin) / 2;  // all centres alike: any halves do
  std::copy(split_.begin() + begin, split_.begin() + end, leaves_.begin() + begin);
  return left;
}

int32_t DynamicTree::buildRange(uint32_t begin, uint32_t end, uint32_t firstInner) {
  if (end - begin == 1) return leaves_[begin].node;
  const uint32_t mid = splitRange(begin, end);
  const int32_t node = inner_[firstInner];
  link(node, buildRange(begin, mid, firstInner + 1), buildRange(mid, end, firstInner + (mid - begin)));
  return node;
}

void DynamicTree::link(int32_t node, int32_t child1, int32_t child2) {
  Node& n = nodes_[node];
  n.child1 = child1;
  n.child2 = child2;
  n.box = nodes_[child1].box.merged(nodes_[child2].box);
  n.height = 1 + std::max(nodes_[child1].height, nodes_[child2].height);
  nodes_[child1].parent = node;
  nodes_[child2].parent = node;
}

float DynamicTree::internalArea() const {
  float sum = 0.0f;
  for (const Node& n : nodes_)
    if (n.height > 0) sum += n.box.perimeter();
  return sum;
}

bool DynamicTree::validate() const {
  if (root_ == kNull) return proxyCount_ == 0;
  return nodes_[root_].parent == kNull && validateNode(root_, kNull);
}

bool DynamicTree::validateNode(int32_t n, int32_t parent) const {
  const Node& node = nodes_[n];
  if (node.parent != parent) return false;
  if (node.child1 == kNull) return node.child2 == kNull && node.height == 0;
  const Node& c1 = nodes_[node.child1];
  const Node& c2 = nodes_[node.child2];
  if (node.height != 1 + std::max(c1.height, c2.height)) return false;
  if (!node.box.contains(c1.box) || !node.box.contains(c2.box)) return false;
  return validateNode(node.child1, n) && validateNode(node.child2, n);
}

}  // namespace haif
