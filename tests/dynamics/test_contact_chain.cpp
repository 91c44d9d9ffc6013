// A chain of contacts (a stack) has its normal rows solved exactly in one sweep: the result must be
// the complementarity solution (every row pushes only where it touches), which plain sweeps only
// approach one contact at a time.
#include "dynamics/contact_chain.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace haif {
namespace {

// Unit cubes (mass 1) on a static ground (body 0), given by their centres, and hand-made face
// contacts between them: no gravity, friction off, so the normal rows alone decide.
struct Pile {
  BodyStore bodies;
  std::vector<Contact> contacts;
  std::vector<ContactConstraint> rows;

  Pile() { bodies.add(BodyKind::Static, Transform{}, 0.0f, Mat3::Zero()); }
  uint32_t box(float x, float y, float vy = 0.0f, float mass = 1.0f) {
    Transform t;
    t.p = Vec3(x, y, 0.0f);
    const uint32_t id = bodies.add(BodyKind::Dynamic, t, mass, Mat3::Identity() * (mass / 6.0f));
    bodies.v[id] = Vec3(0.0f, vy, 0.0f);
    return id;
  }
  // Body `upper` rests on `lower` over the square of half size 0.5 around (x, y, 0).
  void touch(uint32_t lower, uint32_t upper, float x, float y, float impulse = 0.0f) {
    Contact c;
    c.a = lower;
    c.b = upper;
    c.friction = 0.0f;
    const float corners[4][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
    c.manifold.count = 4;
    for (int i = 0; i < 4; ++i) {
      ContactPoint& p = c.manifold.points[i];
      p.position = Vec3(x + corners[i][0], y, corners[i][1]);
      p.normal = Vec3::UnitY();
      p.depth = 0.0f;
      p.id = uint32_t(i);
      c.normalImpulse[i] = impulse;
    }
    contacts.push_back(c);
  }
  // Rows in the given (solve) order of contacts; true when they form a chain.
  bool prepare(std::vector<ChainLink>& links) {
    SolverParams sp;
    rows.resize(contacts.size());
    for (size_t k = 0; k < contacts.size(); ++k) prepareContact(bodies, contacts[k], uint32_t(k), sp, rows[k]);
    links.resize(rows.size());
    std::vector<uint32_t> mark(bodies.size());
    return prepareChain(contacts.data(), rows.data(), uint32_t(rows.size()), mark.data(), links.data());
  }
  // The same rows for the dense solve of a small island; true when it takes them.
  bool prepareSmall(std::vector<ChainLink>& links) {
    SolverParams sp;
    rows.resize(contacts.size());
    for (size_t k = 0; k < contacts.size(); ++k) prepareContact(bodies, contacts[k], uint32_t(k), sp, rows[k]);
    links.resize(rows.size());
    return prepareSmallIsland(contacts.data(), rows.data(), uint32_t(rows.size()), links.data());
  }
  float total(size_t k) const {
    float sum = 0.0f;
    for (int i = 0; i < rows[k].count; ++i) sum += rows[k].normalImpulse[i];
    return sum;
  }
  float fastest() const {
    float v = 0.0f;
    for (uint32_t b = 1; b < bodies.size(); ++b) v = std::max({v, bodies.v[b].norm(), bodies.w[b].norm()});
    return v;
  }
  float gap(const ContactConstraint& c, int i) const {
    return rowVelocity(c, i, bodies.v[c.a], bodies.w[c.a], bodies.v[c.b], bodies.w[c.b]) + c.bias[i];
  }
  // The solution of the normal problem: no row approaches, no row pulls, and a row pushes only
  // where it does not separate.
  void expectComplementary() const {
    for (size_t k = 0; k < rows.size(); ++k)
      for (int i = 0; i < rows[k].count; ++i) {
        const float g = gap(rows[k], i), l = rows[k].normalImpulse[i];
        EXPECT_GE(g, -1e-4f) << "contact " << k << " point " << i << " approaches";
        EXPECT_GE(l, 0.0f) << "contact " << k << " point " << i << " pulls";
        EXPECT_LT(std::fabs(g * l), 1e-4f) << "contact " << k << " point " << i << " pushes while separating";
      }
  }
};

// Five boxes on the ground, contacts listed top down (the solve order), the top one falling at vTop.
Pile column(int boxes, float vTop) {
  Pile s;
  uint32_t below = 0;
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (int h = 0; h < boxes; ++h) {
    const uint32_t b = s.box(0.0f, 0.5f + float(h), h + 1 == boxes ? vTop : 0.0f);
    pairs.push_back({below, b});
    below = b;
  }
  for (int h = boxes; h-- > 0;) s.touch(pairs[h].first, pairs[h].second, 0.0f, float(h));
  return s;
}

TEST(ContactChain, AStackIsAChain) {
  Pile s = column(5, 0.0f);
  std::vector<ChainLink> links;
  EXPECT_TRUE(s.prepare(links));
  for (const ChainLink& l : links) EXPECT_EQ(l.rank, 3);
  for (size_t j = 0; j + 1 < links.size(); ++j) EXPECT_TRUE(links[j].coupledToNext()) << "link " << j;
  EXPECT_FALSE(links.back().coupledToNext());  // the ground contact: the ground is static
}

TEST(ContactChain, ABoxOnTwoBoxesIsNot) {
  // The top box touches two boxes that both stand on the ground: a loop, not a chain.
  Pile s;
  const uint32_t left = s.box(-0.5f, 0.5f), right = s.box(0.5f, 0.5f), top = s.box(0.0f, 1.5f);
  s.touch(left, top, -0.25f, 1.0f);
  s.touch(right, top, 0.25f, 1.0f);
  s.touch(0, left, -0.5f, 0.0f);
  s.touch(0, right, 0.5f, 0.0f);
  std::vector<ChainLink> links;
  EXPECT_FALSE(s.prepare(links));
}

TEST(ContactChain, AColumnHeldAtBothEndsIsNot) {
  // Two boxes between the ground and a static ceiling: the exact solve of rows pushing from both
  // ends along one line is singular (a hull a swept pit's bar had run over took 2e8 N s in one step).
  Pile s = column(2, 0.0f);
  const uint32_t ceiling = s.bodies.add(BodyKind::Static, Transform{}, 0.0f, Mat3::Zero());
  s.touch(2, ceiling, 0.0f, 2.0f);
  for (ContactPoint& p : s.contacts.back().manifold.points) p.normal = -Vec3::UnitY();  // into the top box
  std::swap(s.contacts.back().a, s.contacts.back().b);
  std::rotate(s.contacts.begin(), s.contacts.end() - 1, s.contacts.end());  // top down: ceiling first
  std::vector<ChainLink> links;
  EXPECT_FALSE(s.prepare(links));
  s.contacts.erase(s.contacts.begin());  // without the ceiling it is a chain again
  EXPECT_TRUE(s.prepare(links));
}

TEST(ContactChain, OneSweepStopsALandingOnAStack) {
  Pile s = column(5, -2.0f);
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepare(links));
  solveChainIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true);
  s.expectComplementary();
  // Inelastic contacts on a static ground: everything stops, and every contact passes the top
  // box's momentum (2 N s) on to the one below.
  for (uint32_t b = 1; b < s.bodies.size(); ++b) {
    EXPECT_NEAR(s.bodies.v[b].norm(), 0.0f, 1e-4f) << "box " << b;
    EXPECT_NEAR(s.bodies.w[b].norm(), 0.0f, 1e-4f) << "box " << b;
  }
  for (size_t k = 0; k < s.rows.size(); ++k) {
    float total = 0.0f;
    for (int i = 0; i < 4; ++i) total += s.rows[k].normalImpulse[i];
    EXPECT_NEAR(total, 2.0f, 1e-4f) << "contact " << k;
  }
}

