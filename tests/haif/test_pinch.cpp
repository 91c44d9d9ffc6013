// Bodies pressed from opposite sides by bodies that cannot move (haif/pinch.h): no impulse builds
// up in them, and the static side wins over the kinematic one.
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace haif;
using namespace haif::test;

namespace {

// A small box sunk under the foot of a static wall standing on the ground: the wall's face pushes it
// down, the ground up. Nothing in the scene moves; returns the box's fastest speed over 600 steps.
float fastestUnderWallFoot(bool resolvePinches, uint32_t* pinchedSteps, float* largestImpulse) {
  WorldSettings ws;
  ws.resolvePinches = resolvePinches;
  // The control also goes without rest damping, which holds this scene still by itself (nothing in
  // it moves) while the impulses still grow without bound (haif/rest_damping.h).
  if (!resolvePinches) ws.restDamping = 0.0f;
  World w(ws);
  addGround(w);
  addStaticBox(w, Vec3(0.5f, 2.0f, 0.0f), Vec3(0.5f, 2.0f, 2.0f));  // x 0..1, y 0..4
  const uint32_t box = addBox(w, Vec3(0.3f, 0.15f, 0.0f), Vec3::Constant(0.2f));
  float fastest = 0.0f;
  *pinchedSteps = 0;
  for (int i = 0; i < 600; ++i) {
    w.step();
    *pinchedSteps += w.lastStats().pinchedBodies > 0 ? 1u : 0u;
    fastest = std::max(fastest, w.bodies().v[box].norm());
  }
  *largestImpulse = 0.0f;
  for (const Contact& c : w.contacts())
    for (int i = 0; i < c.manifold.count; ++i) *largestImpulse = std::max(*largestImpulse, c.normalImpulse[i]);
  return fastest;
}

}  // namespace

TEST(Pinch, BoxUnderAWallFootGainsNoEnergy) {
  // Both push-outs want the box to move, in opposite directions. Their impulses grew sweep after
  // sweep and were warm started from step to step (363 N s after 100 steps) until the box was
  // thrown out at 8.6 m/s from a scene where nothing moves (its exact chain solve released them).
  uint32_t pinched = 0;
  float impulse = 0.0f;
  const float calm = fastestUnderWallFoot(true, &pinched, &impulse);
  EXPECT_EQ(pinched, 600u) << "the box stays pinched, and counted, every step";
  EXPECT_LT(calm, 0.1f) << "nothing in the scene moves: nothing may give the box speed";
  EXPECT_LT(impulse, 1.0f) << "no impulse is carried from step to step";
  const float control = fastestUnderWallFoot(false, &pinched, &impulse);
  EXPECT_EQ(pinched, 0u);
  // Without the rule the impulses still grow without bound (245 N s on this 1 kg box after 600
  // steps). They no longer throw it (at 8.6 m/s) only because a body held between two immovable
  // ones is no longer solved as an exact chain (dynamics/contact_chain.cpp).
  EXPECT_GT(impulse, 100.0f) << "the failure this guards against (else the test no longer tests it)";
  EXPECT_LT(control, 0.1f);
}

TEST(Pinch, RollingCapsuleUnderAWallFootStaysPut) {
  // A capsule under the foot of a pit's wall, rolling along it: the state of one body of a swept pit
  // (adaptive 4 ms, step 1168). Alone between the ground and the wall it made a chain whose exact
  // solve is singular (its two rows push along one line from both ends): it was shot 0.16 m into
  // the ground at 9.7 m/s here, through it in the pit. It is swept instead, and nothing gives it speed.
  WorldSettings ws;
  ws.iterations = 4;
  World w(ws);
  addGround(w);
  addStaticBox(w, Vec3(0.0f, 2.0f, -10.5f), Vec3(11.0f, 2.0f, 0.5f));  // inner face at z = -10
  BodyDef d;
  d.shape = Shape::capsule(0.0929590538f, 0.117762007f);
  d.xf.p = Vec3(1.09229565f, 0.0917452648f, -10.6863689f);
  d.xf.q = Quat(-0.703913569f, -0.151295185f, -0.0969439894f, 0.687180698f);
  d.mass = 9.7587738f;
  d.linearVelocity = Vec3(0.0167830121f, 0.0f, -0.199663252f);
  d.angularVelocity = Vec3(-2.16260672f, 0.00135323917f, -0.173898667f);
  const uint32_t cap = w.addBody(d);
  const float reach = d.shape.radius + d.shape.halfHeight;
  const float start = d.linearVelocity.norm() + d.angularVelocity.norm() * reach;
  for (int i = 0; i < 120; ++i) {
    w.step();
    if (i < 60) {
      EXPECT_EQ(w.lastStats().pinchedBodies, 1u) << "step " << i;
    }
    const float speed = w.bodies().v[cap].norm() + w.bodies().w[cap].norm() * reach;
    ASSERT_LE(speed, start + 0.05f) << "step " << i;
    ASSERT_GT(w.bodies().xf[cap].p.y(), 0.085f) << "step " << i;
  }
}

