// TurnProjection (haif/turn_projection.h): after the step, the pairs of a body that turned far are
// collided again and moved apart by their depth past the keep depth, positions only.
#include "haif/turn_projection.h"

#include "support/physics_test_util.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

using test::addGround;
using test::addStaticBox;

constexpr float kDt = 1.0f / 60.0f;

struct Scene {
  BodyStore bodies;
  std::vector<Shape> shapes;
  ContactList contacts;
  uint32_t add(BodyKind kind, const Shape& shape, const Vec3& p, float mass) {
    Transform xf;
    xf.p = p;
    shapes.push_back(shape);
    return bodies.add(kind, xf, kind == BodyKind::Dynamic ? mass : 0.0f,
                      kind == BodyKind::Dynamic ? Mat3(Mat3::Identity() * mass) : Mat3(Mat3::Zero()));
  }
  void pair(uint32_t a, uint32_t b, float apart = kMargin) {
    Contact c;
    c.a = a;
    c.b = b;
    contacts.push_back(c);
    known.push_back(apart);
  }
  // A pair whose narrow phase, at the step's start, found one point `depth` deep at `at`.
  void pairAt(uint32_t a, uint32_t b, const Vec3& at, const Vec3& normal, float depth) {
    pair(a, b);
    Manifold& m = contacts.back().manifold;
    m.count = 1;
    m.points[0] = ContactPoint{at, normal, depth, 0};
  }
  uint32_t apply(const TurnProjectionSettings& s = {}) {
    std::vector<ContactEdge> edges(contacts.size());
    std::vector<float> reach(bodies.size());
    for (size_t i = 0; i < contacts.size(); ++i) {
      ContactEdge& e = edges[i];
      e.a = contacts[i].a, e.b = contacts[i].b;
      e.count = uint8_t(contacts[i].manifold.count);  // as the narrow phase notes them
      e.deepest = e.count > 0 ? contacts[i].manifold.deepest() : -known[i];
    }
    for (size_t i = 0; i < bodies.size(); ++i) {
      const Aabb box = computeAabb(shapes[i], Transform{});
      reach[i] = bodies.isDynamic(uint32_t(i)) ? 0.5f * (box.hi - box.lo).norm() : 0.0f;
    }
    std::vector<Aabb> bounds(bodies.size());  // the final poses stand in for the start's
    for (size_t i = 0; i < bodies.size(); ++i) bounds[i] = computeAabb(shapes[i], bodies.xf[i]);
    TurnProjectionInput in;
    in.bodies = &bodies;
    in.shapes = &shapes;
    in.contacts = &contacts;
    in.edges = edges.data();
    in.reach = reach.data();
    in.startBounds = bounds.data();
    jointed.resize(bodies.size(), 0);
    in.jointed = jointed.data();
    std::vector<uint32_t> pinched;  // as PinchDetector lists the contacts it marked
    for (uint32_t i = 0; i < contacts.size(); ++i)
      if (contacts[i].pinched) pinched.push_back(i);
    in.pinched = &pinched;
    in.dt = kDt;
    in.contactMargin = kMargin;
    return projection.apply(in, s);
  }
  static constexpr float kMargin = 0.02f;  // the narrow phase's base margin
  TurnProjection projection;
  std::vector<uint8_t> jointed;  // per body: has a joint
  std::vector<float> known;      // per pair without points: how far apart it was found (m)
};

