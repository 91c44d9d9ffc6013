// Deep overlaps at the start of a run: found from the first step's contacts, deepest first, described
// with the scene's body names and places.
#include "tools/start_overlaps.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

BodyDef boxAt(float x, float y, BodyKind kind = BodyKind::Dynamic, Vec3 half = Vec3(0.5f, 0.5f, 0.5f)) {
  BodyDef d;
  d.kind = kind;
  d.shape = Shape::box(half);
  d.xf.p = Vec3(x, y, 0.0f);
  return d;
}

// Ground (0), a box resting 5 mm into it (1), and two pairs of boxes through each other by 0.1 m
// (2, 3) and 0.3 m (4, 5), high in the air.
struct OverlapWorld {
  World world;
  OverlapWorld() {
    world.addBody(boxAt(0.0f, -1.0f, BodyKind::Static, Vec3(50.0f, 1.0f, 50.0f)));
    world.addBody(boxAt(-6.0f, 0.495f));
    world.addBody(boxAt(0.0f, 5.0f));
    world.addBody(boxAt(0.9f, 5.0f));
    world.addBody(boxAt(6.0f, 5.0f));
    world.addBody(boxAt(6.7f, 5.0f));
    world.step();
  }
};

TEST(StartOverlaps, DeepPairsOnlyDeepestFirst) {
  OverlapWorld w;
  const std::vector<StartOverlap> found = deepContacts(w.world, kStartOverlapWarningDepth);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].a, 4u);
  EXPECT_EQ(found[0].b, 5u);
  EXPECT_NEAR(found[0].depth, 0.3f, 1e-3f);
  EXPECT_EQ(found[1].a, 2u);
  EXPECT_EQ(found[1].b, 3u);
  EXPECT_NEAR(found[1].depth, 0.1f, 1e-3f);
  // With a lower threshold the resting box's 5 mm shows too.
  EXPECT_EQ(deepContacts(w.world, 0.004f).size(), 3u);
}

TEST(StartOverlaps, DescriptionNamesBodiesAndCapsTheList) {
  OverlapWorld w;
  SceneDesc scene;
  scene.sourcePath = "scenes/x.json";
  for (int i = 0; i < 6; ++i) {
    BodyDesc b;
    b.where = "bodies[" + std::to_string(i) + "]";
    if (i == 4) b.name = "card";
    scene.bodies.push_back(b);
  }
  const std::vector<StartOverlap> found = deepContacts(w.world, kStartOverlapWarningDepth);
  const std::string all = describeStartOverlaps(scene, found, 5);
  EXPECT_EQ(all.find("warning: scenes/x.json: bodies[4] \"card\" and bodies[5] overlap by 0.300 m at the start"), 0u)
      << all;
  EXPECT_NE(all.find("\nwarning: scenes/x.json: bodies[2] and bodies[3] overlap by 0.100 m"), std::string::npos) << all;
  const std::string capped = describeStartOverlaps(scene, found, 1);
  EXPECT_EQ(capped.find("bodies[2] and bodies[3]"), std::string::npos) << capped;
  EXPECT_NE(capped.find("and 1 more pairs overlap by more than 20 mm"), std::string::npos) << capped;
  EXPECT_TRUE(describeStartOverlaps(scene, {}, 5).empty());
}

}  // namespace
}  // namespace haif