TEST(ContactChain, SweepsAloneLeaveTheLandingMoving) {
  // Why the chain solve exists: one sweep contact by contact only shares the momentum along.
  Pile s = column(5, -2.0f);
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepare(links));
  solveIteration(s.bodies, s.rows.data(), s.rows.size(), 1.0f, true);
  float fastest = 0.0f;
  for (uint32_t b = 1; b < s.bodies.size(); ++b) fastest = std::max(fastest, s.bodies.v[b].norm());
  EXPECT_GT(fastest, 0.1f);
}

TEST(ContactChain, LetsGoOfAContactThatSeparates) {
  // Box 2 flies up off box 1, which falls onto the ground; contact 1-2 still holds a warm-start
  // impulse that it must give back, since it cannot pull.
  Pile s;
  const uint32_t b1 = s.box(0.0f, 0.5f, -1.0f), b2 = s.box(0.0f, 1.5f, 1.0f);
  s.touch(b1, b2, 0.0f, 1.0f, 0.1f);
  s.touch(0, b1, 0.0f, 0.0f);
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepare(links));
  solveChainIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true);
  s.expectComplementary();
  for (int i = 0; i < 4; ++i) EXPECT_EQ(s.rows[0].normalImpulse[i], 0.0f);
  EXPECT_NEAR(s.bodies.v[b2].y(), 0.6f, 1e-4f);  // 1 m/s less the 0.4 N s it was pushed with
  EXPECT_NEAR(s.bodies.v[b1].y(), 0.0f, 1e-4f);  // stopped by the ground
}

