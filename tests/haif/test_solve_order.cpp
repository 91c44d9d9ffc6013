// The order the sweeps take an island's contacts in: top-down, then interleaved into lane batches
// (World::batchLanes) so neighbours share no body. The interleaving is for the processor only: it
// must not change a bit of the result.
#include "core/sort_key.h"
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

// An island whose contacts stay as they were takes last step's order again, as long as its contacts
// still sort that way: two stacks bridged by a plank on a kinematic platform that tilts keep every
// contact while one stack sinks below the other, so contacts the plank shares change places. Every
// step, each dynamic body's contacts must come in the order of this step's heights (top first, ties
// by index): the lane batches keep that order for contacts that share a body.
TEST(SolveOrder, ABodysContactsFollowThisStepsHeightsWhenTheGraphStaysTheSame) {
  WorldSettings ws;
  ws.iterations = 10;
  World w(ws);
  addGround(w);
  const float tilt = 0.1f;  // rad/s about z: the stack at x = -2 sinks, the one at +2 rises
  addKinematicBox(w, Vec3(0.0f, 1.0f, 0.0f), Vec3(4.0f, 0.25f, 2.0f), Vec3::Zero(), Vec3(0.0f, 0.0f, tilt));
  for (const float x : {-2.0f, 2.0f})
    for (int h = 0; h < 3; ++h) addBox(w, Vec3(x, 1.75f + float(h), 0.0f), Vec3::Constant(0.5f), 1.0f);
  addBox(w, Vec3(0.0f, 4.5f, 0.0f), Vec3(3.0f, 0.25f, 0.5f), 1.0f);
  const Vec3 up = Vec3::UnitY();  // against gravity, as the solve order reads it
  int crossed = 0;
  std::vector<uint64_t> lastKey(w.bodyCount(), 0);
  std::vector<uint32_t> lastFirst(w.bodyCount(), ~0u);
  uint32_t contactsBefore = 0;
  for (int step = 0; step < 60; ++step) {
    std::vector<Vec3> at(w.bodyCount());  // where the order was made: at the step's start
    for (uint32_t b = 0; b < w.bodyCount(); ++b) at[b] = w.bodies().xf[b].p;
    w.step();
    const IslandSet& is = w.islands();
    if (step > 10) {
      EXPECT_EQ(w.lastStats().contacts, contactsBefore) << "step " << step << ": the graph changed";
    }
    contactsBefore = w.lastStats().contacts;
    std::vector<uint64_t> seen(w.bodyCount(), 0);
    std::vector<bool> any(w.bodyCount(), false);
    std::vector<uint32_t> first(w.bodyCount(), ~0u);
    for (const Island& isl : is.islands)
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        const uint32_t ci = is.contacts[isl.firstContact + j];
        const Contact& c = w.contacts()[ci];
        const uint64_t key = descendingKey(up.dot(at[c.a] + at[c.b]), ci);
        for (const uint32_t b : {c.a, c.b}) {
          if (!w.bodies().isAwakeDynamic(b)) continue;
          EXPECT_TRUE(!any[b] || seen[b] < key) << "step " << step << ": body " << b << "'s contact " << ci
                                                << " comes after one that is lower";
          if (!any[b]) first[b] = ci;
          any[b] = true;
          seen[b] = key;
        }
      }
    for (uint32_t b = 0; b < w.bodyCount(); ++b)
      if (lastFirst[b] != ~0u && first[b] != lastFirst[b]) ++crossed;
    lastFirst = first;
  }
  EXPECT_GT(crossed, 0) << "no body's contacts changed places: the scene does not test the kept order";
}

}  // namespace
}  // namespace haif
