// The contact skin (SolverParams::skin): bodies placed at rest less than the skin apart count as
// touching and stay where they were placed; every other gap is closed as before.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

WorldSettings skinSettings(int iterations = 10) {
  WorldSettings s;
  s.dt = 1.0f / 60.0f;
  s.iterations = iterations;
  return s;
}

float boxHeightAfter(World& w, uint32_t box, int steps) {
  for (int s = 0; s < steps; ++s) w.step();
  return w.bodies().xf[box].p.y();
}

TEST(ContactSkin, ABoxPlacedWithinTheSkinStaysWhereItWasPlaced) {
  World w(skinSettings());
  addGround(w);
  const float skin = w.settings().contact.skin;
  const float placed = 0.5f + 0.5f * skin;
  const uint32_t box = addBox(w, Vec3(0.0f, placed, 0.0f));
  EXPECT_NEAR(boxHeightAfter(w, box, 120), placed, 1e-5f);
  EXPECT_LT(w.bodies().v[box].norm(), 1e-4f);
}

TEST(ContactSkin, ABoxPlacedBeyondTheSkinFallsOntoTheGround) {
  World w(skinSettings());
  addGround(w);
  const float skin = w.settings().contact.skin;
  const uint32_t box = addBox(w, Vec3(0.0f, 0.5f + 3.0f * skin, 0.0f));
  const float y = boxHeightAfter(w, box, 60);
  EXPECT_LE(y, 0.5f + 1e-5f) << "the gap was not closed";
  EXPECT_GT(y, 0.5f - w.settings().contact.slop) << "sank past the slop";
}

// A falling box closes every gap: the skin holds only what is placed at rest, not what lands (a box
// coming down at a few cm/s passes through the skin's band in its last step). A hovering box thrown
// up leaves the skin and lands like any other.
TEST(ContactSkin, ALandingBoxTouchesAndAHoveringBoxThrownUpLandsTouching) {
  World w(skinSettings());
  addGround(w);
  const float skin = w.settings().contact.skin;
  const uint32_t dropped = addBox(w, Vec3(0.0f, 0.52f, 0.0f));
  const uint32_t hovering = addBox(w, Vec3(3.0f, 0.5f + 0.5f * skin, 0.0f));
  for (int s = 0; s < 60; ++s) w.step();
  EXPECT_LE(w.bodies().xf[dropped].p.y(), 0.5f + 1e-5f);
  EXPECT_GT(w.bodies().xf[hovering].p.y(), 0.5f);
  w.bodies().v[hovering] = Vec3(0.0f, 0.5f, 0.0f);
  const float y = boxHeightAfter(w, hovering, 120);
  EXPECT_LE(y, 0.5f + 1e-5f);
}

TEST(ContactSkin, ZeroSkinClosesEveryGap) {
  WorldSettings ws = skinSettings();
  ws.contact.skin = 0.0f;
  World w(ws);
  addGround(w);
  const uint32_t box = addBox(w, Vec3(0.0f, 0.5f + 0.0005f, 0.0f));
  EXPECT_LE(boxHeightAfter(w, box, 60), 0.5f + 1e-5f);
}

}  // namespace
}  // namespace haif::test