TEST(ContactChain, TiltedLandingSettlesOnAnEdgeInOneSweep) {
  // The top box lands spinning about a horizontal axis: one edge of every contact lifts. Those
  // points let go and the links are solved on the basis of the edge that stays (rank 2).
  Pile s = column(4, -1.0f);
  s.bodies.w[4] = Vec3(3.0f, 0.0f, 0.0f);
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepare(links));
  solveChainIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true);
  s.expectComplementary();
  int lifted = 0;
  for (const ContactConstraint& c : s.rows)
    for (int i = 0; i < c.count; ++i) lifted += c.normalImpulse[i] < 1e-5f;
  EXPECT_EQ(lifted, 8) << "two points of each of the four contacts carry nothing";
  // Where 20 plain sweeps still leave rows approaching.
  Pile p = column(4, -1.0f);
  p.bodies.w[4] = Vec3(3.0f, 0.0f, 0.0f);
  ASSERT_TRUE(p.prepare(links));
  float worst = 0.0f;
  for (int sweep = 0; sweep < 20; ++sweep) solveIteration(p.bodies, p.rows.data(), p.rows.size(), 1.0f, true);
  for (const ContactConstraint& c : p.rows)
    for (int i = 0; i < c.count; ++i) worst = std::min(worst, p.gap(c, i));
  EXPECT_LT(worst, -1e-3f);
}

// A 10-box column dropped onto itself through 1 cm gaps, as in stacks_N.
struct LandingRun {
  double meanError = 0.0, maxError = 0.0;
  float deepest = 0.0f;
};

LandingRun landColumn(int iterations, bool chain) {
  LandingRun r;
  const int steps = 60;
  test::stepGappedColumn(iterations, chain, steps, [&](const World& w, int s) {
    r.meanError += w.lastStats().solveError / steps;
    r.maxError = std::max(r.maxError, w.lastStats().solveError);
    if (s >= 30) r.deepest = std::max(r.deepest, test::maxContactDepth(w));
  });
  return r;
}