TEST(Pinch, SweptBoxStaysOnTheStaticSide) {
  // A kinematic bar pushes a box into a wall at 2 m/s and goes on through the wall. The box cannot
  // stay out of both: it stays in front of the wall, on the ground, and the bar passes it.
  for (const bool resolve : {true, false}) {
    WorldSettings ws;
    ws.resolvePinches = resolve;
    // The control goes without the turn projection too: it moves a box out of the bar as well.
    if (!resolve) ws.turnProjection.angle = 0.0f;
    World w(ws);
    addGround(w);
    addStaticBox(w, Vec3(2.0f, 1.0f, 0.0f), Vec3(0.25f, 1.0f, 2.0f));  // inner face at x = 1.75
    const uint32_t box = addBox(w, Vec3(1.0f, 0.4f, 0.0f), Vec3::Constant(0.4f));
    addKinematicBox(w, Vec3(0.0f, 0.5f, 0.0f), Vec3(0.2f, 0.5f, 1.5f), Vec3(2.0f, 0.0f, 0.0f));
    float fastest = 0.0f, furthest = -1e9f, lowest = 1e9f;
    for (int i = 0; i < 150; ++i) {  // 2.5 s: the bar ends at x = 5
      w.step();
      fastest = std::max(fastest, w.bodies().v[box].norm());
      furthest = std::max(furthest, w.bodies().xf[box].p.x());
      lowest = std::min(lowest, w.bodies().xf[box].p.y());
    }
    if (!resolve) {
      EXPECT_GT(furthest, 1.75f) << "without the rule the box is pushed into the wall";
      continue;
    }
    EXPECT_LT(furthest, 1.75f - 0.4f + 0.06f) << "the box stays in front of the wall";
    EXPECT_GT(lowest, 0.4f - 0.06f) << "and on the ground";
    EXPECT_LT(fastest, 2.0f * 2.0f + 1.0f) << "no faster than twice the bar";
  }
}

// A bar 3 mm short of a box that leans on a wall, closing at 2 m/s: its contact is speculative, yet
// it asks the box to move into the wall within the step, so the box is pinched from the first step
// (a box between a paddle's tip and a wall, the tip 3 mm off, was not, and was thrown at 19 m/s).
TEST(Pinch, ABarClosingItsGapPinchesBeforeItTouches) {
  World w;
  addGround(w);
  addStaticBox(w, Vec3(2.0f, 1.0f, 0.0f), Vec3(0.25f, 1.0f, 2.0f));  // inner face at x = 1.75
  const uint32_t box = addBox(w, Vec3(1.551f, 0.2f, 0.0f), Vec3::Constant(0.2f));  // 1 mm into the wall
  addKinematicBox(w, Vec3(1.148f, 0.5f, 0.0f), Vec3(0.2f, 0.5f, 1.5f), Vec3(2.0f, 0.0f, 0.0f));  // 3 mm off
  w.step();
  EXPECT_GT(w.lastStats().pinchedBodies, 0u) << "pinched by a bar that has not touched it yet";
  float fastest = w.bodies().v[box].norm(), furthest = w.bodies().xf[box].p.x();
  for (int i = 0; i < 60; ++i) {
    w.step();
    fastest = std::max(fastest, w.bodies().v[box].norm());
    furthest = std::max(furthest, w.bodies().xf[box].p.x());
  }
  EXPECT_LT(fastest, 2.0f * 2.0f + 1.0f) << "no faster than twice the bar";
  EXPECT_LT(furthest, 1.75f - 0.2f + 0.03f) << "the box stays in front of the wall";
}