// Two balls 6 cm apart at the end of the step, the upper one having come down at 3 m/s (5 cm a
// step): their boxes overlap, so only how far apart the pair began tells whether it may touch. The
// narrow phase collided it with a margin of 10 cm (its base 2 cm and its closing speed) and found
// no point: it cannot have closed 10 cm, and is not looked at again. Known only 2 cm apart, it is,
// and the overlap along the line of centres (-6 cm) settles it without a collision.
TEST(TurnProjection, APairFoundApartByItsClosingMarginIsNotCollidedAgain) {
  for (const float apart : {0.10f, 0.02f}) {
    Scene s;
    const uint32_t low = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(0, 0, 0), 1);
    const uint32_t high = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(0.75f, 0.75f, 0), 1);
    s.bodies.v[high] = Vec3(-3.0f, -3.0f, 0).normalized() * 3.0f;
    s.pair(low, high, apart);
    EXPECT_EQ(s.apply(), 0u);
    EXPECT_EQ(s.projection.settledByReach(), apart > 0.05f ? 0u : 1u) << apart;
    EXPECT_EQ(s.projection.collisions(), 0u) << apart;
  }
}

// A box spinning at 12 rad/s (0.2 rad a step) on the ground, 5 mm deep at the step's start: its
// pair is a candidate. Ending 5 mm
// deep, its overlap along the normal bounds it within the 1 cm keep depth: settled, not collided,
// not moved. Ending 4 cm deep, it is collided and lifted to the keep depth (and checked once more).
TEST(TurnProjection, ATurnedPairThatEndsShallowIsSettledByItsReach) {
  const TurnProjectionSettings d;
  for (const float depth : {0.005f, 0.04f}) {
    Scene s;
    const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
    const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.5f - depth, 0), 2);
    s.pairAt(ground, box, Vec3(0, -0.005f, 0), Vec3::UnitY(), 0.005f);  // the step began 5 mm deep
    s.bodies.w[box] = Vec3(0, 0, 12.0f);
    const bool deep = depth > 0.02f;
    EXPECT_EQ(s.apply(), deep ? 1u : 0u) << depth;
    EXPECT_EQ(s.projection.settledByReach(), deep ? 0u : 1u) << depth;
    EXPECT_EQ(s.projection.collisions(), deep ? 2u : 0u) << depth;
    EXPECT_NEAR(s.bodies.xf[box].p.y(), deep ? 0.5f - d.keep : 0.5f - depth, 1e-5f) << depth;
  }
}

// A spinning box 0.1 m into the ground: it is lifted by 0.1 m less the keep depth, and its
// velocities stay as they were.
TEST(TurnProjection, LiftsATurnedBoxOutOfTheGroundToTheKeepDepth) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f, 0), 2);
  s.pair(ground, box);
  s.bodies.w[box] = Vec3(0, 0, 12.0f);  // 0.2 rad a step
  s.bodies.v[box] = Vec3(1, -2, 0);
  EXPECT_EQ(s.apply(), 1u);
  const TurnProjectionSettings d;
  EXPECT_NEAR(s.bodies.xf[box].p.y(), 0.5f - d.keep, 1e-4f);
  EXPECT_NEAR(s.bodies.xf[box].p.x(), 0.0f, 1e-6f);
  EXPECT_EQ(s.bodies.v[box], Vec3(1, -2, 0));
  EXPECT_EQ(s.bodies.w[box], Vec3(0, 0, 12.0f));
  EXPECT_EQ(s.bodies.xf[ground].p, Vec3(0, -0.5f, 0));
}

// Past its target by less than the least move, a pair is left where it is (moving it would bring
// its neighbours into the round for a fraction of a millimetre); past it by more, it is moved to
// the target. With no least move but the rounding, the small excess is moved too.
TEST(TurnProjection, APairPastItsTargetByLessThanTheLeastMoveIsLeft) {
  const TurnProjectionSettings d;
  ASSERT_GT(d.leastMove, 1e-4f);
  TurnProjectionSettings roundingOnly = d;
  roundingOnly.leastMove = 0.0f;
  struct Case {
    float past;  // m past the keep depth at the step's end
    const TurnProjectionSettings* settings;
    bool moved;
  };
  for (const Case& k : {Case{0.5f * d.leastMove, &d, false}, Case{3.0f * d.leastMove, &d, true},
                        Case{0.5f * d.leastMove, &roundingOnly, true}}) {
    Scene s;
    const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
    const float y = 0.5f - d.keep - k.past;
    const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, y, 0), 2);
    s.pair(ground, box);
    s.bodies.w[box] = Vec3(0, 0, 12.0f);  // 0.2 rad a step: its pairs are collided again
    EXPECT_EQ(s.apply(*k.settings), k.moved ? 1u : 0u) << k.past;
    EXPECT_EQ(s.projection.collisions(), k.moved ? 2u : 1u) << k.past;  // a moved pair is checked again
    EXPECT_NEAR(s.bodies.xf[box].p.y(), k.moved ? 0.5f - d.keep : y, 1e-5f) << k.past;
  }
}