TEST(ContactChain, ColumnLandsWithoutSolveErrorAtTwoIterations) {
  const LandingRun chain = landColumn(2, true), sweeps = landColumn(2, false);
  EXPECT_LT(chain.maxError, 1e-3) << "mean " << chain.meanError;
  EXPECT_GT(sweeps.meanError, 0.1) << "2 sweeps alone should not settle the landing";
  // And it rests: within the slop once landed.
  EXPECT_LT(chain.deepest, 0.005f + 1e-3f);
}

TEST(ContactChain, HeavySpheresLandingOnASmallSpinningBoxStaySane) {
  // From the stress pile (pile_10000, steps 22-25): a 107 kg ball lands on a spinning 8 kg box and a
  // 97 kg ball on it. The box is squeezed between the ground and a ball: large normal impulses, and
  // friction from both sides turns the box between sweeps, so a loaded link separates a little at
  // the start of a sweep. Letting go of all of its impulse there (as the chain once did) threw the
  // box out at 1700 m/s within three steps; nothing may speed up past the 3.6 m/s of the fall.
  WorldSettings ws;
  ws.iterations = 10;
  World w(ws);
  test::addGround(w);
  const uint32_t box = test::addBox(w, Vec3(-0.5348f, 0.12905f, -3.9304f), Vec3(0.09403f, 0.10452f, 0.10157f), 7.986f,
                                    Quat(0.44689f, -0.59922f, -0.41733f, -0.51677f).normalized());
  const uint32_t low = test::addSphere(w, Vec3(-0.55608f, 0.58514f, -3.86054f), 0.29417f, 106.63f);
  const uint32_t high = test::addSphere(w, Vec3(-0.53877f, 1.24238f, -3.83894f), 0.28470f, 96.66f);
  w.bodies().v[box] = Vec3(-0.89217f, -0.23894f, -0.22658f);
  w.bodies().w[box] = Vec3(-1.46002f, 0.00936f, 6.81329f);
  w.bodies().v[low] = w.bodies().v[high] = Vec3(0.0f, -3.597f, 0.0f);
  const double energy = w.kineticEnergy() + w.potentialEnergy();
  float peak = 0.0f;
  for (int s = 0; s < 120; ++s) {
    w.step();
    for (uint32_t b : {box, low, high}) peak = std::max(peak, w.bodies().v[b].norm());
    ASSERT_LE(w.kineticEnergy() + w.potentialEnergy(), energy * 1.001) << "step " << s;
  }
  EXPECT_LT(peak, 4.0f);
}

// Plates 1 m wide and 2 cm thick (20 kg), 2 mm apart, stacked on the ground at x: the 2 cm
// speculative margin reaches past each plate to the one below it. Returns the ids, bottom first.
constexpr float kPlateHalf = 0.01f, kPlatePitch = 2.0f * kPlateHalf + 0.002f;
std::vector<uint32_t> addPlateStack(World& w, int plates, float x) {
  std::vector<uint32_t> ids;
  for (int i = 0; i < plates; ++i)
    ids.push_back(
        test::addBox(w, Vec3(x, kPlateHalf + kPlatePitch * float(i), 0.0f), Vec3(0.5f, kPlateHalf, 0.5f), 20.0f));
  return ids;
}

// The state hash of eight stacks made by addStack(w, s), 120 steps at 4 iterations, on `threads`.
template <class AddStack>
uint64_t eightStacksAtFourIterations(int threads, AddStack addStack) {
  WorldSettings ws;
  ws.threads = threads;
  ws.iterations = 4;
  World w(ws);
  test::addGround(w);
  for (int s = 0; s < 8; ++s) addStack(w, s);
  for (int s = 0; s < 120; ++s) w.step();
  return w.stateHash();
}

