// DynamicTree against brute force: random insert / move / remove keep the invariants, the height
// logarithmic, and every query returns exactly the overlapping proxies.
#include "collision/dynamic_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

namespace haif {
namespace {

struct Item {
  int32_t proxy = DynamicTree::kNull;
  Aabb box;
  bool alive = false;
};

Aabb randomBox(std::mt19937& rng, float world = 100.0f) {
  std::uniform_real_distribution<float> pos(-world, world), size(0.1f, 3.0f);
  const Vec3 c(pos(rng), pos(rng), pos(rng));
  const Vec3 h(size(rng), size(rng), size(rng));
  return {c - h, c + h};
}

std::set<uint32_t> treeQuery(const DynamicTree& t, const Aabb& q) {
  std::set<uint32_t> out;
  t.query(q, [&](uint32_t u) { EXPECT_TRUE(out.insert(u).second) << "proxy reported twice: " << u; });
  return out;
}

std::set<uint32_t> bruteQuery(const std::vector<Item>& items, const Aabb& q) {
  std::set<uint32_t> out;
  for (uint32_t i = 0; i < items.size(); ++i)
    if (items[i].alive && items[i].box.overlaps(q)) out.insert(i);
  return out;
}

// A balanced binary tree of n leaves has height ~log2(n); allow the slack of an AVL-like balance.
int heightBound(int n) { return n <= 1 ? 0 : int(2.0 * std::ceil(std::log2(double(n)))) + 2; }

TEST(DynamicTree, RandomOpsKeepInvariantsAndMatchBruteForce) {
  std::mt19937 rng(1234);
  DynamicTree tree;
  std::vector<Item> items(2000);
  int alive = 0;
  std::uniform_int_distribution<int> op(0, 9);
  std::uniform_int_distribution<uint32_t> pick(0, uint32_t(items.size() - 1));
  for (int k = 0; k < 20000; ++k) {
    Item& it = items[pick(rng)];
    const uint32_t id = uint32_t(&it - items.data());
    const int o = op(rng);
    if (!it.alive) {
      it.box = randomBox(rng);
      it.proxy = tree.createProxy(it.box, id);
      it.alive = true;
      ++alive;
    } else if (o < 7) {
      // Small moves (the common case) and occasional teleports.
      if (o < 5) {
        std::uniform_real_distribution<float> d(-1.0f, 1.0f);
        const Vec3 dv(d(rng), d(rng), d(rng));
        it.box = {it.box.lo + dv, it.box.hi + dv};
      } else {
        it.box = randomBox(rng);
      }
      tree.moveProxy(it.proxy, it.box);
    } else {
      tree.destroyProxy(it.proxy);
      it.alive = false;
      --alive;
    }
    ASSERT_EQ(tree.proxyCount(), alive);
    if (k % 500 == 0) {
      ASSERT_TRUE(tree.validate()) << "after op " << k;
      EXPECT_LE(tree.height(), heightBound(alive)) << "proxies " << alive;
      for (int q = 0; q < 20; ++q) {
        const Aabb box = randomBox(rng);
        const Aabb big = box.expanded(10.0f);
        ASSERT_EQ(treeQuery(tree, box), bruteQuery(items, box)) << "op " << k;
        ASSERT_EQ(treeQuery(tree, big), bruteQuery(items, big)) << "op " << k;
      }
    }
  }
  for (const Item& it : items)
    if (it.alive) {
      EXPECT_EQ(tree.fatAabb(it.proxy).lo, it.box.lo);
      EXPECT_EQ(tree.fatAabb(it.proxy).hi, it.box.hi);
      EXPECT_EQ(tree.userData(it.proxy), uint32_t(&it - items.data()));
    }
}

TEST(DynamicTree, SortedInsertionStaysBalanced) {
  // Inserting along a line is the worst case for an unbalanced tree (it degenerates to a list).
  DynamicTree tree;
  const int n = 4096;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(float(i), 0.0f, 0.0f);
    tree.createProxy({c - Vec3::Constant(0.4f), c + Vec3::Constant(0.4f)}, uint32_t(i));
  }
  ASSERT_TRUE(tree.validate());
  EXPECT_LE(tree.height(), heightBound(n));
  // Each box overlaps only itself along the line.
  for (int i = 0; i < n; i += 97) {
    const Vec3 c(float(i), 0.0f, 0.0f);
    const auto got = treeQuery(tree, {c - Vec3::Constant(0.1f), c + Vec3::Constant(0.1f)});
    EXPECT_EQ(got, std::set<uint32_t>{uint32_t(i)});
  }
}

TEST(DynamicTree, RemoveEverythingLeavesAnEmptyTree) {
  std::mt19937 rng(7);
  DynamicTree tree;
  std::vector<int32_t> proxies;
  for (int i = 0; i < 300; ++i) proxies.push_back(tree.createProxy(randomBox(rng), uint32_t(i)));
  std::shuffle(proxies.begin(), proxies.end(), rng);
  for (int32_t p : proxies) tree.destroyProxy(p);
  EXPECT_EQ(tree.proxyCount(), 0);
  EXPECT_EQ(tree.height(), 0);
  EXPECT_TRUE(treeQuery(tree, {Vec3::Constant(-1e6f), Vec3::Constant(1e6f)}).empty());
  // Freed nodes are reused and the tree works again.
  const int32_t p = tree.createProxy({Vec3::Zero(), Vec3::Ones()}, 42);
  EXPECT_TRUE(tree.validate());
  EXPECT_EQ(treeQuery(tree, {Vec3::Constant(0.5f), Vec3::Constant(2.0f)}), std::set<uint32_t>{42});
  EXPECT_EQ(tree.userData(p), 42u);
}

}  // namespace
}  // namespace haif