// A spinning box 0.1 m into the ground, with a resting box 3 cm to its side: lifted out, it brings
// its pair with that box into the round, but their boxes are still 3 cm apart, which says the pair
// is apart without a collision. Only the ground pair is collided, before and after the lift (2);
// colliding each pair the lift brings in would make 3.
TEST(TurnProjection, APairWhoseBoxesAreApartIsNotCollided) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f, 0), 2);
  const uint32_t side = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(1.03f, 0.5f, 0), 2);
  s.pair(ground, box);
  s.pairAt(ground, side, Vec3(1.03f, 0, 0), Vec3::UnitY(), 0.0f);
  s.pair(box, side, 0.03f);
  s.bodies.w[box] = Vec3(0, 0, 12.0f);  // 0.2 rad a step
  EXPECT_EQ(s.apply(), 1u);
  const TurnProjectionSettings d;
  EXPECT_NEAR(s.bodies.xf[box].p.y(), 0.5f - d.keep, 1e-4f);
  EXPECT_EQ(s.bodies.xf[side].p, Vec3(1.03f, 0.5f, 0));
  EXPECT_EQ(s.projection.collisions(), 2u);
}

// A pair whose points cannot move the narrow phase's margin in a step is not collided again (the
// solver's push-out handles a slow body), a sphere turns without moving its surface, and depth
// within the keep depth is left.
TEST(TurnProjection, LeavesSlowBodiesSpheresAndShallowPairsAlone) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t slow = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f, 0), 1);
  const uint32_t ball = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(3, 0.4f, 0), 1);
  const uint32_t shallow = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(-3, 0.495f, 0), 1);
  for (uint32_t b : {slow, ball, shallow}) s.pair(ground, b);
  s.bodies.w[slow] = Vec3(0, 0, 1.0f);  // corners at 0.87 m/s: 1.4 cm a step, under the 2 cm margin
  s.bodies.w[ball] = Vec3(0, 0, 30.0f);
  s.bodies.w[shallow] = Vec3(0, 0, 30.0f);
  EXPECT_EQ(s.apply(), 0u);
  EXPECT_EQ(s.bodies.xf[slow].p.y(), 0.4f);
  EXPECT_EQ(s.bodies.xf[ball].p.y(), 0.4f);
  EXPECT_EQ(s.bodies.xf[shallow].p.y(), 0.495f);
  TurnProjectionSettings off;
  off.angle = 0.0f;
  s.bodies.w[slow] = Vec3(0, 0, 50.0f);
  EXPECT_EQ(s.apply(off), 0u);
  EXPECT_EQ(s.bodies.xf[slow].p.y(), 0.4f);
}

// A heavy turned box sunk into a light one that rests on the ground: the lower pair is settled
// first and the heavy one moves up, instead of the light one being driven into the ground.
TEST(TurnProjection, MovesTheUpperBodyOfAStackedPair) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t light = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.5f, 0), 1);
  const uint32_t heavy = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 1.3f, 0), 100);
  s.pair(light, heavy);  // listed first: the height order, not the list order, decides
  s.pair(ground, light);
  s.bodies.w[heavy] = Vec3(20.0f, 0, 0);
  s.bodies.w[light] = Vec3(20.0f, 0, 0);
  EXPECT_EQ(s.apply(), 1u);  // the light box touches the ground without overlap
  const TurnProjectionSettings d;
  EXPECT_EQ(s.bodies.xf[light].p.y(), 0.5f);
  EXPECT_NEAR(s.bodies.xf[heavy].p.y(), 1.5f - d.keep, 1e-4f);
}