namespace {

struct CrushResult {
  float fastest = 0.0f, furthest = -1e9f, lowest = 1e9f;
  uint32_t limited = 0, pinchedSteps = 0;
};

// The same bar drives a row of three boxes, each touching the next, into the wall: only the first
// touches the bar and only the last the wall, so no single box is pressed from both sides.
CrushResult crushRowOfThree(bool resolve) {
  WorldSettings ws;
  ws.resolvePinches = resolve;
  // The control goes without the turn projection too: it moves the row out of the bar as well (and,
  // since session 25, alone keeps it from being thrown: fastest 2.1 m/s, 0.2 m short of the wall).
  if (!resolve) ws.turnProjection.angle = 0.0f;
  World w(ws);
  addGround(w);
  addStaticBox(w, Vec3(2.0f, 1.0f, 0.0f), Vec3(0.25f, 1.0f, 2.0f));  // inner face at x = 1.75
  std::vector<uint32_t> row;
  for (int i = 0; i < 3; ++i) row.push_back(addBox(w, Vec3(0.45f + 0.4f * float(i), 0.2f, 0.0f), Vec3::Constant(0.2f)));
  addKinematicBox(w, Vec3(0.0f, 0.5f, 0.0f), Vec3(0.2f, 0.5f, 1.5f), Vec3(2.0f, 0.0f, 0.0f));
  CrushResult r;
  for (int i = 0; i < 150; ++i) {  // 2.5 s: the bar ends at x = 5
    w.step();
    r.limited += w.lastStats().speedLimited;
    r.pinchedSteps += w.lastStats().pinchedBodies > 0 ? 1u : 0u;
    for (uint32_t b : row) {
      r.fastest = std::max(r.fastest, w.bodies().v[b].norm());
      r.furthest = std::max(r.furthest, w.bodies().xf[b].p.x());
      r.lowest = std::min(r.lowest, w.bodies().xf[b].p.y());
    }
  }
  return r;
}

}  // namespace

TEST(Pinch, ACrushedRowIsPassedByTheBarWithoutBeingThrown) {
  // A 2 m/s blade driving a pile into a wall threw bodies out at the speed bound (7435 times in 1200
  // steps of a bulldozer scene): the row's impulses grew step after step like a single pinched body's.
  const CrushResult r = crushRowOfThree(true);
  EXPECT_GT(r.pinchedSteps, 0u) << "the crush is seen and counted";
  EXPECT_EQ(r.limited, 0u) << "the speed bound never has to act";
  EXPECT_LT(r.fastest, 2.0f * 2.0f + 1.0f) << "no box faster than twice the bar";
  // The row is seen as crushed once its contacts overlap: the last box is 6 cm into the wall by then
  // (without the rule the bar pushes the row through it, to x = 5.4).
  EXPECT_LT(r.furthest, 1.75f - 0.2f + 0.08f) << "the row stays in front of the wall";
  EXPECT_GT(r.lowest, 0.2f - 0.06f) << "and on the ground";
  const CrushResult control = crushRowOfThree(false);
  EXPECT_TRUE(control.limited > 0 || control.fastest > 5.0f || control.furthest > 1.75f)
      << "without the rule the row is thrown or pushed into the wall (else the test no longer tests it): fastest "
      << control.fastest << " furthest " << control.furthest;
}

namespace {

// A kinematic body pushing box A along `push` (its contact normal), box B on A and leaning on a wall
// behind it (normal +z into B); each pair 1 cm deep, as the narrow phase would hand them to the
// detector. `lean` is the normal from A into B.
// `marks`, when given, receives each contact's pinched flag: lift-A, A-B, wall-B.
uint32_t crushesOfALeaningRow(const Vec3& push, const Vec3& lean, const Vec3& liftVelocity,
                              std::vector<bool>* marks = nullptr) {
  BodyStore bodies;
  auto add = [&](BodyKind kind, const Vec3& p) {
    Transform xf;
    xf.p = p;
    const float m = kind == BodyKind::Dynamic ? 1.0f : 0.0f;
    return bodies.add(kind, xf, m, Mat3(Mat3::Identity() * m));
  };
  const uint32_t lift = add(BodyKind::Kinematic, Vec3(0, 0, 0));
  const uint32_t wall = add(BodyKind::Static, Vec3(0, 1, -1));
  const uint32_t a = add(BodyKind::Dynamic, Vec3(0, 0.5f, 0));
  const uint32_t b = add(BodyKind::Dynamic, Vec3(0, 1, -0.5f));
  bodies.v[lift] = liftVelocity;
  ContactList contacts;
  std::vector<ContactEdge> edges;
  auto pair = [&](uint32_t x, uint32_t y, const Vec3& normal, bool immovable) {
    Contact c;
    c.a = x;
    c.b = y;
    c.manifold.count = 1;
    c.manifold.points[0] = ContactPoint{bodies.xf[y].p, normal, 0.01f, 0};
    contacts.push_back(c);
    ContactEdge e;
    e.a = x, e.b = y, e.count = 1, e.deepest = 0.01f, e.overlapping = true, e.pressedByImmovable = immovable;
    edges.push_back(e);
  };
  pair(lift, a, push, true);
  pair(a, b, lean, false);
  pair(wall, b, Vec3::UnitZ(), true);
  PinchDetector detector;
  const uint32_t pinched = detector.mark(bodies, edges.data(), contacts);
  if (marks)
    for (const Contact& c : contacts) marks->push_back(c.pinched);
  return pinched;
}

}  // namespace

