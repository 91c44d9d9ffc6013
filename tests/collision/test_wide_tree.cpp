// The broad phase's four-wide copy of its tree (collision/wide_tree.h) answers every query with
// the same leaves in the same order as the tree itself: the pairs, and so the contacts' order and
// every result after them, do not depend on which of the two a step queried.
#include "collision/broad_phase.h"
#include "collision/wide_tree.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

namespace haif {
namespace {

Aabb cube(const Vec3& centre, float half) { return {centre - Vec3::Constant(half), centre + Vec3::Constant(half)}; }

std::vector<uint32_t> queried(const DynamicTree& tree, const Aabb& box) {
  std::vector<uint32_t> leaves;
  tree.query(box, [&](uint32_t u) { leaves.push_back(u); });
  return leaves;
}

std::vector<uint32_t> queried(const WideTree& tree, const Aabb& box) {
  std::vector<uint32_t> leaves;
  tree.query(box, [&](uint32_t u) { leaves.push_back(u); });
  return leaves;
}

// A tree grown leaf by leaf, then moved about (each move a removal and an insertion with rotations),
// then built afresh: at every stage, random boxes of every size find the same leaves in the same
// order in the tree and in its wide copy.
TEST(WideTree, FindsWhatTheTreeFindsInTheSameOrder) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> pos(-6.0f, 6.0f), size(0.05f, 0.6f), step(-0.4f, 0.4f), reach(0.0f, 3.0f);
  DynamicTree tree;
  WideTree wide;
  auto compare = [&](const char* stage) {
    wide.build(tree);
    size_t found = 0;
    for (int q = 0; q < 300; ++q) {
      const Aabb box = cube(Vec3(pos(rng), pos(rng), pos(rng)), reach(rng));
      const std::vector<uint32_t> expected = queried(tree, box);
      EXPECT_EQ(queried(wide, box), expected) << stage << ", query " << q;
      found += expected.size();
    }
    return found;
  };
  EXPECT_EQ(compare("empty"), 0u);
  std::vector<int32_t> proxies;
  std::vector<Vec3> centres;
  for (uint32_t i = 0; i < 700; ++i) {
    centres.push_back(Vec3(pos(rng), pos(rng), pos(rng)));
    proxies.push_back(tree.createProxy(cube(centres.back(), size(rng)), 1000 + i));
    if (i == 0) {
      EXPECT_LE(compare("one leaf"), 300u);
    }
  }
  EXPECT_GT(compare("grown"), 1000u);  // the queries meet leaves: the comparison is not of empty lists
  for (int round = 0; round < 3; ++round)
    for (uint32_t i = 0; i < proxies.size(); i += 2) {
      centres[i] += Vec3(step(rng), step(rng), step(rng));
      tree.moveProxy(proxies[i], cube(centres[i], size(rng)));
    }
  ASSERT_TRUE(tree.validate());
  EXPECT_GT(compare("moved"), 1000u);
  tree.rebuild();
  EXPECT_GT(compare("rebuilt"), 1000u);
}

// Two broad phases driven alike, one of them reading its wide copies, report the same new pairs in
// the same order, step after step; a copy made before bodies moved is not read after they did.
TEST(WideTree, ABroadPhaseReadingItsCopyReportsTheSamePairsAfterEveryMove) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> pos(-4.0f, 4.0f), step(-0.15f, 0.15f);
  const uint32_t n = 500;
  BroadPhase plain, wide;
  std::vector<Vec3> centre(n);
  for (uint32_t i = 0; i < n; ++i) {
    centre[i] = Vec3(pos(rng), pos(rng), pos(rng));
    const bool isStatic = i % 50 == 0;
    plain.addBody(i, cube(centre[i], 0.2f), isStatic);
    wide.addBody(i, cube(centre[i], 0.2f), isStatic);
  }
  auto pairs = [](BroadPhase& bp) {
    std::vector<std::pair<uint32_t, uint32_t>> found;
    for (uint32_t m : bp.moved()) bp.queryMoved(m, [&](uint32_t a, uint32_t b) { found.emplace_back(a, b); });
    bp.clearMoved();
    return found;
  };
  wide.prepareQueries();
  EXPECT_EQ(pairs(wide), pairs(plain));
  size_t reported = 0;
  for (int s = 0; s < 30; ++s) {
    // The copy is made at the start of some steps, before the moves: those moves must make it stale.
    if (s % 3 == 0) wide.prepareQueries();
    const bool rebuild = s % 2 == 1;
    for (uint32_t i = 0; i < n; ++i) {
      if (i % 50 == 0) continue;  // static
      centre[i] += Vec3(step(rng), step(rng), step(rng));
      const Aabb tight = cube(centre[i], 0.2f);
      for (BroadPhase* bp : {&plain, &wide})
        if (!bp->fits(i, tight)) bp->move(i, tight, Vec3::Zero(), rebuild);
    }
    if (rebuild) {
      plain.rebuildMovingTree();
      wide.rebuildMovingTree();
    }
    if (s % 3 != 0) wide.prepareQueries();
    const auto expected = pairs(plain);
    ASSERT_EQ(pairs(wide), expected) << "step " << s;
    reported += expected.size();
  }
  EXPECT_GT(reported, 200u);
}

}  // namespace
}  // namespace haif