TEST(ContactChain, ThinPlatesWhoseMarginReachesPastAPlateStillStackAsAChain) {
  // 30 plates: the island has more contacts than bodies and was swept, not solved as a chain. At
  // 4 iterations (3 sweeps and a relax) it sank into itself (plates 0.45 m into each other) and
  // sprang back for the whole minute. Those contacts now follow the chain
  // (World::moveOutOfReachToTail). The case needs the full 2 cm margin: scaled to these 2 cm plates
  // (haif/small_bodies.h) it no longer reaches past a plate, and the stack is a plain chain.
  for (const float toleranceThickness : {0.0f, WorldSettings{}.toleranceThickness}) {
    WorldSettings ws;
    ws.iterations = 4;
    ws.toleranceThickness = toleranceThickness;
    World w(ws);
    test::addGround(w);
    const int plates = 30;
    const std::vector<uint32_t> ids = addPlateStack(w, plates, 0.0f);
    w.step();
    int pastAPlate = 0;
    for (const Contact& c : w.contacts())
      if (c.touching() && std::max(c.a, c.b) - std::min(c.a, c.b) >= 2) ++pastAPlate;
    if (toleranceThickness == 0.0f) ASSERT_GT(pastAPlate, 0) << "the case needs contacts that reach past a plate";
    else EXPECT_EQ(pastAPlate, 0);
    for (int s = 1; s < 600; ++s) w.step();
    EXPECT_LT(w.kineticEnergy(), 1e-3);
    for (int i = 0; i < plates; ++i) {
      const Vec3 p = w.bodies().xf[ids[size_t(i)]].p;
      EXPECT_LT(std::hypot(p.x(), p.z()), 1e-3f) << "plate " << i;
      // Resting on the one below: the gaps closed, no plate sunk into another beyond the slop.
      EXPECT_NEAR(p.y(), kPlateHalf + 2.0f * kPlateHalf * float(i), 0.005f + 1e-3f) << "plate " << i;
    }
  }
}

TEST(ContactChain, PlatesThinnerThanTheSlopStackAsAChainAtFourIterations) {
  // Ten 1 kg plates 4 mm thick, touching, on the ground. The ground's contact with the second plate,
  // 4 mm below it through the first, is in the margin on the first step (the fall adds to it); by the
  // unscaled 5 mm slop it was in reach, the island no chain, and swept at 4 iterations the stack sank
  // half a plate into itself over its first steps. The reach now takes the contact's scaled slop.
  WorldSettings ws;
  ws.iterations = 4;
  World w(ws);
  test::addGround(w);
  const float half = 0.002f;
  std::vector<uint32_t> ids;
  for (int i = 0; i < 10; ++i)
    ids.push_back(test::addBox(w, Vec3(0.0f, half + 2.0f * half * float(i), 0.0f), Vec3(0.5f, half, 0.5f), 1.0f));
  float deepest = 0.0f;
  for (int s = 0; s < 120; ++s) {
    w.step();
    for (const Contact& c : w.contacts()) deepest = std::max(deepest, c.manifold.deepest());
  }
  EXPECT_LT(deepest, 0.0005f);  // an eighth of a plate (the scaled slop is 0.4 mm)
  for (int i = 0; i < 10; ++i)
    EXPECT_NEAR(w.bodies().xf[ids[size_t(i)]].p.y(), half + 2.0f * half * float(i), 0.0005f) << "plate " << i;
}

TEST(ContactChain, ThinPlateStacksHaveOneStateAtAnyThreadCount) {
  // Islands with a tail of contacts out of reach, ordered and solved concurrently.
  test::expectSameStateForThreadCounts([](int threads) {
    return eightStacksAtFourIterations(threads, [](World& w, int s) { addPlateStack(w, 12, 2.0f * float(s)); });
  });
}

TEST(ContactChain, SameStateForAnyThreadCount) {
  test::expectSameStateForThreadCounts([](int threads) {
    return eightStacksAtFourIterations(
        threads, [](World& w, int s) { test::addColumn(w, 12, 3.0f * float(s), 0.0f, 1.01f); });
  });
}