// A turned box lifted out of the ground lifts the box on it, which then sits in the box above that
// (a pair of two bodies that did not turn): the next round takes it. Each pair keeps 1 cm.
TEST(TurnProjection, ABodyItMovedBringsItsPairsIntoTheNextRound) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t a = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f, 0), 1);
  const uint32_t b = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 1.4f, 0), 1);
  const uint32_t c = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 2.4f, 0), 1);
  s.pair(b, c);
  s.pair(a, b);
  s.pair(ground, a);
  s.bodies.w[a] = Vec3(0, 20.0f, 0);
  EXPECT_EQ(s.apply(), 3u);
  EXPECT_NEAR(s.bodies.xf[a].p.y(), 0.49f, 1e-4f);
  EXPECT_NEAR(s.bodies.xf[b].p.y(), 1.48f, 1e-4f);
  EXPECT_NEAR(s.bodies.xf[c].p.y(), 2.47f, 1e-4f);
}

// A column of nine boxes standing on each other, the lowest turned 0.1 m into the ground: each lift
// pushes the box above 1 cm less deep into the next, and the whole column is lifted in one call,
// more boxes than rounds: a move brings its body's higher pairs into the same round (a knocked tower
// moved a block into the one above it after the last round and left the pair 0.2 m deep).
TEST(TurnProjection, AMoveBringsTheHigherPairsOfItsBodyIntoTheSameRound) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  std::vector<uint32_t> column;
  for (int i = 0; i < 9; ++i) column.push_back(s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f + float(i), 0), 1));
  s.pair(ground, column[0]);
  // Touching: the narrow phase found a point at depth 0 (a pair without points began the step
  // farther apart than its margin).
  for (int i = 0; i + 1 < 9; ++i) s.pairAt(column[size_t(i)], column[size_t(i) + 1], Vec3(0, 0.9f + float(i), 0), Vec3::UnitY(), 0.0f);
  s.bodies.w[column[0]] = Vec3(0, 20.0f, 0);
  EXPECT_EQ(s.apply(), 9u);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(s.bodies.xf[column[size_t(i)]].p.y(), 0.49f + 0.99f * float(i), 1e-3f) << "box " << i;
}

// A box 4 cm in the ground is lifted 1 cm (to the 3 cm it may keep) between two neighbours it
// touches. Its pairs with them are not collided again: no point of it moved more than 1 cm, and a
// pair that touched cannot now be deeper than that, nor than the 1 cm it may keep. Only its ground
// pair is, to see that it is out (2 collisions). A neighbour pressed 5 mm into it may now be 1.5 cm
// deep: that pair is looked at again, and left, being no deeper than it was: its overlap along its
// normal (5 mm) says so without a collision.
TEST(TurnProjection, APairItsMovesCannotHaveCarriedPastItsTargetIsNotCollidedAgain) {
  for (const float pressed : {0.0f, 0.005f}) {
    Scene s;
    const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
    const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.46f, 0), 1);
    const uint32_t left = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(-1.0f + pressed, 0.5f, 0), 1);
    const uint32_t right = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(1.0f, 0.5f, 0), 1);
    s.pairAt(ground, box, Vec3(0, -0.02f, 0), Vec3::UnitY(), 0.04f);
    s.pairAt(ground, left, Vec3(-1.0f, 0, 0), Vec3::UnitY(), 0.0f);
    s.pairAt(ground, right, Vec3(1.0f, 0, 0), Vec3::UnitY(), 0.0f);
    s.pairAt(left, box, Vec3(-0.5f, 0.5f, 0), Vec3::UnitX(), pressed);
    s.pairAt(box, right, Vec3(0.5f, 0.5f, 0), Vec3::UnitX(), 0.0f);
    EXPECT_EQ(s.apply(), 1u) << pressed;
    EXPECT_NEAR(s.bodies.xf[box].p.y(), 0.47f, 1e-4f);
    EXPECT_EQ(s.projection.collisions(), 2u) << pressed;
    EXPECT_EQ(s.projection.settledByReach(), pressed > 0.0f ? 1u : 0u) << pressed;
    EXPECT_EQ(s.bodies.xf[left].p, Vec3(-1.0f + pressed, 0.5f, 0));
    EXPECT_EQ(s.bodies.xf[right].p, Vec3(1.0f, 0.5f, 0));
  }
}

