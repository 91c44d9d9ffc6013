// Giant islands are cut into strips whose two phases can be swept in parallel (haif/island_split.h).
#include "haif/island_split.h"
#include "haif/tsan_pool.h"
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <set>

namespace haif {
namespace {

using test::addBox;
using test::addGround;
using test::addPyramid2d;

/// A world holding a pyramid big enough to be split, advanced a few steps so its contacts exist.
void buildPyramid(World& w, int base, int steps) {
  addGround(w);
  addPyramid2d(w, base);
  for (int s = 0; s < steps; ++s) w.step();
}

TEST(IslandSplit, StripsOfOnePhaseShareNoDynamicBody) {
  World w;
  buildPyramid(w, 40, 2);
  const IslandSet& set = w.islands();
  ASSERT_EQ(set.islands.size(), 1u);
  ASSERT_GE(set.islands[0].rows, kSplitRows);

  IslandSet copy = set;
  IslandSplitter splitter;
  StripLayout layout;
  splitter.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout);
  ASSERT_GE(layout.strips, 2u);
  const Island& isl = copy.islands[0];
  EXPECT_EQ(layout.start[layout.strips + 1], isl.contactCount);

  // The same contacts, regrouped.
  std::multiset<uint32_t> before(set.contacts.begin(), set.contacts.end());
  std::multiset<uint32_t> after(copy.contacts.begin(), copy.contacts.end());
  EXPECT_EQ(before, after);

  auto dynamicBodies = [&](uint32_t s) {
    std::set<uint32_t> bodies;
    for (uint32_t j = layout.start[s]; j < layout.start[s + 1]; ++j) {
      const Contact& c = w.contacts()[copy.contacts[isl.firstContact + j]];
      for (uint32_t b : {c.a, c.b})
        if (w.bodies().isDynamic(b)) bodies.insert(b);
    }
    return bodies;
  };
  uint32_t tasksWithWork = 0;
  for (uint32_t phase = 0; phase < 2; ++phase) {
    std::set<uint32_t> seen;
    for (uint32_t s = phase; s < layout.strips; s += 2) {
      const std::set<uint32_t> mine = dynamicBodies(s);
      if (!mine.empty()) ++tasksWithWork;
      for (uint32_t b : mine) EXPECT_TRUE(seen.insert(b).second) << "body " << b << " in two strips of phase " << phase;
    }
  }
  EXPECT_GE(tasksWithWork, layout.strips - 1) << "strips should all carry work";
  // Unit boxes never span more than neighbouring strips: nothing is left for the serial tail.
  EXPECT_EQ(layout.start[layout.strips + 1] - layout.start[layout.strips], 0u);
  // The critical path is shorter than the island.
  EXPECT_LT(layout.criticalRows(), isl.rows);
}

TEST(IslandSplit, StripsHoldEqualShareOfTheBodiesInOrderAlongTheCut) {
  World w;
  buildPyramid(w, 40, 2);  // 820 boxes: the cut runs along x, the pyramid's width
  IslandSet copy = w.islands();
  IslandSplitter splitter;
  StripLayout layout;
  splitter.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout);
  const Island& isl = copy.islands[0];
  std::vector<uint32_t> count(layout.strips, 0);
  std::vector<float> lo(layout.strips, 1e30f), hi(layout.strips, -1e30f);
  for (uint32_t j = 0; j < isl.bodyCount; ++j) {
    const uint32_t b = copy.bodies[isl.firstBody + j], s = splitter.stripOf(b);
    ASSERT_LT(s, layout.strips);
    ++count[s];
    lo[s] = std::min(lo[s], w.bodies().xf[b].p.x());
    hi[s] = std::max(hi[s], w.bodies().xf[b].p.x());
  }
  for (uint32_t s = 0; s < layout.strips; ++s) {
    // ranks [ceil(s n / K), ceil((s + 1) n / K)): counts differ by at most one
    EXPECT_LE(count[s], isl.bodyCount / layout.strips + 1) << "strip " << s;
    EXPECT_GE(count[s], isl.bodyCount / layout.strips) << "strip " << s;
    if (s > 0) {
      EXPECT_LE(hi[s - 1], lo[s]) << "strip " << s - 1 << " reaches past strip " << s;
    }
  }
}

TEST(IslandSplit, KeepsTheSolveOrderInsideEachStrip) {
  World w;
  buildPyramid(w, 40, 2);
  const IslandSet& set = w.islands();
  const Island& isl = set.islands[0];
  // The island's contacts arrive in solve order (top-down); each strip keeps that order.
  std::vector<uint32_t> rank(w.contacts().size());
  for (uint32_t j = 0; j < isl.contactCount; ++j) rank[set.contacts[isl.firstContact + j]] = j;
  IslandSet copy = set;
  IslandSplitter splitter;
  StripLayout layout;
  splitter.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout);
  for (uint32_t s = 0; s <= layout.strips; ++s)
    for (uint32_t j = layout.start[s] + 1; j < layout.start[s + 1]; ++j)
      EXPECT_LT(rank[copy.contacts[isl.firstContact + j - 1]], rank[copy.contacts[isl.firstContact + j]])
          << "strip " << s << " position " << j;
}