// A small-island system with room for the most rows.
struct DenseStorage {
  std::vector<double> doubles = std::vector<double>(DenseNormalSystem::doublesFor(DenseNormalSystem::kMaxRows));
  DenseNormalSystem system;
  DenseStorage() { system.attach(doubles.data(), DenseNormalSystem::kMaxRows); }
};

// A box of mass `top` on two unit boxes standing on the ground, falling at vTop; contacts top down.
// The top's two face contacts can each carry it alone (rank 3 each): more normal rows than the
// bodies have ways to move.
Pile boxOnTwoBoxes(float top, float vTop) {
  Pile s;
  const uint32_t left = s.box(-0.5f, 0.5f), right = s.box(0.5f, 0.5f), upper = s.box(0.0f, 1.5f, vTop, top);
  s.touch(left, upper, -0.25f, 1.0f);
  s.touch(right, upper, 0.25f, 1.0f);
  s.touch(0, left, -0.5f, 0.0f);
  s.touch(0, right, 0.5f, 0.0f);
  return s;
}

TEST(SmallIsland, AHeavyBoxLandingOnTwoLightOnesStopsInOneSweep) {
  Pile s = boxOnTwoBoxes(10.0f, -2.0f);
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepareSmall(links));
  DenseStorage storage;
  DenseNormalSystem& system = storage.system;
  solveSmallIslandIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true, system);
  s.expectComplementary();
  EXPECT_LT(s.fastest(), 1e-4f);
  // The 20 N s of the landing go down both sides alike: of the impulses that stop it, the
  // least-squares solve takes the smallest, the even share.
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(s.total(k), 10.0f, 1e-3f) << "contact " << k;
  // Sweeps pass the landing through the light boxes a fraction at a time: 20 leave it moving.
  Pile p = boxOnTwoBoxes(10.0f, -2.0f);
  ASSERT_TRUE(p.prepareSmall(links));
  for (int sweep = 0; sweep < 20; ++sweep) solveIteration(p.bodies, p.rows.data(), p.rows.size(), 1.0f, true);
  EXPECT_GT(p.fastest(), 0.05f);
}

TEST(SmallIsland, AgreesWithTheChainSolveOnAColumn) {
  Pile chain = column(5, -2.0f), dense = column(5, -2.0f);
  dense.bodies.w[5] = chain.bodies.w[5] = Vec3(1.0f, 0.0f, 0.0f);  // a tilted landing: edges lift
  std::vector<ChainLink> chainLinks, denseLinks;
  ASSERT_TRUE(chain.prepare(chainLinks));
  ASSERT_TRUE(dense.prepareSmall(denseLinks));
  DenseStorage storage;
  DenseNormalSystem& system = storage.system;
  solveChainIteration(chain.bodies, chain.rows.data(), chainLinks.data(), uint32_t(chainLinks.size()), 1.0f, true);
  solveSmallIslandIteration(dense.bodies, dense.rows.data(), denseLinks.data(), uint32_t(denseLinks.size()), 1.0f,
                            true, system);
  dense.expectComplementary();
  for (size_t k = 0; k < chain.rows.size(); ++k)
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(dense.rows[k].normalImpulse[i], chain.rows[k].normalImpulse[i], 1e-3f) << k << "/" << i;
  for (uint32_t b = 1; b < chain.bodies.size(); ++b) {
    EXPECT_LT((dense.bodies.v[b] - chain.bodies.v[b]).norm(), 1e-4f) << "box " << b;
    EXPECT_LT((dense.bodies.w[b] - chain.bodies.w[b]).norm(), 1e-4f) << "box " << b;
  }
}