// A row is crushed when an immovable body pushes back against the kinematic body's push: a lift
// raising a box under one that leans on a wall (A into B at 60 degrees from up, towards the wall)
// is not, though B is pushed towards the wall by A; read as a crush, the lift passed through A
// (0.138 m deep in a lift of 170 bodies). The same row driven at the wall by a blade is crushed.
TEST(Pinch, ALiftRaisingALeaningRowIsNotACrush) {
  const Vec3 lean = Vec3(0, 0.8f, -0.6f).normalized();
  EXPECT_EQ(crushesOfALeaningRow(Vec3::UnitY(), lean, Vec3(0, 0.5f, 0)), 0u);
  EXPECT_GT(crushesOfALeaningRow(-Vec3::UnitZ(), Vec3(0, 0.3f, -0.95f).normalized(), Vec3(0, 0, -0.5f)), 0u)
      << "a blade pushing the row at the wall still closes a crush";
}

// A crushed row's ends are marked, not its links: with both ends carrying nothing between steps the
// row's impulses cannot grow, and the links between dynamic bodies keep theirs (in a pile they carry
// its weight).
TEST(Pinch, ACrushMarksTheEndsOfItsRowNotItsLinks) {
  std::vector<bool> marks;
  const uint32_t pinched =
      crushesOfALeaningRow(-Vec3::UnitZ(), Vec3(0, 0.3f, -0.95f).normalized(), Vec3(0, 0, -0.5f), &marks);
  EXPECT_EQ(pinched, 2u) << "the row's two bodies, one at each end";
  ASSERT_EQ(marks.size(), 3u);
  EXPECT_TRUE(marks[0]) << "the blade's contact with the row's first body";
  EXPECT_FALSE(marks[1]) << "the link between the row's two dynamic bodies";
  EXPECT_TRUE(marks[2]) << "the wall's contact with its last";
}

namespace {

struct PileDriven {
  float linkRms = 0.0f;  // RMS depth (m) of the bricks' contacts with each other over the last 100 steps
  float fastest = 0.0f;
  uint32_t limited = 0;
};

// A bar on the ground at 0.5 m/s drives a pile of bricks two layers high (8 long, 3 wide) into a
// wall: from step ~115 the pile is pushed against the wall, and by step 300 the bar is 0.4 m from it,
// the bricks crushed and climbing over each other.
PileDriven driveAPileIntoAWall(bool resolve) {
  WorldSettings ws;
  ws.resolvePinches = resolve;
  World w(ws);
  addGround(w);
  addStaticBox(w, Vec3(2.25f, 1.0f, 0.0f), Vec3(0.25f, 1.0f, 1.0f));  // inner face at x = 2
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k)
        addBox(w, Vec3(-0.7f + 0.25f * float(i) + 0.1f * float(layer), 0.1f + 0.2f * float(layer), -0.5f + 0.5f * float(k)),
               Vec3(0.1f, 0.1f, 0.2f), 16.0f);  // 1000 kg/m^3
  addKinematicBox(w, Vec3(-1.0f, 0.31f, 0.0f), Vec3(0.1f, 0.3f, 1.0f), Vec3(0.5f, 0.0f, 0.0f));
  PileDriven r;
  double sum = 0.0;
  long points = 0;
  const BodyStore& b = w.bodies();
  for (int s = 0; s < 300; ++s) {
    w.step();
    r.limited += w.lastStats().speedLimited;
    for (uint32_t i = 0; i < b.size(); ++i)
      if (b.isDynamic(i)) r.fastest = std::max(r.fastest, b.v[i].norm());
    if (s < 200) continue;
    for (const Contact& c : w.contacts()) {
      if (!b.isDynamic(c.a) || !b.isDynamic(c.b)) continue;
      for (int i = 0; i < c.manifold.count; ++i, ++points) sum += std::pow(std::max(0.0f, c.manifold.points[i].depth), 2.0f);
    }
  }
  r.linkRms = float(std::sqrt(sum / double(std::max(points, 1L))));
  return r;
}

}  // namespace

// With every contact of a crushed row marked (no push-out, nothing carried between steps), the
// bricks sank 6.1 cm RMS into each other over the last 100 steps (3.8 with the ends marked); with
// no pinch rule the bar throws them at 8.6 m/s and the speed bound acts 42 times.
TEST(Pinch, APileDrivenIntoAWallKeepsItsBricksApartWithoutThrowingThem) {
  const PileDriven r = driveAPileIntoAWall(true);
  EXPECT_LT(r.linkRms, 0.05f) << "the bricks' links keep their push-out and load";
  EXPECT_EQ(r.limited, 0u) << "the speed bound never has to act";
  EXPECT_LT(r.fastest, 5.0f) << "no brick thrown";
  const PileDriven control = driveAPileIntoAWall(false);
  EXPECT_TRUE(control.limited > 0 || control.fastest > 5.0f)
      << "without the rule the bricks are thrown (else the test no longer tests it): fastest " << control.fastest;
}
