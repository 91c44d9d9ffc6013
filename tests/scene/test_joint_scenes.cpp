// The "joints" list of scene files: references by name, index and "world", every joint type, the
// World built from them, and one-line errors pointing at the offending value.
#include "scene/build_world.h"
#include "scene/scene_validate.h"
#include "scene_test_util.h"

namespace haif::test {
namespace {

// Three boxes in a row (a, b dynamic; post static) and the given joints.
std::string scene(const std::string& joints) {
  return "{\n  \"bodies\": [\n"
         "    {\"name\": \"a\", \"shape\": {\"type\": \"box\"}, \"position\": [0, 5, 0]},\n"
         "    {\"name\": \"b\", \"shape\": {\"type\": \"box\"}, \"position\": [1, 5, 0], \"orientation\": {\"euler_deg\": [0, 90, 0]}},\n"
         "    {\"name\": \"post\", \"type\": \"static\", \"shape\": {\"type\": \"box\"}, \"position\": [3, 5, 0]}\n"
         "  ],\n  \"joints\": [\n    " + joints + "\n  ]\n}\n";
}

TEST(JointScenes, EveryTypeParsesAndBuilds) {
  const SceneDesc s = parseOk(scene(
      R"({"type": "ball", "body_a": "world", "body_b": "a", "anchor": [-0.5, 5.5, 0]},
    {"type": "hinge", "body_a": 0, "body_b": 1, "anchor": [0.5, 5, 0], "axis": [0, 0, 1], "limits_deg": [-45, 30], "motor": {"speed": 1, "max_force": 20}},
    {"type": "fixed", "body_a": "a", "body_b": "post", "anchor": [2, 5, 0], "break_force": 500},
    {"type": "distance", "body_a": "b", "body_b": "post", "anchor_a": [1, 5.5, 0], "anchor_b": [3, 5.5, 0], "min": 1.5},
    {"type": "rope", "body_b": "b", "local_anchor_a": [1, 9, 0], "local_anchor_b": [0, 0.5, 0], "length": 4},
    {"type": "slider", "body_a": "post", "body_b": "b", "anchor": [1, 5, 0], "local_axis": [1, 0, 0], "limits": [-1, 0.5], "servo": {"keys": [[0, 0], [1, 0.4]], "max_force": 100, "loop": true}},
    {"name": "shoulder", "type": "cone_twist", "body_a": "a", "body_b": "b", "anchor": [0.5, 5, 0], "axis": [1, 0, 0], "swing_deg": 60, "twist_deg": [-20, 20], "collide": true})"));
  ASSERT_EQ(s.joints.size(), 7u);
  EXPECT_EQ(s.joints[0].bodyA, -1);
  EXPECT_EQ(s.joints[0].bodyB, 0);
  EXPECT_NEAR(s.joints[1].params.lower, -45.0f * kPi / 180.0f, 1e-6f);
  EXPECT_TRUE(s.joints[1].params.motorEnabled);
  EXPECT_FLOAT_EQ(s.joints[2].params.breakForce, 500.0f);
  EXPECT_FLOAT_EQ(s.joints[3].params.minDistance, 1.5f);
  EXPECT_LT(s.joints[3].params.maxDistance, 0.0f) << "unset: the initial distance";
  EXPECT_TRUE(s.joints[4].localAnchors);
  EXPECT_EQ(s.joints[5].params.servo.size(), 2u);
  EXPECT_TRUE(s.joints[5].localAxis);
  EXPECT_EQ(s.joints[6].name, "shoulder");
  EXPECT_NEAR(s.joints[6].params.swingLimit, kPi / 3.0f, 1e-6f);
  EXPECT_TRUE(s.joints[6].params.collideConnected);

  World w(s.settings.world);
  std::string error;
  ASSERT_TRUE(buildWorld(s, w, error)) << error;
  ASSERT_EQ(w.jointCount(), 7u);
  for (uint32_t j = 0; j < w.jointCount(); ++j) {
    if (j == 4) continue;  // the rope starts slack
    EXPECT_LT(w.jointError(j).linear, 1e-5f) << "joint " << j << " should start satisfied";
  }
  EXPECT_NEAR(w.joint(3).def.maxDistance, 2.0f, 1e-5f) << "max from the initial distance";
  EXPECT_NEAR(w.joint(3).def.minDistance, 1.5f, 1e-5f);
  EXPECT_FLOAT_EQ(w.joint(4).def.maxDistance, 4.0f);
  EXPECT_NEAR((w.bodies().xf[1].apply(w.joint(4).def.localAnchorB) - Vec3(1.0f, 5.5f, 0.0f)).norm(), 0.0f, 1e-5f)
      << "local anchors are in the body frame: b is turned 90 degrees about y";
  EXPECT_EQ(w.joint(0).def.bodyA, kWorldBody);
  for (int i = 0; i < 30; ++i) w.step();
  EXPECT_TRUE(isFinite(w.bodies().xf[1].p));
}

TEST(JointScenes, BadReferencesPointAtTheValue) {
  EXPECT_ERROR(scene(R"({"type": "ball", "body_a": "world", "body_b": "aa", "anchor": [0, 0, 0]})"), "\"aa\"",
                     "joints[0].body_b: no body is named 'aa' (did you mean 'a'?)");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_a": 7, "body_b": "a", "anchor": [0, 0, 0]})"), "7",
                     "joints[0].body_a: must be in [0, 2] (got 7)");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_a": "a", "body_b": 0, "anchor": [0, 0, 0]})"), "0, \"anchor",
                     "joints[0].body_b: a joint needs two different bodies");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_a": "world", "body_b": "post", "anchor": [0, 0, 0]})"), "\"post\", \"anchor",
                     "joints[0].body_b: a joint needs a dynamic body (body_a is the world, body_b is static 'post')");
  EXPECT_ERROR(scene(R"({"type": "ball", "anchor": [0, 0, 0]})"), "{\"type\": \"ball\"",
                     "joints[0]: missing required key 'body_b'");
}

