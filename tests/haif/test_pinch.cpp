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
float fastestUnderWallFoot(bool resolvePinches, uint32_t* pinchedSteps) {
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
  return fastest;
}

}  // namespace

TEST(Pinch, BoxUnderAWallFootGainsNoEnergy) {
  // Both push-outs want the box to move, in opposite directions. Their impulses grew sweep after
  // sweep and were warm started from step to step (363 N s after 100 steps) until the box was
  // thrown out at 8.6 m/s from a scene where nothing moves.
  uint32_t pinched = 0;
  const float calm = fastestUnderWallFoot(true, &pinched);
  EXPECT_EQ(pinched, 600u) << "the box stays pinched, and counted, every step";
  EXPECT_LT(calm, 0.1f) << "nothing in the scene moves: nothing may give the box speed";
  const float kicked = fastestUnderWallFoot(false, &pinched);
  EXPECT_EQ(pinched, 0u);
  EXPECT_GT(kicked, 2.0f) << "the failure this guards against (else the test no longer tests it)";
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
