// Lane batches (haif/lane_batches.h) and the wide sweep in the world (WorldSettings::wideSolve).
#include "haif/lane_batches.h"
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace haif {
namespace {

using test::addGround;
using test::addPyramid2d;

// Random contacts among 40 dynamic bodies and 2 static ones, in a random solve order.
struct RandomGraph {
  BodyStore bodies;
  std::vector<Contact> contacts;
  std::vector<uint32_t> ids;
  explicit RandomGraph(uint32_t seed, int n = 300) {
    for (int i = 0; i < 2; ++i) bodies.add(BodyKind::Static, Transform{}, 0.0f, Mat3::Zero());
    for (int i = 0; i < 40; ++i) bodies.add(BodyKind::Dynamic, Transform{}, 1.0f, Mat3::Identity());
    std::mt19937 rng(seed);
    std::uniform_int_distribution<uint32_t> body(0, 41);
    while (int(contacts.size()) < n) {
      Contact c;
      c.a = body(rng);
      c.b = body(rng);
      if (c.a == c.b || (c.a < 2 && c.b < 2)) continue;
      ids.push_back(uint32_t(contacts.size()));
      contacts.push_back(c);
    }
  }
  bool dynamic(uint32_t b) const { return bodies.kind[b] == BodyKind::Dynamic; }
};

TEST(LaneBatches, BatchesShareNoDynamicBodyAndKeepEachBodysOrder) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    RandomGraph g(seed);
    std::vector<uint32_t> ids = g.ids;
    std::vector<uint8_t> run(ids.size());
    LaneBatcher batcher;
    batcher.batch(g.bodies, g.contacts.data(), nullptr, ids.data(), uint32_t(ids.size()), run.data());
    // A permutation of the input, cut into runs of 1..kLanes.
    std::vector<uint32_t> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, g.ids);
    size_t j = 0, batches = 0;
    while (j < ids.size()) {
      const int len = run[j];
      ASSERT_GE(len, 1);
      ASSERT_LE(len, kLanes);
      std::vector<uint32_t> seen;
      for (int k = 0; k < len; ++k) {
        const Contact& c = g.contacts[ids[j + size_t(k)]];
        if (k > 0) {
          EXPECT_EQ(run[j + size_t(k)], 0);
        }
        for (const uint32_t b : {c.a, c.b}) {
          if (!g.dynamic(b)) continue;
          EXPECT_EQ(std::count(seen.begin(), seen.end(), b), 0) << "body " << b << " twice in a batch";
          seen.push_back(b);
        }
      }
      j += size_t(len);
      ++batches;
    }
    EXPECT_LT(batches, ids.size());  // some batches hold several constraints
    // Per dynamic body, its contacts come in the input order (input ids are increasing).
    for (uint32_t b = 2; b < 42; ++b) {
      uint32_t last = 0;
      bool first = true;
      for (const uint32_t id : ids) {
        const Contact& c = g.contacts[id];
        if (c.a != b && c.b != b) continue;
        if (!first) {
          EXPECT_GT(id, last) << "body " << b;
        }
        last = id;
        first = false;
      }
    }
  }
}

TEST(LaneBatches, ALevelIsColouredSoItsPathFillsLanes) {
  // A row of 17 boxes touching side by side: 16 contacts forming a path, all at one height. In
  // solve order each shares a box with the next, so without levels every batch holds one contact;
  // coloured as one level they go into batches of 8 (every other contact).
  BodyStore bodies;
  std::vector<Contact> contacts;
  std::vector<uint32_t> ids;
  for (int i = 0; i < 17; ++i) bodies.add(BodyKind::Dynamic, Transform{}, 1.0f, Mat3::Identity());
  std::vector<float> level;
  for (uint32_t i = 0; i + 1 < 17; ++i) {
    Contact c;
    c.a = i;
    c.b = i + 1;
    ids.push_back(uint32_t(contacts.size()));
    contacts.push_back(c);
    level.push_back(1.0f);
  }
  std::vector<uint8_t> run(ids.size());
  LaneBatcher batcher;
  std::vector<uint32_t> plain = ids;
  batcher.batch(bodies, contacts.data(), nullptr, plain.data(), uint32_t(plain.size()), run.data());
  EXPECT_EQ(std::count(run.begin(), run.end(), 1), 16);
  batcher.batch(bodies, contacts.data(), level.data(), ids.data(), uint32_t(ids.size()), run.data());
  EXPECT_EQ(run[0], 8);
  EXPECT_EQ(run[8], 8);
}

// A 2D pyramid of `base` boxes on the ground, `steps` at 60 Hz and 10 iterations.
std::vector<Vec3> runPyramid(int base, int steps, bool wide, int threads, uint64_t* hash) {
  WorldSettings ws;
  ws.iterations = 10;
  ws.wideSolve = wide;
  ws.threads = threads;
  World w(ws);
  addGround(w);
  addPyramid2d(w, base);
  for (int s = 0; s < steps; ++s) w.step();
  if (hash) *hash = w.stateHash();
  std::vector<Vec3> positions;
  for (const Transform& t : w.bodies().xf) positions.push_back(t.p);
  return positions;
}

TEST(WideSolve, PyramidStandsAsWithScalarSweeps) {
  uint64_t hs = 0, hw = 0;
  const std::vector<Vec3> start = runPyramid(20, 0, false, 1, nullptr);
  const std::vector<Vec3> scalar = runPyramid(20, 120, false, 1, &hs);
  const std::vector<Vec3> wide = runPyramid(20, 120, true, 1, &hw);
  float maxDiff = 0.0f, drop = 0.0f;
  for (size_t i = 1; i < start.size(); ++i) {
    maxDiff = std::max(maxDiff, (wide[i] - scalar[i]).norm());
    drop += start[i].y() - wide[i].y();
  }
  drop /= float(start.size() - 1);
  EXPECT_NE(hw, hs);  // the wide code ran (its rounding differs)...
  EXPECT_LT(maxDiff, 1e-3f);  // ...and did what the scalar sweeps do
  EXPECT_LT(drop, 0.01f);     // the pyramid stands
}

TEST(WideSolve, SplitIslandHasOneStateForAnyThreadCount) {
  // 820 boxes: one island of ~17000 rows, split into strips and swept in lane batches.
  test::expectSameStateForThreadCounts([](int threads) {
    uint64_t h = 0;
    runPyramid(40, 20, true, threads, &h);
    return h;
  });
}

}  // namespace
}  // namespace haif
