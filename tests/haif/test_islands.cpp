// Island formation: connected components of awake dynamic bodies; statics never join or merge islands.
#include "haif/tsan_pool.h"
#include "haif/world.h"

#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

namespace haif {
namespace {

using test::addBox;
using test::addGround;

std::vector<uint32_t> addStack(World& w, float x, float z, int n) { return test::addColumn(w, n, x, z, 1.005f); }

// Every awake dynamic body is in exactly one island, islandOf agrees, and islands are largest first.
void checkPartition(const World& w) {
  const IslandSet& is = w.islands();
  std::map<uint32_t, int> seen;
  for (uint32_t k = 0; k < is.islands.size(); ++k) {
    const Island& isl = is.islands[k];
    for (uint32_t j = 0; j < isl.bodyCount; ++j) {
      const uint32_t b = is.bodies[isl.firstBody + j];
      EXPECT_EQ(seen.count(b), 0u) << "body " << b << " in two islands";
      seen[b] = int(k);
      EXPECT_EQ(w.islandOf(b), int32_t(k));
    }
    if (k > 0) {
      EXPECT_GE(is.islands[k - 1].rows, isl.rows) << "islands not ordered largest first";
    }
  }
  for (uint32_t i = 0; i < w.bodyCount(); ++i) {
    const bool awakeDynamic = w.bodies().isDynamic(i) && !w.bodies().asleep[i];
    EXPECT_EQ(seen.count(i), awakeDynamic ? 1u : 0u) << "body " << i;
    if (!awakeDynamic) {
      EXPECT_EQ(w.islandOf(i), -1) << "static/sleeping body " << i << " in an island";
    }
  }
  // Contacts of an island touch only that island's bodies (or statics).
  for (uint32_t k = 0; k < is.islands.size(); ++k) {
    const Island& isl = is.islands[k];
    for (uint32_t j = 0; j < isl.contactCount; ++j) {
      const Contact& c = w.contacts()[is.contacts[isl.firstContact + j]];
      for (uint32_t b : {c.a, c.b}) {
        if (w.bodies().isDynamic(b)) {
          EXPECT_EQ(w.islandOf(b), int32_t(k));
        }
      }
    }
  }
}

// The step's contact counts and the islands' contact lists agree with the contacts themselves.
void checkContacts(const World& w) {
  uint32_t touching = 0, points = 0;
  for (const Contact& c : w.contacts()) {
    if (!c.touching()) continue;
    ++touching;
    points += uint32_t(c.manifold.count);
  }
  EXPECT_EQ(w.lastStats().contacts, touching);
  EXPECT_EQ(w.lastStats().contactPoints, points);
  std::set<uint32_t> listed;
  for (uint32_t ci : w.islands().contacts) {
    ASSERT_LT(ci, w.contacts().size());
    EXPECT_TRUE(listed.insert(ci).second) << "contact " << ci << " listed twice";
    EXPECT_TRUE(w.contacts()[ci].touching()) << "contact " << ci << " listed without points";
  }
}

TEST(Islands, TwoStacksOnSharedGroundAreTwoIslands) {
  World w;
  const uint32_t ground = addGround(w);
  const auto a = addStack(w, 0.0f, 0.0f, 4);
  const auto b = addStack(w, 5.0f, 0.0f, 4);
  for (int s = 0; s < 3; ++s) w.step();
  ASSERT_EQ(w.islands().islands.size(), 2u) << "the static ground must not merge the stacks";
  EXPECT_EQ(w.islandOf(ground), -1);
  for (uint32_t i : a) EXPECT_EQ(w.islandOf(i), w.islandOf(a[0]));
  for (uint32_t i : b) EXPECT_EQ(w.islandOf(i), w.islandOf(b[0]));
  EXPECT_NE(w.islandOf(a[0]), w.islandOf(b[0]));
  EXPECT_EQ(w.lastStats().islands, 2u);
  EXPECT_EQ(w.lastStats().largestIsland, 4u);
  checkPartition(w);
  checkContacts(w);
}

TEST(Islands, ChainOfTouchingBoxesIsOneIsland) {
  World w;
  addGround(w);
  std::vector<uint32_t> chain;
  for (int i = 0; i < 8; ++i) chain.push_back(addBox(w, Vec3(1.0f * float(i), 0.5f, 0.0f)));  // faces touch
  for (int s = 0; s < 3; ++s) w.step();
  ASSERT_EQ(w.islands().islands.size(), 1u);
  EXPECT_EQ(w.islands().islands[0].bodyCount, 8u);
  checkPartition(w);
  checkContacts(w);
}

TEST(Islands, LargestFirstAndLoneBodiesCounted) {
  World w;
  addGround(w);
  const auto small = addStack(w, 0.0f, 0.0f, 2);
  const auto big = addStack(w, 4.0f, 0.0f, 6);
  const auto mid = addStack(w, 8.0f, 0.0f, 3);
  const uint32_t flying = addBox(w, Vec3(20.0f, 30.0f, 0.0f));  // touches nothing
  w.step();
  const IslandSet& is = w.islands();
  ASSERT_EQ(is.islands.size(), 4u);
  EXPECT_EQ(w.islandOf(big[0]), 0);
  EXPECT_EQ(w.islandOf(mid[0]), 1);
  EXPECT_EQ(w.islandOf(small[0]), 2);
  EXPECT_EQ(w.islandOf(flying), 3);
  EXPECT_EQ(is.islands[3].rows, 0u);
  EXPECT_EQ(is.largestBodies, 6u);
  EXPECT_EQ(is.largestRows, is.islands[0].rows);
  uint32_t total = 0;
  for (const Island& isl : is.islands) total += isl.rows;
  EXPECT_EQ(is.totalRows, total);
  checkPartition(w);
  checkContacts(w);
}

TEST(Islands, BoxBridgingTwoStacksMergesThem) {
  // A dynamic plank lying across two stacks joins them into one island (dynamic bodies do merge).
  World w;
  addGround(w);
  addStack(w, 0.0f, 0.0f, 2);
  addStack(w, 3.0f, 0.0f, 2);
  BodyDef plank;
  plank.shape = Shape::box(Vec3(2.0f, 0.25f, 0.5f));
  plank.xf.p = Vec3(1.5f, 2.0f + 0.01f + 0.25f, 0.0f);
  plank.mass = 1.0f;
  w.addBody(plank);
  for (int s = 0; s < 5; ++s) w.step();
  EXPECT_EQ(w.islands().islands.size(), 1u);
  checkPartition(w);
  checkContacts(w);
}

TEST(Islands, ContactsDestroyedDuringARunLeaveIslandsAndCountsRight) {
  // A box thrown up out of a row: its contacts part, then are destroyed (the last contact moves
  // into the freed slot), and the row falls apart into two islands. Every step the islands must
  // match the contacts as they now are.
  World w;
  addGround(w);
  std::vector<uint32_t> row;
  for (int i = 0; i < 6; ++i) row.push_back(addBox(w, Vec3(1.0f * float(i), 0.5f, 0.0f)));
  for (int s = 0; s < 3; ++s) w.step();
  ASSERT_EQ(w.islands().islands.size(), 1u);
  const size_t before = w.contacts().size();
  w.bodies().v[row[2]] = Vec3(0.0f, 12.0f, 0.0f);
  for (int s = 0; s < 30; ++s) {
    w.step();
    checkPartition(w);
    checkContacts(w);
  }
  EXPECT_LT(w.contacts().size(), before) << "the thrown box's contacts were never destroyed";
  ASSERT_EQ(w.islands().islands.size(), 3u);  // {0, 1}, {3, 4, 5} and the box in the air
  EXPECT_EQ(w.islandOf(row[0]), w.islandOf(row[1]));
  EXPECT_EQ(w.islandOf(row[3]), w.islandOf(row[5]));
  EXPECT_NE(w.islandOf(row[0]), w.islandOf(row[3]));
  EXPECT_NE(w.islandOf(row[2]), w.islandOf(row[0]));
}

// A graph for the island builder: n bodies (one in 50 static, one in 50 kinematic and, with
// `sleepers`, one in 50 asleep) and m edges, mostly short (chains and clusters of every size), some
// long ones merging them, one in `emptyOneIn` without points (they join nothing).
struct RandomGraph {
  BodyStore bodies;
  std::vector<ContactEdge> edges;
};
RandomGraph randomGraph(std::mt19937& rng, uint32_t n, size_t m, bool sleepers, uint32_t emptyOneIn) {
  RandomGraph g;
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t r = rng() % 50;
    g.bodies.add(r == 0 ? BodyKind::Static : r == 1 ? BodyKind::Kinematic : BodyKind::Dynamic, Transform{}, 1.0f,
                 Mat3::Identity());
    if (sleepers && r == 2) g.bodies.asleep[i] = 1;
  }
  g.edges.resize(m);
  for (ContactEdge& e : g.edges) {
    e.a = uint32_t(rng() % n);
    e.b = rng() % 8 == 0 ? uint32_t(rng() % n) : std::min(n - 1, e.a + 1 + uint32_t(rng() % 3));
    e.count = uint8_t(rng() % emptyOneIn == 0 ? 0 : 1 + rng() % 4);
  }
  return g;
}

// The unions run concurrently on a pool's threads: the islands (their members, numbering, order and
// contact lists) are those of the build on one thread, and they are the graph's components.
TEST(IslandBuilder, ConcurrentUnionsGiveTheSameIslandsAtEveryThreadCount) {
  std::mt19937 rng(7);
  const uint32_t n = 30000;
  RandomGraph graph = randomGraph(rng, n, 60000, /*sleepers=*/true, /*emptyOneIn=*/10);
  const BodyStore& bodies = graph.bodies;
  const std::vector<ContactEdge>& edges = graph.edges;
  std::vector<Joint> joints;
  IslandBuilder one;
  IslandSet expected;
  one.build(bodies, edges.data(), uint32_t(edges.size()), joints, expected);

  // The components by a search over the same edges.
  std::vector<std::vector<uint32_t>> adjacent(n);
  for (const ContactEdge& e : edges)
    if (e.count > 0 && bodies.isAwakeDynamic(e.a) && bodies.isAwakeDynamic(e.b)) {
      adjacent[e.a].push_back(e.b);
      adjacent[e.b].push_back(e.a);
    }
  std::vector<int32_t> component(n, -1);
  int32_t components = 0;
  for (uint32_t i = 0; i < n; ++i) {
    if (!bodies.isAwakeDynamic(i) || component[i] >= 0) continue;
    std::vector<uint32_t> stack{i};
    component[i] = components;
    while (!stack.empty()) {
      const uint32_t b = stack.back();
      stack.pop_back();
      for (uint32_t c : adjacent[b])
        if (component[c] < 0) {
          component[c] = components;
          stack.push_back(c);
        }
    }
    ++components;
  }
  ASSERT_EQ(expected.islands.size(), size_t(components));
  std::set<int32_t> seen;
  for (const Island& isl : expected.islands) {
    const int32_t c = component[expected.bodies[isl.firstBody]];
    EXPECT_TRUE(seen.insert(c).second) << "component " << c << " in two islands";
    for (uint32_t j = 0; j < isl.bodyCount; ++j) EXPECT_EQ(component[expected.bodies[isl.firstBody + j]], c);
  }

  for (int threads : {2, 4, 8}) {
    TsanPool pool(threads);
    for (int round = 0; round < 3; ++round) {
      IslandBuilder many;
      IslandSet out;
      // Round 0 runs the ranges one at a time, last first: any order is allowed, so none may matter.
      many.build(bodies, edges.data(), uint32_t(edges.size()), joints, out,
                 [&](uint32_t count, uint32_t grain, auto&& f) {
                   if (round > 0) return pool.run(count, std::max(1u, grain / 16), f);
                   for (uint32_t i = count; i-- > 0;) f(i, i + 1);
                 });
      ASSERT_EQ(out.islands.size(), expected.islands.size()) << threads << " threads";
      for (size_t k = 0; k < out.islands.size(); ++k) {
        const Island &x = out.islands[k], &y = expected.islands[k];
        EXPECT_TRUE(x.firstBody == y.firstBody && x.bodyCount == y.bodyCount && x.firstContact == y.firstContact &&
                    x.contactCount == y.contactCount && x.rows == y.rows)
            << "island " << k << ", " << threads << " threads";
      }
      EXPECT_EQ(out.bodies, expected.bodies) << threads << " threads";
      EXPECT_EQ(out.contacts, expected.contacts) << threads << " threads";
      EXPECT_EQ(out.touchingContacts, expected.touchingContacts);
      EXPECT_EQ(out.contactPoints, expected.contactPoints);
    }
  }
}

// Two builds' islands, member for member.
void expectSameIslands(const IslandSet& got, const IslandSet& want, const char* what) {
  ASSERT_EQ(got.islands.size(), want.islands.size()) << what;
  for (size_t k = 0; k < want.islands.size(); ++k) {
    const Island &g = got.islands[k], &e = want.islands[k];
    EXPECT_EQ(g.firstBody, e.firstBody) << what << ", island " << k;
    EXPECT_EQ(g.bodyCount, e.bodyCount) << what << ", island " << k;
    EXPECT_EQ(g.firstContact, e.firstContact) << what << ", island " << k;
    EXPECT_EQ(g.contactCount, e.contactCount) << what << ", island " << k;
    EXPECT_EQ(g.rows, e.rows) << what << ", island " << k;
    EXPECT_EQ(g.firstJoint, e.firstJoint) << what << ", island " << k;
    EXPECT_EQ(g.jointCount, e.jointCount) << what << ", island " << k;
    EXPECT_EQ(g.carrier, e.carrier) << what << ", island " << k;
    EXPECT_EQ(g.carrierV, e.carrierV) << what << ", island " << k;
    EXPECT_EQ(g.carrierW, e.carrierW) << what << ", island " << k;
    EXPECT_EQ(g.carrierAt, e.carrierAt) << what << ", island " << k;
  }
  EXPECT_EQ(got.bodies, want.bodies) << what;
  EXPECT_EQ(got.contacts, want.contacts) << what;
  EXPECT_EQ(got.joints, want.joints) << what;
  EXPECT_EQ(got.totalRows, want.totalRows) << what;
  EXPECT_EQ(got.largestRows, want.largestRows) << what;
  EXPECT_EQ(got.largestBodies, want.largestBodies) << what;
  EXPECT_EQ(got.touchingContacts, want.touchingContacts) << what;
  EXPECT_EQ(got.contactPoints, want.contactPoints) << what;
}

// A graph equal to the last build's gets the last build's islands again (the callers rearrange the
// contacts they were given: that must not leak back), with the carriers' motion read anew; any change
// a build reads (a point count, an apart flag, a body asleep or of another kind, a joint broken, a
// contact more) builds them afresh. Either way they are what a new builder makes of the same graph.
TEST(IslandBuilder, AnUnchangedGraphGetsTheLastIslandsAndAChangedOneIsBuiltAfresh) {
  std::mt19937 rng(11);
  const uint32_t n = 3000;
  RandomGraph graph = randomGraph(rng, n, 6000, /*sleepers=*/false, /*emptyOneIn=*/3);
  BodyStore& bodies = graph.bodies;
  std::vector<ContactEdge>& edges = graph.edges;
  std::vector<Joint> joints(40);
  for (Joint& j : joints) {
    j.def.type = rng() % 2 ? JointType::Ball : JointType::Hinge;
    j.def.bodyA = uint32_t(rng() % n);
    j.def.bodyB = uint32_t(rng() % n);
  }
  IslandBuilder kept;
  IslandSet out;
  auto expectFresh = [&](const char* what, bool reused) {
    // What the caller does with the islands between steps (the solve order sorts each island's contacts).
    std::reverse(out.contacts.begin(), out.contacts.end());
    kept.build(bodies, edges.data(), uint32_t(edges.size()), joints, out);
    EXPECT_EQ(kept.reused(), reused) << what;
    IslandBuilder fresh;
    IslandSet want;
    fresh.build(bodies, edges.data(), uint32_t(edges.size()), joints, want);
    EXPECT_FALSE(fresh.reused()) << what;
    expectSameIslands(out, want, what);
  };
  // Unchanged after a change: a changed contact leaves the keys stale, written at the next build (not
  // reused) and the one after reuses; a changed body or joint, or a new count of contacts, is kept at once.
  auto settle = [&](const char* what, bool keysStale) {
    expectFresh(what, !keysStale);
    if (keysStale) expectFresh(what, true);
  };
  kept.build(bodies, edges.data(), uint32_t(edges.size()), joints, out);
  EXPECT_FALSE(kept.reused()) << "a first build has nothing to reuse";
  expectFresh("the same graph", true);
  uint32_t carrier = 0;
  for (const Island& isl : out.islands)
    if (isl.carrier != Island::kNoCarrier) carrier = isl.carrier;
  ASSERT_EQ(bodies.kind[carrier], BodyKind::Kinematic) << "the graph has an island on a kinematic body";
  bodies.v[carrier] = Vec3(1.0f, 2.0f, 3.0f);
  bodies.w[carrier] = Vec3(0.0f, 0.5f, 0.0f);
  bodies.xf[carrier].p = Vec3(4.0f, 5.0f, 6.0f);
  expectFresh("a carrier moving", true);

  auto touchingDynamicEdge = [&](bool touching) {
    for (uint32_t ci = 0;; ++ci)
      if ((edges[ci].count > 0) == touching && bodies.isAwakeDynamic(edges[ci].a) && bodies.isAwakeDynamic(edges[ci].b) &&
          edges[ci].a != edges[ci].b)
        return ci;
  };
  edges[touchingDynamicEdge(false)].count = 1;
  expectFresh("a contact made", false);
  expectFresh("unchanged after a contact made: its keys written again", false);
  expectFresh("unchanged after a contact made", true);
  const uint32_t pressed = touchingDynamicEdge(true);
  edges[pressed].count = uint8_t(edges[pressed].count % 4 + 1);
  expectFresh("a point more or fewer", false);
  settle("unchanged after a point more or fewer", true);
  edges[touchingDynamicEdge(true)].apart = true;
  expectFresh("a contact apart", false);
  settle("unchanged after a contact apart", true);
  bodies.asleep[edges[touchingDynamicEdge(true)].a] = 1;
  expectFresh("a body asleep", false);
  settle("unchanged after a body asleep", false);
  bodies.kind[edges[touchingDynamicEdge(true)].b] = BodyKind::Kinematic;
  expectFresh("a body made kinematic", false);
  settle("unchanged after a body made kinematic", false);
  for (Joint& j : joints)
    if (!j.broken && bodies.isAwakeDynamic(j.def.bodyA)) {
      j.broken = true;
      break;
    }
  expectFresh("a joint broken", false);
  settle("unchanged after a joint broken", false);
  joints[0].def.type = joints[0].def.type == JointType::Ball ? JointType::Hinge : JointType::Ball;
  expectFresh("a joint of another type (other rows)", false);
  settle("unchanged after a joint of another type (other rows)", false);
  edges.push_back(ContactEdge{});
  edges.back().a = edges[pressed].a;
  edges.back().b = uint32_t(rng() % n);
  edges.back().count = 2;
  expectFresh("a contact more", false);
  settle("unchanged after a contact more", false);  // a new count of contacts: all keys written at once
}

}  // namespace
}  // namespace haif