// Two boxes pressed 5 mm into each other, each 4 cm in the ground, are both lifted 1 cm (to the 3 cm
// they may keep). Moved alike, they are where they were relative to each other: their pair cannot be
// deeper than it was, and is not collided again (a jam pushed against `swept_pit`'s bar moves its
// bodies the same way). Only the ground pairs are, ahead and after the lift: 4 collisions. A bound
// on what each body moved, not on how they moved relative to each other, collides it too (5).
TEST(TurnProjection, APairOfBodiesMovedAlikeIsNotCollidedAgain) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t left = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(-0.4975f, 0.46f, 0), 1);
  const uint32_t right = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0.4975f, 0.46f, 0), 1);
  s.pairAt(ground, left, Vec3(-0.5f, -0.02f, 0), Vec3::UnitY(), 0.04f);
  s.pairAt(ground, right, Vec3(0.5f, -0.02f, 0), Vec3::UnitY(), 0.04f);
  s.pairAt(left, right, Vec3(0, 0.46f, 0), Vec3::UnitX(), 0.005f);
  EXPECT_EQ(s.apply(), 2u);
  EXPECT_NEAR(s.bodies.xf[left].p.y(), 0.47f, 1e-4f);
  EXPECT_NEAR(s.bodies.xf[right].p.y(), 0.47f, 1e-4f);
  EXPECT_EQ(s.bodies.xf[left].p.x(), -0.4975f);
  EXPECT_EQ(s.bodies.xf[right].p.x(), 0.4975f);
  EXPECT_EQ(s.projection.collisions(), 4u);
}

// A plate turning about its normal at 2 rad/s turns 0.033 rad a step, under the angle, but its rim
// (1.42 m out) sweeps 4.7 cm a step, more than the narrow phase's 2 cm margin: features of its pairs
// that were not among their points may have met within the step (a turning 1080 kg block of
// `tower_collapse` went 13 cm into the next while their one point read as parting). So its pairs are
// collided again even where their points say nothing moves: a box found 5 cm into it is lifted to
// the keep depth. At 0.5 rad/s (its rim 1.2 cm a step) the point is believed.
TEST(TurnProjection, ABodyWhoseTurnSweepsItsSurfacePastTheMarginCountsAsTurned) {
  for (const float spin : {2.0f, 0.5f}) {
    Scene s;
    const uint32_t plate = s.add(BodyKind::Dynamic, Shape::box(Vec3(1.0f, 0.05f, 1.0f)), Vec3(0, 1.0f, 0), 10);
    const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.1f)), Vec3(0, 1.1f, 0), 1);
    s.pairAt(plate, box, Vec3(0, 1.05f, 0), Vec3::UnitY(), 0.0f);  // at the step's start: touching
    s.bodies.xf[box].p.y() -= 0.05f;  // where the step left it
    s.bodies.w[plate] = Vec3(0, spin, 0);
    const TurnProjectionSettings d;
    if (spin > 1.0f) {
      EXPECT_EQ(s.apply(), 1u);
      EXPECT_NEAR(s.bodies.xf[box].p.y(), 1.15f - d.keep, 1e-4f);
    } else {
      EXPECT_EQ(s.apply(), 0u);
      EXPECT_EQ(s.projection.collisions(), 0u);
    }
  }
}