TEST(SmallIsland, RowsAskingForWhatNoMotionGivesDoNotFight) {
  // The left box is 2 cm into the ground on its left edge only, so push-out asks it to turn; its
  // neighbours through the top cannot follow without opening their own contacts. The rows cannot
  // all have what they ask, and the system is singular there: inverted as it is, it would press the
  // boxes between each other with impulses that move nothing. The least-squares solve answers with
  // the push-out's own size.
  Pile s = boxOnTwoBoxes(10.0f, 0.0f);
  for (ContactPoint& p : s.contacts[2].manifold.points)
    if (p.position.x() < -0.5f) p.depth = 0.02f;
  std::vector<ChainLink> links;
  ASSERT_TRUE(s.prepareSmall(links));
  DenseStorage storage;
  DenseNormalSystem& system = storage.system;
  for (int sweep = 0; sweep < 4; ++sweep)
    solveSmallIslandIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true, system);
  const float push = SolverParams{}.maxPushVelocity;
  // (Here 0.17 m/s and at most 0.4 N s a contact.)
  EXPECT_LT(s.fastest(), 2.0f * push);
  for (size_t k = 0; k < s.rows.size(); ++k) EXPECT_LT(s.total(k), 4.0f * push) << "contact " << k;
}

TEST(SmallIsland, ASpeculativeContactThroughABoardDoesNotLetABoxFallThroughIt) {
  // A 100 kg box 1 cm into the top one of two 2 kg boards, falling at 1.8 m/s, also has a
  // speculative contact with the lower board, 3 cm away through the upper one. The three rows
  // depend on each other (box on lower = box on upper + upper on lower); solved with the
  // speculative one, its allowance (3 cm a step) let the box fall on through the upper board. In
  // either order of the contacts one sweep stops it on the upper board.
  for (const bool speculativeFirst : {true, false}) {
    Pile s;
    const uint32_t lower = s.box(0.0f, 0.5f, 0.0f, 2.0f), upper = s.box(0.0f, 1.5f, 0.0f, 2.0f);
    const uint32_t box = s.box(0.0f, 2.5f, -1.8f, 100.0f);
    auto speculative = [&] {
      s.touch(lower, box, 0.0f, 1.0f);
      for (ContactPoint& p : s.contacts.back().manifold.points) p.depth = -0.03f;
    };
    if (speculativeFirst) speculative();
    s.touch(upper, box, 0.0f, 2.0f);
    for (ContactPoint& p : s.contacts.back().manifold.points) p.depth = 0.01f;
    if (!speculativeFirst) speculative();
    s.touch(lower, upper, 0.0f, 1.0f);
    s.touch(0, lower, 0.0f, 0.0f);
    std::vector<ChainLink> links;
    ASSERT_TRUE(s.prepareSmall(links));
    DenseStorage storage;
    solveSmallIslandIteration(s.bodies, s.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true,
                              storage.system);
    const size_t onUpper = speculativeFirst ? 1 : 0;
    for (int i = 0; i < 4; ++i) EXPECT_GE(s.gap(s.rows[onUpper], i), -1e-4f) << "the box goes on into the board";
    EXPECT_GT(s.bodies.v[box].y(), -0.01f) << (speculativeFirst ? "speculative first" : "speculative second");
  }
}

TEST(SmallIsland, AnIslandWhoseContactsAllSeparateSolvesNothing) {
  // The system's storage is reused island after island. An island whose links all come apart has
  // nothing to factor, and must not substitute what the last island left (a 5-link column's rows,
  // past this island's 4 links).
  DenseStorage storage;
  std::vector<ChainLink> links;
  Pile column5 = column(5, -2.0f);
  ASSERT_TRUE(column5.prepareSmall(links));
  solveSmallIslandIteration(column5.bodies, column5.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true,
                            storage.system);
  storage.system.attach(storage.doubles.data(), DenseNormalSystem::kMaxRows);  // as the World does each step
  Pile apart = boxOnTwoBoxes(10.0f, 3.0f);
  for (uint32_t b = 1; b <= 2; ++b) apart.bodies.v[b] = Vec3(0.0f, 1.0f, 0.0f);  // off the ground, below the top
  ASSERT_TRUE(apart.prepareSmall(links));
  solveSmallIslandIteration(apart.bodies, apart.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true,
                            storage.system);
  EXPECT_EQ(storage.system.rows, 0) << "rows left from the column";
  for (size_t k = 0; k < apart.rows.size(); ++k) EXPECT_EQ(apart.total(k), 0.0f) << "contact " << k;
  EXPECT_EQ(apart.bodies.v[3].y(), 3.0f);
  EXPECT_EQ(apart.bodies.v[1].y(), 1.0f);
}

