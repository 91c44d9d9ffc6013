// Small bodies: the contact tolerances (slop, contact margin, broad-phase margins, manifold reuse)
// are lengths sized for bodies of centimetres and up; a body thinner than
// WorldSettings::toleranceThickness scales them down with its thickness (haif/small_bodies.h). A cup
// of 6-10 mm beads rested 3-4 mm deep in each other (the 5 mm slop) and kept 100 pairs a bead: 400
// beads took 6-8 ms a step, over a 4 ms budget at any iteration count.
#include "scene_test_util.h"

#include "haif/small_bodies.h"
#include "haif/world.h"
#include "scene/build_world.h"

#include <algorithm>
#include <string>

namespace haif::test {
namespace {

// `count` beads (spheres and boxes, bounding radius 3-5 mm) poured from up to 15 cm into a 10 cm
// cup; sleeping off, so every step collides and solves all of them.
std::string beadCup(int count) {
  return R"({"settings": {"sleeping": false},
    "generators": [{"type": "ground"},
      {"type": "random_pile", "count": )" +
         std::to_string(count) + R"(, "min": [-0.045, 0.01, -0.045], "max": [0.045, 0.15, 0.045],
       "shapes": ["sphere", "box"], "size": [0.003, 0.005], "seed": 7}],
    "bodies": [
      {"type": "static", "shape": {"type": "box", "half_extents": [0.06, 0.03, 0.005]}, "position": [0, 0.03, 0.055]},
      {"type": "static", "shape": {"type": "box", "half_extents": [0.06, 0.03, 0.005]}, "position": [0, 0.03, -0.055]},
      {"type": "static", "shape": {"type": "box", "half_extents": [0.005, 0.03, 0.06]}, "position": [0.055, 0.03, 0]},
      {"type": "static", "shape": {"type": "box", "half_extents": [0.005, 0.03, 0.06]}, "position": [-0.055, 0.03, 0]}]})";
}

struct CupState {
  double pairsPerBody = 0.0;  // pairs the broad phase keeps, over the dynamic bodies
  float restingDepth = 0.0f;  // deepest contact over the last 100 steps (m)
  uint64_t hash = 0;
};

CupState pourBeads(int count, float toleranceThickness, int threads = 1) {
  const SceneDesc scene = parseOk(beadCup(count));
  WorldSettings ws = scene.settings.world;
  ws.toleranceThickness = toleranceThickness;
  ws.threads = threads;
  World w(ws);
  std::string error;
  EXPECT_TRUE(buildWorld(scene, w, error)) << error;
  CupState s;
  for (int step = 0; step < 400; ++step) {
    w.step();
    if (step < 300) continue;
    for (const Contact& c : w.contacts()) s.restingDepth = std::max(s.restingDepth, c.manifold.deepest());
  }
  s.pairsPerBody = double(w.contacts().size()) / double(count);
  s.hash = w.stateHash();
  return s;
}

// Settled, no two beads overlap past a tenth of the thinnest one's size (the scaled slop and the
// push-out's reach), where the unscaled 5 mm slop left them up to 4 mm deep; and the broad phase
// keeps a few pairs a bead, not every bead within 10 cm.
TEST(SmallBodies, ABeadCupRestsShallowWithFewPairs) {
  const CupState scaled = pourBeads(200, WorldSettings{}.toleranceThickness);
  const CupState unscaled = pourBeads(200, 0.0f);
  EXPECT_LT(scaled.restingDepth, 0.001f);  // 0.5 mm
  EXPECT_LT(scaled.pairsPerBody, 50.0);  // 33 (fat boxes reach twice a bead's size)
  // The control: the unscaled tolerances fail both, so the test measures the rule.
  EXPECT_GT(unscaled.restingDepth, 0.002f);  // 3.3 mm
  EXPECT_GT(unscaled.pairsPerBody, 70.0);  // 105
}

// Bodies at least the threshold thick keep every tolerance as set: the same state to the bit.
TEST(SmallBodies, OrdinaryBodiesKeepTheirTolerances) {
  const SceneDesc scene = parseOk(R"({"generators": [{"type": "ground"},
      {"type": "random_pile", "count": 150, "min": [-2, 1, -2], "max": [2, 5, 2], "size": [0.04, 0.3], "seed": 3}]})");
  float thinnest = 1e30f;
  auto run = [&](float toleranceThickness) {
    WorldSettings ws = scene.settings.world;
    ws.toleranceThickness = toleranceThickness;
    World w(ws);
    std::string error;
    EXPECT_TRUE(buildWorld(scene, w, error)) << error;
    for (uint32_t i = 0; i < w.bodyCount(); ++i)
      if (w.bodies().isDynamic(i)) thinnest = std::min(thinnest, smallestExtent(w.shape(i)));
    for (int step = 0; step < 150; ++step) w.step();
    return w.stateHash();
  };
  const uint64_t unscaled = run(0.0f);
  ASSERT_LT(thinnest, 0.1f);
  // No pair is scaled with the threshold at the thinnest body; above it, that body's pairs are.
  EXPECT_EQ(run(thinnest), unscaled);
  EXPECT_NE(run(1.5f * thinnest), unscaled);
}

TEST(SmallBodies, SameStateForAnyThreadCount) {
  const uint64_t one = pourBeads(120, WorldSettings{}.toleranceThickness, 1).hash;
  EXPECT_EQ(pourBeads(120, WorldSettings{}.toleranceThickness, 2).hash, one);
  EXPECT_EQ(pourBeads(120, WorldSettings{}.toleranceThickness, 4).hash, one);
}

// The factor is the body's smallest extent over the threshold, 1 from the threshold up and with the
// rule off, and never 0.
TEST(SmallBodies, TheFactorFollowsTheThinnestExtent) {
  EXPECT_FLOAT_EQ(toleranceScale(Shape::box(Vec3(0.5f, 0.005f, 0.5f)), 0.05f), 0.2f);  // a 1 cm plate
  EXPECT_FLOAT_EQ(toleranceScale(Shape::sphere(0.01f), 0.05f), 0.4f);
  EXPECT_FLOAT_EQ(toleranceScale(Shape::capsule(0.1f, 0.5f), 0.05f), 1.0f);
  EXPECT_FLOAT_EQ(toleranceScale(Shape::sphere(0.001f), 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(toleranceScale(Shape::sphere(1e-5f), 0.05f), kMinToleranceScale);
}

}  // namespace
}  // namespace haif::test
