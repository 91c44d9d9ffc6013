// Compound shapes in scene files: parts read with their poses, the body placed at their centre of
// mass, joints anchored where the file says, and one clear error for each kind of mistake.
#include "scene_test_util.h"

#include "collision/compound.h"
#include "scene/build_world.h"

namespace haif::test {
namespace {

const char* kDumbbell = R"({
  "bodies": [
    {"name": "dumbbell", "position": [1, 2, 3], "shape": {"type": "compound", "parts": [
      {"shape": {"type": "sphere", "radius": 0.2}, "position": [0, 0, 0]},
      {"shape": {"type": "sphere", "radius": 0.2}, "position": [2, 0, 0]},
      {"shape": {"type": "box", "size": [2, 0.1, 0.1]}, "position": [1, 0, 0], "orientation": {"euler_deg": [0, 0, 0]}, "draw": false}
    ]}}
  ]
})";

TEST(CompoundScenes, PartsAreReadAndTheBodySitsAtTheirCentreOfMass) {
  const SceneDesc s = parseOk(kDumbbell);
  ASSERT_EQ(s.bodies.size(), 1u);
  const ShapeDesc& shape = s.bodies[0].shape;
  ASSERT_EQ(shape.type, ShapeType::Compound);
  ASSERT_EQ(shape.parts.size(), 3u);
  EXPECT_EQ(shape.parts[1].shape.type, ShapeType::Sphere);
  EXPECT_EQ(shape.parts[1].position, Vec3(2, 0, 0));
  EXPECT_TRUE(shape.parts[0].draw);
  EXPECT_FALSE(shape.parts[2].draw);
  World w;
  std::string error;
  ASSERT_TRUE(buildWorld(s, w, error)) << error;
  // Symmetric about x = 1 in the file's body frame: the centre of mass is at (1, 0, 0) from the origin.
  const Vec3 p = w.bodies().xf[0].p;
  EXPECT_NEAR(p.x(), 2.0f, 1e-5f);
  EXPECT_NEAR(p.y(), 2.0f, 1e-5f);
  EXPECT_NEAR(p.z(), 3.0f, 1e-5f);
  ASSERT_EQ(w.shape(0).type, ShapeType::Compound);
  const Aabb box = computeAabb(w.shape(0), w.bodies().xf[0]);
  EXPECT_NEAR(box.lo.x(), 0.8f, 1e-5f);
  EXPECT_NEAR(box.hi.x(), 3.2f, 1e-5f);
}

TEST(CompoundScenes, MistakesNameThePart) {
  auto compound = [](const std::string& parts) { return body("", R"({"type": "compound", "parts": )" + parts + "}"); };
  EXPECT_ERROR(compound("[]"), "[]", "bodies[0].shape.parts: a compound needs at least one part");
  EXPECT_ERROR(compound(R"([{"shape": {"type": "plane"}}])"), "\"plane\"",
               "bodies[0].shape.parts[0].shape.type: a compound's part cannot be a plane; use sphere, box, capsule or hull");
  EXPECT_ERROR(compound(R"([{"shape": {"type": "sphere"}}, {"shape": {"type": "compound", "parts": [{"shape": {"type": "box"}}]}}])"),
               "\"compound\", \"parts\": [{\"shape\": {\"type\": \"box",
               "bodies[0].shape.parts[1].shape.type: a compound's part cannot be a compound");
  EXPECT_ERROR(compound(R"([{"shape": {"type": "sphere", "radius": -1}}])"), "-1",
               "bodies[0].shape.parts[0].shape.radius: must be > 0");
  EXPECT_ERROR(compound(R"([{"shape": {"type": "sphere"}, "postion": [0, 0, 0]}])"), "\"postion\"",
               "bodies[0].shape.parts[0].postion: unknown key (did you mean 'position'?)");
  EXPECT_ERROR(compound(R"([{"position": [0, 0, 0]}])"), "{\"position\"", "bodies[0].shape.parts[0]: missing required key 'shape'");
}

}  // namespace
}  // namespace haif::test