TEST(SmallIsland, TakesOnlyIslandsItCanHold) {
  std::vector<ChainLink> links;
  Pile small = boxOnTwoBoxes(10.0f, 0.0f);
  EXPECT_TRUE(small.prepareSmall(links));
  // A pinched body (haif/pinch.h) is swept.
  small.contacts[0].pinched = true;
  EXPECT_FALSE(small.prepareSmall(links));
  // More contacts than the system holds.
  Pile big = column(DenseNormalSystem::kMaxLinks + 1, 0.0f);
  EXPECT_FALSE(big.prepareSmall(links));
}

TEST(SmallIsland, AnIslandPastTheCheapSizeCountsOnlyTheRowsOfContactsThatTouch) {
  // 40 contacts, each a face (3 rows): given room for 60 rows, the column is taken only when half
  // of its contacts are gaps of 5 cm, which take part only once the solve drives them in.
  const int links40 = 40, room = 60;
  ASSERT_GT(links40, DenseNormalSystem::kCheapLinks);
  std::vector<ChainLink> links;
  auto prepared = [&](Pile& p) {
    SolverParams sp;
    p.rows.resize(p.contacts.size());
    for (size_t k = 0; k < p.contacts.size(); ++k) prepareContact(p.bodies, p.contacts[k], uint32_t(k), sp, p.rows[k]);
    links.resize(p.rows.size());
    return prepareSmallIsland(p.contacts.data(), p.rows.data(), uint32_t(p.rows.size()), links.data(), room);
  };
  Pile touching = column(links40, 0.0f);
  EXPECT_FALSE(prepared(touching));
  Pile gapped = column(links40, 0.0f);
  for (size_t k = 0; k < gapped.contacts.size(); k += 2)
    for (ContactPoint& p : gapped.contacts[k].manifold.points) p.depth = -0.05f;
  EXPECT_TRUE(prepared(gapped));
  // When the gaps close, more links take part than there is room for: that sweep's rounds give way
  // to the manifolds' passes, and the next sweep with the same links must not take the factor
  // made for the links that touched before as its own.
  DenseStorage storage;
  storage.system.attach(storage.doubles.data(), room);
  solveSmallIslandIteration(gapped.bodies, gapped.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true,
                            storage.system);
  EXPECT_EQ(storage.system.rows, room) << "the 20 touching links";
  for (uint32_t b = 1; b < gapped.bodies.size(); ++b) gapped.bodies.v[b] = Vec3(0.0f, -5.0f * float(b), 0.0f);
  for (int sweep = 0; sweep < 2; ++sweep) {
    solveSmallIslandIteration(gapped.bodies, gapped.rows.data(), links.data(), uint32_t(links.size()), 1.0f, true,
                              storage.system);
    EXPECT_EQ(storage.system.rows, 0) << "sweep " << sweep << " kept a factor of other links";
  }
  for (uint32_t b = 1; b < gapped.bodies.size(); ++b) EXPECT_TRUE(gapped.bodies.v[b].allFinite()) << "box " << b;
  // Up to kCheapLinks contacts every row counts, touching or not.
  Pile small = column(DenseNormalSystem::kCheapLinks, 0.0f);
  for (size_t k = 0; k < small.contacts.size(); k += 2)
    for (ContactPoint& p : small.contacts[k].manifold.points) p.depth = -0.05f;
  EXPECT_FALSE(prepared(small)) << "96 rows in room for 60";
}

}  // namespace
}  // namespace haif