// A 100 kg ball landing on a 1 kg box that rests on the ground: ten Gauss-Seidel sweeps pass the
// box's support up a fraction m/(m+M) at a time, so the ball goes on sinking. It began the step 5 cm
// in and ended 10 cm in, still falling, without turning: the 5 cm the step added go, and 2 cm of
// the depth it began with; only the upper body moves, and no velocity changes.
TEST(TurnProjection, PushesAHeavyBallSinkingIntoALightBoxBackByWhatTheStepAdded) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.5f, 0), 1);
  const uint32_t ball = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(0, 1.4f, 0), 100);
  s.pair(ground, box);
  s.pairAt(box, ball, Vec3(0, 0.975f, 0), Vec3::UnitY(), 0.05f);
  s.bodies.v[ball] = Vec3(0, -3.0f, 0);
  EXPECT_EQ(s.apply(), 1u);
  const TurnProjectionSettings d;
  EXPECT_NEAR(s.bodies.xf[ball].p.y(), 1.4f + 0.05f + d.crushRecover, 1e-4f);
  EXPECT_EQ(s.bodies.xf[box].p.y(), 0.5f);
  EXPECT_EQ(s.bodies.v[ball], Vec3(0, -3.0f, 0));
  // Off: left to the solver.
  s.bodies.xf[ball].p.y() = 1.4f;
  TurnProjectionSettings off;
  off.crushKeep = 0.0f;
  EXPECT_EQ(s.apply(off), 0u);
  EXPECT_EQ(s.bodies.xf[ball].p.y(), 1.4f);
}

// Two balls 8 cm into each other with no point between them: at the step's start they were apart
// by more than they closed, and a blow within the step drove them together at 10 m/s. Their final
// boxes overlap, so they are collided again and moved apart to the keep depth, by inverse mass.
// Closing at 0.5 m/s (under the narrow phase's margin a step) they are the solver's.
TEST(TurnProjection, CollidesAgainAPairStruckTogetherWithinTheStep) {
  for (const float closing : {10.0f, 0.5f}) {
    Scene s;
    const uint32_t a = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(0, 1, 0), 1);
    const uint32_t b = s.add(BodyKind::Dynamic, Shape::sphere(0.5f), Vec3(0.92f, 1, 0), 1);
    s.pair(a, b);
    s.bodies.v[a] = Vec3(closing, 0, 0);
    const TurnProjectionSettings d;
    if (closing > 1.0f) {
      EXPECT_EQ(s.apply(), 1u);
      EXPECT_NEAR(s.bodies.xf[b].p.x() - s.bodies.xf[a].p.x(), 1.0f - d.keep, 1e-4f);
      EXPECT_NEAR(s.bodies.xf[a].p.x() + s.bodies.xf[b].p.x(), 0.92f, 1e-5f);  // equal masses: equal shares
    } else {
      EXPECT_EQ(s.apply(), 0u);
      EXPECT_EQ(s.bodies.xf[b].p.x(), 0.92f);
    }
  }
}

// Bodies that began the step half a metre into each other (spawned so) and did not go deeper are
// brought apart by crushRecover a step, not in one jump: a jump pushed one of them 0.38 m into the
// ground in a random world.
TEST(TurnProjection, AnOldDeepOverlapComesApartByABoundedStep) {
  Scene s;
  const uint32_t a = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 1, 0), 1);
  const uint32_t b = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0.5f, 1, 0), 1);
  s.pairAt(a, b, Vec3(0.25f, 1, 0), Vec3::UnitX(), 0.5f);
  const TurnProjectionSettings d;
  for (int step = 1; step <= 3; ++step) {
    s.contacts[0].manifold.points[0].depth = 1.0f - (s.bodies.xf[b].p.x() - s.bodies.xf[a].p.x());  // the next narrow phase
    EXPECT_EQ(s.apply(), 1u);
    EXPECT_NEAR(s.bodies.xf[b].p.x() - s.bodies.xf[a].p.x(), 0.5f + float(step) * d.crushRecover, 1e-4f);
  }
}