TEST(JointScenes, BadParametersPointAtTheValue) {
  EXPECT_ERROR(scene(R"({"type": "hnge", "body_b": "a", "anchor": [0, 0, 0]})"), "\"hnge\"",
                     "joints[0].type: unknown joint type 'hnge' (did you mean 'hinge'?)");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_b": "a", "anchor": [0, 0, 0], "axis": [1, 0, 0]})"), "\"axis\"",
                     "joints[0].axis: unknown key");
  EXPECT_ERROR(scene(R"({"type": "hinge", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 0]})"),
                     "[0, 0, 0]}", "joints[0].axis: must not be the zero vector");
  EXPECT_ERROR(scene(R"({"type": "hinge", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 1], "limits_deg": [30, -30]})"),
                     "-30]", "joints[0].limits_deg[1]: upper must be >= lower (30)");
  EXPECT_ERROR(scene(R"({"type": "hinge", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 1], "limits_deg": [-200, 30]})"),
                     "-200", "joints[0].limits_deg[0]: must be within +-180 degrees (got -200)");
  EXPECT_ERROR(scene(R"({"type": "hinge", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 1], "motor": {"speed": 1}})"),
                     "{\"speed\"", "joints[0].motor: missing required key 'max_force'");
  EXPECT_ERROR(scene(R"({"type": "hinge", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 1], "motor": {"speed": 1, "max_force": 2}, "servo": {"keys": [[0, 0]], "max_force": 2}})"),
                     "\"servo\"", "joints[0].servo: give either a motor (constant speed) or a servo (trajectory), not both");
  EXPECT_ERROR(scene(R"({"type": "slider", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 0, 1], "servo": {"keys": [[0, 0], [0, 1]], "max_force": 2}})"),
                     "0, 1]]", "joints[0].servo.keys[1][0]: times must increase (previous key at 0 s)");
  EXPECT_ERROR(scene(R"({"type": "distance", "body_b": "a", "anchor_a": [0, 9, 0], "anchor_b": [0, 5, 0], "min": 3, "max": 2})"),
                     "2}", "joints[0].max: must be >= min (3)");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_b": "a", "anchor": [0, 0, 0], "local_anchor_a": [0, 0, 0]})"),
                     "\"local_anchor_a\"", "joints[0].local_anchor_a: give world anchors or local anchors, not both");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_b": "a"})"), "{\"type\": \"ball\"",
                     "joints[0]: missing required key 'anchor'");
  EXPECT_ERROR(scene(R"({"type": "cone_twist", "body_b": "a", "anchor": [0, 0, 0], "axis": [0, 1, 0], "swing_deg": 0})"),
                     "0}", "joints[0].swing_deg: must be > 0 (got 0)");
  EXPECT_ERROR(scene(R"({"type": "ball", "body_b": "a", "anchor": [0, 0, 0], "break_force": -1})"), "-1",
                     "joints[0].break_force: must be > 0 (got -1)");
}

TEST(JointScenes, AmbiguousNamesAreRefused) {
  const std::string text =
      "{\n  \"bodies\": [\n    {\"name\": \"x\", \"shape\": {\"type\": \"box\"}},\n"
      "    {\"name\": \"x\", \"shape\": {\"type\": \"box\"}, \"position\": [2, 0, 0]}\n  ],\n"
      "  \"joints\": [{\"type\": \"ball\", \"body_b\": \"x\", \"anchor\": [0, 1, 0]}]\n}\n";
  EXPECT_ERROR(text, "\"x\", \"anchor", "joints[0].body_b: body name 'x' is ambiguous: bodies[0] and bodies[1] both have it");
}

TEST(JointScenes, CoincidentDistanceAnchorsFailToBuild) {
  const SceneDesc s = parseOk(scene(R"({"type": "distance", "body_b": "a", "anchor_a": [0, 5, 0], "anchor_b": [0, 5, 0]})"));
  World w;
  std::string error;
  EXPECT_FALSE(buildWorld(s, w, error));
  EXPECT_EQ(error, "mem/test.json: joints[0]: the anchors coincide; a distance joint needs a length > 0");
}

TEST(JointScenes, ValidateCatchesCodeBuiltMistakes) {
  SceneDesc s = parseOk(scene(R"({"type": "ball", "body_b": "a", "anchor": [0, 5, 0]})"));
  s.joints[0].bodyB = 9;
  SceneIssue issue;
  EXPECT_FALSE(validateScene(s, issue));
  EXPECT_EQ(issue.describe(s), "joints[0].body_b: body index 9 is out of range");
}

}  // namespace
}  // namespace haif::test