TEST(IslandSplit, AWideBodyGoesToTheSerialTail) {
  World w;
  addGround(w);
  // A long plank lying across a row of 600 boxes: it touches boxes in every strip.
  for (int i = 0; i < 600; ++i) addBox(w, Vec3(float(i) * 1.0f - 300.0f, 0.5f, 0.0f));
  addBox(w, Vec3(0.0f, 1.25f, 0.0f), Vec3(300.0f, 0.25f, 0.5f), 600.0f);
  w.step();
  const IslandSet& set = w.islands();
  ASSERT_EQ(set.islands.size(), 1u);
  IslandSet copy = set;
  IslandSplitter splitter;
  StripLayout layout;
  splitter.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout);
  ASSERT_GE(layout.strips, 2u);
  EXPECT_GT(layout.start[layout.strips + 1] - layout.start[layout.strips], 0u);
}

// The split's stages run chunk by chunk on a pool's threads, or in reverse order; the strips, their
// order and the regrouped contacts are those of the split on one thread, every time.
TEST(IslandSplit, ConcurrentSplitMatchesTheSplitOnOneThreadCount) {
  World w;
  buildPyramid(w, 70, 2);  // 2485 boxes, ~4800 contacts: several chunks of each kind
  const IslandSet& set = w.islands();
  ASSERT_EQ(set.islands.size(), 1u);
  IslandSet serial = set;
  IslandSplitter one;
  StripLayout expected;
  one.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), serial, 0, expected);
  ASSERT_GE(expected.strips, 16u);
  TsanPool pool(4);
  for (int round = 0; round < 5; ++round) {
    IslandSet copy = set;
    IslandSplitter many;
    StripLayout layout;
    // Round 0 runs the ranges one at a time, last first: any order is allowed, so none may matter.
    many.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout,
               [&](uint32_t n, uint32_t grain, auto&& f) {
                 if (round > 0) return pool.run(n, std::max(1u, grain / 8), f);
                 for (uint32_t i = n; i-- > 0;) f(i, i + 1);
               });
    ASSERT_EQ(layout.strips, expected.strips);
    for (uint32_t s = 0; s <= layout.strips + 1; ++s) EXPECT_EQ(layout.start[s], expected.start[s]) << "strip " << s;
    for (uint32_t s = 0; s <= layout.strips; ++s) EXPECT_EQ(layout.rows[s], expected.rows[s]) << "strip " << s;
    EXPECT_EQ(copy.contacts, serial.contacts) << "round " << round;
    for (uint32_t b : set.bodies) EXPECT_EQ(many.stripOf(b), one.stripOf(b)) << "body " << b;
  }
}

TEST(IslandSplit, BodiesComeStripByStripAndTheImmovableOnesOnce) {
  // The solver copies a split island's velocities into this order (World::assignSlots), so that
  // strips swept at once write apart in memory; the immovable bodies are read from slots of their own.
  World w;
  const uint32_t ground = addGround(w);
  addPyramid2d(w, 40);
  for (int s = 0; s < 2; ++s) w.step();
  IslandSet copy = w.islands();
  ASSERT_EQ(copy.islands.size(), 1u);
  IslandSplitter splitter;
  StripLayout layout;
  splitter.split(w.bodies(), w.contactEdges().data(), Vec3::UnitY(), copy, 0, layout);
  const Island& isl = copy.islands[0];
  std::set<uint32_t> ranked;
  uint32_t lastStrip = 0;
  for (uint32_t r = 0; r < isl.bodyCount; ++r) {
    const uint32_t body = splitter.bodyAtRank(r);
    EXPECT_TRUE(ranked.insert(body).second) << "body " << body << " ranked twice";
    EXPECT_GE(splitter.stripOf(body), lastStrip) << "rank " << r;
    lastStrip = splitter.stripOf(body);
  }
  EXPECT_EQ(ranked, std::set<uint32_t>(copy.bodies.begin() + isl.firstBody, copy.bodies.begin() + isl.firstBody + isl.bodyCount));
  EXPECT_EQ(lastStrip, layout.strips - 1);
  EXPECT_EQ(splitter.immovableBodies(), std::vector<uint32_t>{ground});
}

// A phase's strips are dealt to its tasks in contiguous groups: every strip once, one group per
// thread where there are strips enough, and no group more than one strip larger than another (3
// tasks of two strips on 2 threads left one thread idle for a third of the phase).
TEST(IslandSplit, APhasesStripsAreDealtEvenlyToOneGroupPerThread) {
  for (uint32_t strips = 1; strips <= kMaxStrips / 2; ++strips)
    for (int threads = 1; threads <= 16; ++threads) {
      const uint32_t groups = stripGroups(strips, threads);
      EXPECT_EQ(groups, std::min(strips, uint32_t(threads))) << strips << " strips, " << threads << " threads";
      uint32_t next = 0, least = strips, most = 0;
      for (uint32_t g = 0; g < groups; ++g) {
        const StripGroup group = stripGroup(g, groups, strips);
        EXPECT_EQ(group.first, next) << "group " << g << " of " << groups << ", " << strips << " strips";
        EXPECT_GT(group.last, group.first) << "group " << g << " is empty";
        next = group.last;
        least = std::min(least, group.last - group.first);
        most = std::max(most, group.last - group.first);
      }
      EXPECT_EQ(next, strips) << strips << " strips, " << threads << " threads";
      EXPECT_LE(most - least, 1u) << strips << " strips, " << threads << " threads";
      EXPECT_EQ(most, (strips + groups - 1) / groups) << strips << " strips, " << threads << " threads";
    }
}

TEST(IslandSplit, SameStateForAnyThreadCount) {
  test::expectSameStateForThreadCounts([](int threads) {
    WorldSettings ws;
    ws.threads = threads;
    World w(ws);
    buildPyramid(w, 40, 60);
    return w.stateHash();
  });
}

}  // namespace
}  // namespace haif