// A box 0.1 m into the ground and 0.15 m into a slab beside it, spinning: the ground's pair is
// lower and lifts it 9 cm; the slab's pair, collided ahead at the round's start, is collided again
// (its box moved) and lifts it 5 cm more, to the keep depth. With the stale depth it would go up
// 14 cm and leave the ground.
TEST(TurnProjection, APairWhoseBodyAnEarlierPairMovedIsCollidedAgain) {
  Scene s;
  const uint32_t ground = s.add(BodyKind::Static, Shape::box(Vec3(10, 0.5f, 10)), Vec3(0, -0.5f, 0), 0);
  const uint32_t slab = s.add(BodyKind::Static, Shape::box(Vec3(1, 0.5f, 1)), Vec3(1.2f, -0.45f, 0), 0);
  const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.4f, 0), 1);
  s.pair(slab, box);
  s.pair(ground, box);
  s.bodies.w[box] = Vec3(0, 20.0f, 0);
  EXPECT_EQ(s.apply(), 2u);
  EXPECT_NEAR(s.bodies.xf[box].p.y(), 0.54f, 1e-4f);
}

// A box 8 cm into a kinematic platform rising at 1 m/s, 1 cm in at the step's start: the platform
// does not give way, so the box moves out to the keep depth (a turning drum pressed the bottom of its
// pile 9 cm into its wall). Marked pinched (pressed from the other side too, haif/pinch.h), it is left.
TEST(TurnProjection, MovesABodyOutOfAKinematicOneUnlessPinched) {
  for (const bool pinched : {false, true}) {
    Scene s;
    const uint32_t platform = s.add(BodyKind::Kinematic, Shape::box(Vec3(2, 0.25f, 2)), Vec3(0, 0, 0), 0);
    const uint32_t box = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.5f)), Vec3(0, 0.67f, 0), 1);
    s.pairAt(platform, box, Vec3(0, 0.25f, 0), Vec3::UnitY(), 0.01f);
    s.contacts[0].pinched = pinched;
    s.bodies.v[platform] = Vec3(0, 1, 0);
    const TurnProjectionSettings d;
    EXPECT_EQ(s.apply(), pinched ? 0u : 1u);
    EXPECT_NEAR(s.bodies.xf[box].p.y(), pinched ? 0.67f : 0.75f - d.keep, 1e-4f);
    EXPECT_EQ(s.bodies.xf[platform].p, Vec3::Zero());
  }
}

// A crate 8 cm into the end of a plank of a rope bridge, 1 cm in at the step's start and thrown at it
// at 4 m/s: the plank has joints and is not moved (its joints would be pulled apart; free, it would
// take its inverse-mass share), the crate moves out of it to the keep depth. Two jointed bodies in
// each other are left to the solver.
TEST(TurnProjection, MovesABodyOutOfAJointedOneButNeverTheJointedOne) {
  for (const bool crateJointed : {false, true}) {
    Scene s;
    const uint32_t plank = s.add(BodyKind::Dynamic, Shape::box(Vec3(1, 0.1f, 0.5f)), Vec3(0, 5, 0), 4);
    const uint32_t crate = s.add(BodyKind::Dynamic, Shape::box(Vec3::Constant(0.3f)), Vec3(1.22f, 5, 0), 15);
    s.pairAt(plank, crate, Vec3(1, 5, 0), Vec3::UnitX(), 0.01f);
    s.bodies.v[crate] = Vec3(-4, 0, 0);
    s.jointed.assign(2, 0);
    s.jointed[plank] = 1;
    s.jointed[crate] = crateJointed ? 1 : 0;
    const TurnProjectionSettings d;
    EXPECT_EQ(s.apply(), crateJointed ? 0u : 1u);
    EXPECT_EQ(s.bodies.xf[plank].p, Vec3(0, 5, 0));
    EXPECT_NEAR(s.bodies.xf[crate].p.x(), crateJointed ? 1.22f : 1.3f - d.keep, 1e-4f);
  }
}

