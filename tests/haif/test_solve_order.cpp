// The order the sweeps take an island's contacts in: top-down, then interleaved into lane batches
// (World::batchLanes) so neighbours share no body. The interleaving is for the processor only: it
// must not change a bit of the result.
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

using namespace test;

// Some of everything the order meets: a 2D pyramid big enough to be split into strips, small
// pyramids (islands of their own), a stack (a chain), and spheres landing on the small pyramids.
void buildPiles(World& w) {
  addGround(w);
  addPyramid2d(w, 40);
  for (int p = 0; p < 6; ++p)
    for (int i = 0; i < 6; ++i)
      for (int j = i; j < 6; ++j)
        addBox(w, Vec3(0.5f * float(i + 1) + float(j - i) - 3.0f + 8.0f * float(p % 3), 0.5f + float(i),
                       3.0f + 3.0f * float(p / 3)));
  addColumn(w, 12, 30.0f, 0.0f);
  for (int s = 0; s < 6; ++s) addSphere(w, Vec3(8.0f * float(s % 3), 8.0f, 3.0f + 3.0f * float(s / 3)), 0.4f);
}

uint64_t hashAfter(int steps, bool interleave, int threads) {
  WorldSettings ws;
  ws.iterations = 10;
  ws.threads = threads;
  ws.interleaveSolveOrder = interleave;
  World w(ws);
  buildPiles(w);
  for (int s = 0; s < steps; ++s) w.step();
  return w.stateHash();
}

TEST(SolveOrder, InterleavingChangesNoBitOfTheResult) {
  for (const int threads : {1, 2}) {
    EXPECT_EQ(hashAfter(90, true, threads), hashAfter(90, false, threads)) << threads << " threads";
  }
}

// Share of an island's consecutive contacts that share a dynamic body, over all islands.
double sharedNeighbours(const World& w) {
  const IslandSet& is = w.islands();
  const BodyStore& b = w.bodies();
  size_t pairs = 0, shared = 0;
  for (const Island& isl : is.islands)
    for (uint32_t j = 1; j < isl.contactCount; ++j) {
      const Contact& p = w.contacts()[is.contacts[isl.firstContact + j - 1]];
      const Contact& c = w.contacts()[is.contacts[isl.firstContact + j]];
      auto moves = [&](uint32_t body) { return b.isAwakeDynamic(body); };
      const bool share = (moves(c.a) && (c.a == p.a || c.a == p.b)) || (moves(c.b) && (c.b == p.a || c.b == p.b));
      ++pairs;
      shared += share ? 1 : 0;
    }
  return pairs ? double(shared) / double(pairs) : 0.0;
}

TEST(SolveOrder, NeighboursShareNoBodyOnceInterleaved) {
  // In top-down order a row of boxes is a path: 56 % of neighbours share a body. Interleaved: 14 %.
  double share[2];
  for (const bool interleave : {false, true}) {
    WorldSettings ws;
    ws.interleaveSolveOrder = interleave;
    World w(ws);
    buildPiles(w);
    for (int s = 0; s < 5; ++s) w.step();
    share[interleave] = sharedNeighbours(w);
  }
  EXPECT_GT(share[0], 0.4);
  EXPECT_LT(share[1], 0.2);
}

}  // namespace
}  // namespace haif
