// The broad phase's fat boxes: a box that leads along a body's path is re-inserted every few steps,
// and the pairs still appear no later than the bodies' swept boxes meet.
#include "collision/broad_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

namespace haif {
namespace {

Aabb cube(const Vec3& centre, float half) { return {centre - Vec3::Constant(half), centre + Vec3::Constant(half)}; }

// Steps a 0.3 m box falling at `speed` for `steps` steps (dt 1/60), its fat box leading
// `leadSteps` steps of its path; returns how often it was re-inserted.
int reinsertions(float speed, int leadSteps, int steps) {
  BroadPhase bp;
  const float dt = 1.0f / 60.0f;
  Vec3 p(0.0f, 100.0f, 0.0f);
  bp.addBody(0, cube(p, 0.3f), false);
  int count = 0;
  for (int s = 0; s < steps; ++s) {
    const Vec3 d(0.0f, -speed * dt, 0.0f);
    if (bp.update(0, cube(p, 0.3f).swept(d), float(leadSteps) * d)) ++count;
    bp.clearMoved();
    p += d;
  }
  return count;
}

TEST(BroadPhase, ABoxLeadingAlongTheBodysPathIsReinsertedEveryFewSteps) {
  // At 12 m/s a step moves 0.2 m, past the kept margin: re-inserted every step without a lead.
  EXPECT_EQ(reinsertions(12.0f, 0, 60), 60);
  const int led = reinsertions(12.0f, 4, 60);
  EXPECT_LE(led, 60 / 4 + 1);
  EXPECT_GE(led, 60 / 6);  // the lead is four steps, not more: boxes stay as small as they can be
}

// A box falls past others placed beside and under its path at random offsets; every pair whose
// swept boxes overlap at a step has been reported by that step, with the lead as without it.
TEST(BroadPhase, ALeadingBoxReportsEveryPairNoLaterThanTheSweptBoxesMeet) {
  for (int leadSteps : {0, 4}) {
    BroadPhase bp;
    const float dt = 1.0f / 60.0f, half = 0.2f;
    Vec3 p(0.0f, 20.0f, 0.0f);
    bp.addBody(0, cube(p, half), false);
    std::vector<Aabb> others;
    for (int k = 0; k < 40; ++k) {
      // A column of boxes a little off the path (some within reach, some not), every 0.45 m down.
      const float off = 0.05f * float(k % 13) - 0.3f;
      const Vec3 c(off, 19.0f - 0.45f * float(k), 0.25f * float((k * 7) % 5) - 0.5f);
      others.push_back(cube(c, half));
      bp.addBody(uint32_t(k + 1), others.back(), true);
    }
    std::set<std::pair<uint32_t, uint32_t>> pairs;
    for (int s = 0; s < 120; ++s) {
      const Vec3 d(0.0f, -(2.0f + 0.2f * float(s)) * dt, 0.0f);  // speeding up, as in free fall
      const Aabb box = cube(p, half).swept(d);
      bp.update(0, box, float(leadSteps) * d);
      bp.findNewPairs([&](uint32_t a, uint32_t b) { pairs.insert({std::min(a, b), std::max(a, b)}); });
      for (uint32_t k = 0; k < others.size(); ++k)
        if (box.overlaps(others[k])) {
          EXPECT_TRUE(pairs.count({0u, k + 1})) << "lead " << leadSteps << ", step " << s << ", box " << k + 1;
        }
      p += d;
    }
    EXPECT_GE(pairs.size(), 10u);
  }
}

// A churning pile moves many bodies a step; the broad phase may then set their boxes and build
// the tree afresh (World::updateBroadPhase). The new pairs must be those that moving each body
// into the tree finds: they depend on the fat boxes only, not on the tree.
TEST(BroadPhase, MovesFollowedByARebuildFindTheSamePairsAsMovesOneByOne) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> pos(-4.0f, 4.0f), step(-0.12f, 0.12f);
  const uint32_t n = 600;
  std::vector<Vec3> centre(n);
  BroadPhase oneByOne, rebuilt;
  for (uint32_t i = 0; i < n; ++i) {
    centre[i] = Vec3(pos(rng), pos(rng), pos(rng));
    oneByOne.addBody(i, cube(centre[i], 0.2f), false);
    rebuilt.addBody(i, cube(centre[i], 0.2f), false);
  }
  auto pairsOf = [](BroadPhase& bp) {
    std::set<std::pair<uint32_t, uint32_t>> pairs;
    bp.findNewPairs([&](uint32_t a, uint32_t b) { EXPECT_TRUE(pairs.insert({std::min(a, b), std::max(a, b)}).second); });
    return pairs;
  };
  EXPECT_EQ(pairsOf(oneByOne), pairsOf(rebuilt));
  size_t found = 0, moved = 0;
  for (int s = 0; s < 40; ++s) {
    for (uint32_t i = 0; i < n; ++i) {
      centre[i] += Vec3(step(rng), step(rng), step(rng));
      const Aabb tight = cube(centre[i], 0.2f);
      oneByOne.update(i, tight);
      if (!rebuilt.fits(i, tight)) rebuilt.move(i, tight, Vec3::Zero(), true);
    }
    moved += rebuilt.moved().size();
    EXPECT_EQ(oneByOne.moved(), rebuilt.moved()) << "step " << s;
    rebuilt.rebuildMovingTree();
    ASSERT_TRUE(rebuilt.movingTree().validate()) << "step " << s;
    const auto want = pairsOf(oneByOne), got = pairsOf(rebuilt);
    EXPECT_EQ(got, want) << "step " << s;
    found += want.size();
  }
  EXPECT_GE(moved, size_t(40 * n / 4));  // most steps would rebuild in a World
  EXPECT_GE(found, 1000u);
}

}  // namespace
}  // namespace haif