// 400 boxes, capsules and balls of 1-40 kg thrown spinning into a 6 m pit: the scans and each
// round's collisions run on the workers, and the stage moves the same bodies by the same amounts as
// on one thread (a pair collided ahead and taken after its body moved is collided again).
uint64_t pourAtThreads(int threads, uint64_t& projected) {
  World w;
  w.setThreads(threads);
  addGround(w);
  for (int side = -1; side <= 1; side += 2) {
    addStaticBox(w, Vec3(3.5f * float(side), 2, 0), Vec3(0.5f, 2, 4));
    addStaticBox(w, Vec3(0, 2, 3.5f * float(side)), Vec3(4, 2, 0.5f));
  }
  for (int i = 0; i < 400; ++i) {
    BodyDef d;
    const int kind = i % 3;
    d.shape = kind == 0 ? Shape::box(Vec3(0.3f, 0.15f, 0.2f)) : kind == 1 ? Shape::capsule(0.12f, 0.3f) : Shape::sphere(0.25f);
    d.xf.p = Vec3(-2.4f + 0.8f * float(i % 7), 1.0f + 0.7f * float(i / 49), -2.4f + 0.8f * float((i / 7) % 7));
    d.linearVelocity = Vec3(0, -12.0f, 0);
    d.angularVelocity = Vec3(float(i % 5) - 2.0f, float(i % 3) - 1.0f, float(i % 4) - 1.5f) * 4.0f;
    d.mass = 1.0f + float((i * 7) % 40);
    w.addBody(d);
  }
  projected = 0;
  for (int step = 0; step < 90; ++step) {
    w.step();
    projected += w.lastStats().turnProjected;
  }
  return w.stateHash();
}

TEST(TurnProjection, APourMovesTheSameAtEveryThreadCount) {
  uint64_t one = 0, three = 0;
  EXPECT_EQ(pourAtThreads(1, one), pourAtThreads(3, three));
  EXPECT_EQ(one, three);
  EXPECT_GT(one, 50u) << "the stage should have work in this pour";
}

// The controller plans the turn projection with the work after the solve, not as sweeps: it costs the
// same at any iteration count. A controller that records what it is told sees the projection's time
// moved out of the solve's (StepStats::solveMs keeps it, as stats.csv documents) into the rest.
class RecordingController final : public IterationController {
 public:
  int choose(const ControlContext&) override { return 10; }
  void observe(const ControlContext&, const SolveObservation& obs) override { last = obs; }
  std::string name() const override { return "recording"; }
  SolveObservation last;
};

TEST(TurnProjection, TheControllerSeesItsTimeAfterTheSolveNotInIt) {
  World w;
  addGround(w);
  for (int i = 0; i < 40; ++i) {
    BodyDef d;
    d.shape = Shape::box(Vec3(0.6f, 0.1f, 0.1f));
    d.xf.p = Vec3(1.5f * float(i % 8), 0.3f, 1.5f * float(i / 8));
    d.linearVelocity = Vec3(0, -3.0f, 0);
    d.angularVelocity = Vec3(0, 0, 30.0f);  // half a radian a step: every one is turned
    w.addBody(d);
  }
  auto recorder = std::make_unique<RecordingController>();
  RecordingController* seen = recorder.get();
  w.setController(std::move(recorder));
  int projectedSteps = 0;
  for (int step = 0; step < 30; ++step) {
    w.step();
    const StepStats& s = w.lastStats();
    const SolveObservation& o = seen->last;
    EXPECT_NEAR(o.solveMs + o.integrateMs, s.solveMs + s.integrateMs, 1e-9);
    if (s.turnProjected == 0) continue;
    ++projectedSteps;
    EXPECT_LT(o.solveMs, s.solveMs) << "step " << step;
    EXPECT_GT(o.integrateMs, s.integrateMs) << "step " << step;
  }
  EXPECT_GT(projectedSteps, 0) << "the projection should have had work";
}

}  // namespace
}  // namespace haif
