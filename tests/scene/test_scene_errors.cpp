// Bad scene input: each problem gives one line "FILE:LINE:COL: PLACE: what", pointing at the value.
#include "scene_test_util.h"

#include "scene/json_positions.h"

namespace haif::test {
namespace {

TEST(SceneErrors, SyntaxErrorReportsLineAndColumn) {
  const std::string text = "{\n  \"bodies\": [1,,2]\n}\n";
  const std::string e = parseError(text);
  EXPECT_EQ(e.rfind("mem/bad.json:2:16: syntax error: ", 0), 0u) << e;
  EXPECT_NE(e.find("unexpected ','"), std::string::npos) << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;

  const std::string unterminated = parseError("{\n  \"name\": \"x\"\n");
  EXPECT_NE(unterminated.find("mem/bad.json:3:1: syntax error: "), std::string::npos) << unterminated;
}

TEST(SceneErrors, MissingFile) {
  SceneDesc s;
  std::string error;
  EXPECT_FALSE(loadSceneFile("/nonexistent/dir/x.json", s, error));
  EXPECT_EQ(error, "/nonexistent/dir/x.json: cannot open scene file (No such file or directory)");
}

TEST(SceneErrors, TopLevelMustBeAnObject) {
  EXPECT_EQ(parseError("[1, 2]"), "mem/bad.json:1:1: scene: a scene file must hold one JSON object {...} (got an array of 2)");
}

TEST(SceneErrors, UnknownKeysSuggestTheClosestKnownOne) {
  const std::string top = "{\n  \"bodys\": []\n}";
  EXPECT_EQ(parseError(top), "mem/bad.json:2:3: bodys: unknown key (did you mean 'bodies'?)");
  EXPECT_ERROR(body(R"("positon": [0, 1, 0])"), "\"positon\"", "bodies[0].positon: unknown key (did you mean 'position'?)");
  EXPECT_ERROR(body("", R"({"type": "box", "radius": 1})"), "\"radius\"",
               "bodies[0].shape.radius: unknown key (known keys: type, half_extents, size)");
  EXPECT_ERROR(R"({"settings": {"dt": 0.01, "itrations": 5}})", "\"itrations\"",
               "settings.itrations: unknown key (did you mean 'iterations'?)");
}

// Keys and strings quoted back may hold escaped control characters: the message stays one line.
TEST(SceneErrors, QuotedKeysAndStringsWithNewlinesStayOnOneLine) {
  EXPECT_EQ(parseError(R"({"bo\ndies": []})"), R"(mem/bad.json:1:2: bo\ndies: unknown key (did you mean 'bodies'?))");
  const std::string type = parseError(body(R"("type": "dyn\u0001amic\tx\r")"));
  EXPECT_NE(type.find(R"(unknown body type 'dyn\u0001amic\tx\r')"), std::string::npos) << type;
  const std::string nested = parseError(R"({"bodies": [{"shape": {"type": "sphere"}, "a\nb": {"c\nd": 1}}]})");
  EXPECT_NE(nested.find(R"(bodies[0].a\nb: unknown key)"), std::string::npos) << nested;
  for (const std::string& e : {type, nested}) EXPECT_EQ(e.find_first_of("\n\r\t\x01"), std::string::npos) << e;
}

TEST(SceneErrors, CommentKeysAreIgnored) {
  EXPECT_EQ(parseOk(R"({"_comment": "hi", "bodies": [{"_note": 1, "shape": {"type": "sphere"}}]})").bodies.size(), 1u);
}

TEST(SceneErrors, DuplicateKey) {
  const std::string text = body(R"("mass": 1, "mass": 2)");
  EXPECT_ERROR(text, "\"mass\": 2", "duplicate key: 'mass' appears twice");
}

TEST(SceneErrors, UnknownShapeType) {
  EXPECT_ERROR(body("", R"({"type": "cube"})"), "\"cube\"",
               "bodies[0].shape.type: unknown shape type 'cube'; use sphere, box, capsule, hull, mesh, plane or compound");
  EXPECT_ERROR(body("", R"({"type": "shpere"})"), "\"shpere\"", "unknown shape type 'shpere' (did you mean 'sphere'?)");
  EXPECT_ERROR(body("", R"({"radius": 1})"), "{\"radius\"", "bodies[0].shape: missing required key 'type'");
}

TEST(SceneErrors, MissingShape) {
  const std::string text = "{\"bodies\": [\n  {\"position\": [0, 0, 0]}\n]}";
  EXPECT_ERROR(text, "{\"position\"", "bodies[0]: missing required key 'shape'");
}

TEST(SceneErrors, WrongValueTypes) {
  EXPECT_ERROR(body("", R"({"type": "sphere", "radius": "big"})"), "\"big\"",
               "bodies[0].shape.radius: must be a number (got string \"big\")");
  EXPECT_ERROR(body(R"("position": [0, 1])"), "[0, 1]", "bodies[0].position: must be an array of 3 numbers [x, y, z] (got an array of 2)");
  EXPECT_ERROR(body(R"("position": [0, true, 1])"), "true", "bodies[0].position[1]: must be a number (got true)");
  EXPECT_ERROR(R"({"settings": {"sleeping": "yes"}})", "\"yes\"", "settings.sleeping: must be true or false");
  EXPECT_ERROR(R"({"settings": {"iterations": 2.5}})", "2.5", "settings.iterations: must be an integer (got 2.5)");
  EXPECT_ERROR(R"({"bodies": {"a": 1}})", "{\"a\"", "bodies: must be an array [...] (got an object)");
  EXPECT_ERROR(body(R"("type": "dynamc")"), "\"dynamc\"", "bodies[0].type: unknown body type 'dynamc' (did you mean 'dynamic'?)");
}

TEST(SceneErrors, NanInfinityAndOverflow) {
  EXPECT_ERROR(body(R"("mass": "nan")"), "\"nan\"", "bodies[0].mass: must be a finite number (got string \"nan\"; NaN and infinity are not allowed)");
  EXPECT_ERROR(body(R"("velocity": [0, "-Infinity", 0])"), "\"-Inf", "bodies[0].velocity[1]: must be a finite number");
  EXPECT_ERROR(body(R"("position": [0, 1e999, 0])"), "1e999", "syntax error: number out of range");
  EXPECT_ERROR(body(R"("position": [0, -1e39, 0])"), "-1e39", "bodies[0].position[1]: number out of range (got -1e+39");
}

TEST(SceneErrors, MassRules) {
  const std::string text =
      "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"sphere\"}},\n    {\"shape\": {\"type\": \"sphere\"}},\n"
      "    {\"shape\": {\"type\": \"sphere\"}},\n    {\"shape\": {\"type\": \"box\"}, \"mass\": -2}\n  ]\n}\n";
  EXPECT_EQ(parseError(text), at(text, "-2") + "bodies[3].mass: must be > 0 for a dynamic body (got -2)");
  EXPECT_ERROR(body(R"("mass": 0)"), "0}", "bodies[0].mass: must be > 0 for a dynamic body (got 0)");
  EXPECT_ERROR(body(R"("type": "static", "mass": 5)"), "5}", "bodies[0].mass: only dynamic bodies have a mass (this body is static)");
}

TEST(SceneErrors, NonPositiveSizes) {
  EXPECT_ERROR(body("", R"({"type": "sphere", "radius": 0})"), "0}", "bodies[0].shape.radius: must be > 0 (got 0)");
  EXPECT_ERROR(body("", R"({"type": "box", "half_extents": [1, -1, 1]})"), "-1", "bodies[0].shape.half_extents[1]: must be > 0 (got -1)");
  EXPECT_ERROR(body("", R"({"type": "box", "size": -3})"), "-3", "bodies[0].shape.size: must be > 0 (got -3)");
  EXPECT_ERROR(body("", R"({"type": "capsule", "half_height": -0.5})"), "-0.5", "bodies[0].shape.half_height: must be >= 0 (got -0.5)");
}

TEST(SceneErrors, SettingsRanges) {
  EXPECT_ERROR(R"({"settings": {"dt": 0}})", "0}", "settings.dt: must be > 0 (got 0)");
  EXPECT_ERROR(R"({"settings": {"dt": -0.01}})", "-0.01", "settings.dt: must be > 0 (got -0.01)");
  EXPECT_ERROR(R"({"settings": {"iterations": 0}})", "0}", "settings.iterations: must be in [1, 100000] (got 0)");
  EXPECT_ERROR(R"({"settings": {"omega": 2}})", "2}", "settings.omega: must be in [1, 2) (got 2)");
  EXPECT_ERROR(R"({"settings": {"omega": 0.9}})", "0.9", "settings.omega: must be in [1, 2) (got 0.9)");
  EXPECT_ERROR(R"({"settings": {"beta": 1.5}})", "1.5", "settings.beta: must be in [0, 1] (got 1.5)");
  EXPECT_ERROR(R"({"settings": {"momentum_layers": -2}})", "-2", "settings.momentum_layers: must be >= 0 (got -2)");
  EXPECT_ERROR(R"({"settings": {"deep_layers_per_sweep": -3}})", "-3", "settings.deep_layers_per_sweep: must be >= 0 (got -3)");
  EXPECT_ERROR(R"({"settings": {"moving_layers_per_sweep": -1}})", "-1", "settings.moving_layers_per_sweep: must be >= 0 (got -1)");
  EXPECT_ERROR(R"({"settings": {"tolerance_thickness": -0.1}})", "-0.1", "settings.tolerance_thickness: must be >= 0 (got -0.1)");
  EXPECT_ERROR(R"({"settings": {"rest_damping": 2}})", "2}", "settings.rest_damping: must be in [0, 1] (got 2; 0 turns it off)");
  EXPECT_ERROR(R"({"settings": {"frames": -1}})", "-1", "settings.frames: must be in [1, 100000000] (got -1)");
  EXPECT_ERROR(R"({"camera": {"eye": [0, 1, 0], "target": [0, 1, 0]}})", "[0, 1, 0]}", "camera.target: must differ from eye");
  EXPECT_ERROR(R"({"camera": {"fov_deg": 180}})", "180", "camera.fov_deg: must be in (0, 180) degrees (got 180)");
}

TEST(SceneErrors, MaterialRules) {
  EXPECT_ERROR(R"({"materials": {"ice": {"friction": -0.1}}})", "-0.1", "materials.ice.friction: must be >= 0 (got -0.1)");
  EXPECT_ERROR(R"({"materials": {"ice": {"restitution": -1}}})", "-1", "materials.ice.restitution: must be in [0, 1] (got -1)");
  EXPECT_ERROR(R"({"materials": {"ice": {"density": 0}}})", "0}", "materials.ice.density: must be > 0 (got 0)");
  EXPECT_ERROR(R"({"materials": {"felt": {"rolling_resistance": -0.01}}})", "-0.01",
               "materials.felt.rolling_resistance: must be >= 0 (got -0.01)");
  EXPECT_ERROR(R"({"materials": {"ice": {"frict": 1}}})", "\"frict\"", "materials.ice.frict: unknown key (did you mean 'friction'?)");
  const std::string text = "{\"materials\": {\"steel\": {}},\n \"bodies\": [{\"shape\": {\"type\": \"box\"}, \"material\": \"stel\"}]}";
  EXPECT_ERROR(text, "\"stel\"", "bodies[0].material: unknown material 'stel' (did you mean 'steel'?)");
  EXPECT_ERROR(body(R"("material": "zzz")"), "\"zzz\"", "bodies[0].material: unknown material 'zzz' (defined: default)");
}

TEST(SceneErrors, StaticOnlyShapesOnMovingBodies) {
  EXPECT_ERROR(body("", R"({"type": "plane"})"), "\"plane\"",
               "bodies[0].shape.type: shape 'plane' is static-only; a dynamic body needs sphere, box, capsule or hull");
  EXPECT_ERROR(body(R"("type": "kinematic")", R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,0,1]], "indices": [0,1,2]})"),
               "\"mesh\"", "shape 'mesh' is static-only; a kinematic body");
  EXPECT_ERROR(body(R"("type": "static", "velocity": [1, 0, 0])"), "[1, 0, 0]",
               "bodies[0].velocity: a static body cannot move (make it \"kinematic\"");
}

TEST(SceneErrors, HullAndMeshData) {
  EXPECT_ERROR(body("", R"({"type": "hull", "points": [[0,0,0],[1,0,0],[0,1,0]]})"), "[[0,0,0]",
               "bodies[0].shape.points: a hull needs at least 4 points (got 3)");
  EXPECT_ERROR(body("", R"({"type": "hull", "points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]})"), "[[0,0,0]",
               "bodies[0].shape.points: all hull points lie in one plane");
  EXPECT_ERROR(body("", R"({"type": "hull"})"), "{\"type\": \"hull\"", "bodies[0].shape: a hull needs 'points'");
  EXPECT_ERROR(body(R"("type": "static")", R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,0,1]], "indices": [0,1,3]})"), "3]",
               "bodies[0].shape.indices[2]: must be in [0, 2] (got 3)");
  EXPECT_ERROR(body(R"("type": "static")", R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,0,1]], "indices": [0,1]})"), "[0,1]",
               "bodies[0].shape.indices: must hold 3 vertex indices per triangle (got 2 indices)");
  EXPECT_ERROR(body(R"("orientation": [0, 0, 0, 0])"), "[0, 0, 0, 0]", "bodies[0].orientation: must not be the zero quaternion");
  EXPECT_ERROR(body(R"("orientation": {"euler": [0, 0, 0]})"), "\"euler\"", "bodies[0].orientation.euler: unknown key (did you mean 'euler_deg'?)");
}

TEST(SceneErrors, MissingAssetNamesTheFieldAndTheFile) {
  EXPECT_ERROR(body(R"("type": "static")", R"({"type": "mesh", "asset": "assets/nothere.obj"})"), "\"assets/nothere.obj\"",
               "bodies[0].shape.asset: cannot open asset file 'mem/assets/nothere.obj' (No such file or directory)");
}

TEST(SceneErrors, GeneratorParameters) {
  EXPECT_ERROR(R"({"generators": [{"type": "ground"}, {"type": "stacks", "count": 0}]})", "0}",
               "generators[1].count: must be in [1, 1000000] (got 0)");
  EXPECT_ERROR(R"({"generators": [{"type": "stacks"}]})", "{\"type\": \"stacks\"", "generators[0]: missing required key 'count'");
  EXPECT_ERROR(R"({"generators": [{"type": "stacks", "count": -5}]})", "-5", "generators[0].count: must be in [1, 1000000] (got -5)");
  EXPECT_ERROR(R"({"generators": [{"type": "stacks", "count": 10, "spacing": 0.5}]})", "0.5",
               "generators[0].spacing: stacks would overlap: spacing 0.5 is less than the box width 1");
  EXPECT_ERROR(R"({"generators": [{"type": "many_pyramids", "rows": 200, "cols": 200, "base": 10}]})", "10}",
               "generators[0].base: would make 2200000 bodies; a scene holds at most 1000000");
  EXPECT_ERROR(R"({"generators": [{"type": "pyramid"}]})", "\"pyramid\"",
               "generators[0].type: unknown generator type 'pyramid' (did you mean 'pyramid_2d'?)");
  EXPECT_ERROR(R"({"generators": [{"type": "random_pile", "count": 100, "min": [0, 0, 0], "max": [2, 2, 2]}]})", "100",
               "generators[0].count: the region holds at most 8 bodies of size up to 0.4 (got 100)");
  EXPECT_ERROR(R"({"generators": [{"type": "random_pile", "count": 1, "min": [0, 0, 0], "max": [2, -2, 2]}]})", "-2",
               "generators[0].max[1]: must be greater than min (0)");
  EXPECT_ERROR(R"({"generators": [{"type": "domino_run", "count": 5, "spacing": 0.1}]})", "0.1",
               "generators[0].spacing: dominoes would overlap");
  EXPECT_ERROR(R"({"generators": [{"type": "grid", "counts": [2, 1, 1], "spacing": 0.5, "shape": {"type": "sphere"}}]})", "0.5",
               "generators[0].spacing: bodies would overlap: spacing along x is 0.5 but the shape is 1 wide");
  EXPECT_ERROR(R"({"generators": [{"type": "grid", "counts": [1, 1, 1], "spacing": 1, "shape": {"type": "plane"}}]})", "\"plane\"",
               "generators[0].shape.type: shape 'plane' is static-only");
  EXPECT_ERROR(R"({"generators": [{"type": "wall", "rows": 2, "cols": 3, "bond": "runing"}]})", "\"runing\"",
               "generators[0].bond: unknown bond 'runing' (did you mean 'running'?)");
  EXPECT_ERROR(R"({"generators": [{"type": "stack", "count": 3, "mass": -1}]})", "-1",
               "generators[0].mass: must be > 0 for a dynamic body (got -1)");
}

TEST(SceneErrors, FinalValidationPointsAtTheGeneratorThatMadeTheBody) {
  // Every parameter is fine on its own, but 1e38 * 9 overflows a float position.
  const std::string text = "{\"generators\": [\n  {\"type\": \"grid\", \"counts\": [10, 1, 1], \"spacing\": 1e38, \"shape\": {\"type\": \"sphere\"}}\n]}";
  EXPECT_ERROR(text, "{\"type\": \"grid\"", "generators[0] #4.position: must be finite");
}

TEST(SceneErrors, BodiesOutsideTheSupportedSizesAndMassesAreRefused) {
  EXPECT_ERROR(body("", R"({"type": "sphere", "radius": 1e-4})"), "{\"type\": \"sphere\"",
               "bodies[0].shape: a moving body of 0.0002 m is outside the sizes the engine supports (0.001 to 1000 m)");
  EXPECT_ERROR(body(R"("type": "kinematic")", R"({"type": "box", "half_extents": [600, 1, 1]})"), "{\"type\": \"box\"",
               "bodies[0].shape: a moving body of 1200 m is outside");
  EXPECT_ERROR(body(R"("mass": 1e13)"), "1e13", "bodies[0].mass: a mass of 1e+13 kg is outside the masses the engine supports");
  // From density: a 2 mm sphere of 1e-6 kg/m^3 weighs 4e-15 kg.
  const std::string light = "{\n  \"materials\": {\"fog\": {\"density\": 1e-6}},\n  \"bodies\": [\n    {\"shape\": {\"type\": "
                            "\"sphere\", \"radius\": 0.001}, \"material\": \"fog\"}\n  ]\n}\n";
  EXPECT_NE(parseError(light).find("bodies[0].mass: a mass of 4.188791e-15 kg (density x volume) is outside"), std::string::npos)
      << parseError(light);
  // A static ground may be larger than any moving body.
  EXPECT_EQ(parseOk(body(R"("type": "static")", R"({"type": "box", "half_extents": [5000, 1, 5000]})")).bodies.size(), 1u);
}

TEST(SceneErrors, AJointOverTheSupportedMassRatioIsRefused) {
  const std::string text =
      "{\n  \"bodies\": [\n    {\"name\": \"a\", \"shape\": {\"type\": \"sphere\"}, \"mass\": 1},\n"
      "    {\"name\": \"b\", \"shape\": {\"type\": \"sphere\"}, \"position\": [0, -1, 0], \"mass\": 1e6}\n  ],\n"
      "  \"joints\": [{\"type\": \"ball\", \"body_a\": \"a\", \"body_b\": \"b\", \"anchor\": [0, -0.5, 0]}]\n}\n";
  EXPECT_ERROR(text, "\"b\", \"anchor\"", "joints[0].body_b: joins bodies of 1 and 1000000 kg: a mass ratio of 1:1000000, above the 1:100000");
}

// 20,000 nested '[' overflowed the stack of the recursive position scanner (a segfault), also where
// nothing reads the value, inside a comment.
TEST(SceneErrors, DeepNestingIsOneSyntaxErrorNotACrash) {
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  const std::string text = "{\"_comment\": " + deep + ", \"bodies\": []}";
  const std::string e = parseError(text);
  // The object is level 1, so the 256th bracket opens level 257: column 14 + 255.
  EXPECT_EQ(e, "mem/bad.json:1:269: syntax error: nested deeper than 256 levels of [ and {");
  EXPECT_EQ(parseError("{\"bodies\": " + deep + "}").rfind("mem/bad.json:1:", 0), 0u);
  // As deep as allowed is fine.
  const std::string ok = "{\"_comment\": " + std::string(kMaxJsonDepth - 1, '[') + std::string(kMaxJsonDepth - 1, ']') + "}";
  EXPECT_TRUE(parseOk(ok).bodies.empty());
}

TEST(SceneErrors, ATinyNumberIsReportedAsWritten) {
  // 1e-300 rounds to 0 as a float: the message used to say "(got 0)".
  EXPECT_ERROR(R"({"settings": {"dt": 1e-300}})", "1e-300",
               "settings.dt: must be > 0 (got 1e-300, which is 0 in the engine's 32-bit floats)");
  EXPECT_ERROR(R"({"settings": {"dt": -2.5e-7}})", "-2.5e-7", "settings.dt: must be > 0 (got -2.5e-07)");
}

TEST(SceneErrors, AMeshOfOnlyDegenerateTrianglesIsRefused) {
  // Three points on a line, and a triangle that repeats a corner: no area anywhere.
  EXPECT_ERROR(body(R"("type": "static")", R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[2,0,0]], "indices": [0,1,2, 0,0,1]})"),
               "[0,1,2", "bodies[0].shape.indices: all 2 triangles are degenerate (zero area)");
  // One good triangle among degenerate ones is a mesh.
  EXPECT_EQ(parseOk(body(R"("type": "static")", R"({"type": "mesh", "vertices": [[0,0,0],[1,0,0],[2,0,0],[0,0,1]], "indices": [0,1,2, 0,1,3]})"))
                .bodies.size(),
            1u);
}

TEST(SceneErrors, AbsurdSpeedsAreRefusedWithTheBound) {
  EXPECT_ERROR(body(R"("velocity": [1e20, 0, 0])"), "[1e20",
               "bodies[0].velocity: a speed of 1e+20 m/s is outside the speeds the engine supports (up to 10000 m/s)");
  EXPECT_ERROR(body(R"("type": "kinematic", "angular_velocity": [0, 0, -3e5])"), "[0, 0, -3e5]",
               "bodies[0].angular_velocity: a spin of 300000 rad/s is outside the spins the engine supports (up to 10000 rad/s)");
  EXPECT_EQ(parseOk(body(R"("velocity": [300, 0, 0])")).bodies.size(), 1u);  // a bullet is fine
}

TEST(SceneErrors, ASceneNameMustNotBeAPath) {
  EXPECT_ERROR(R"({"name": "../../../x"})", "\"../../../x\"",
               "name: must be a plain name, not a path (got '../../../x') (the name is the default output folder");
  EXPECT_ERROR(R"({"name": ".."})", "\"..\"", "name: must be a plain name, not a path");
  EXPECT_ERROR(R"({"name": ""})", "\"\"", "name: must not be empty");
  EXPECT_EQ(parseOk(R"({"name": "tower collapse, take 2"})").name, "tower collapse, take 2");
}

TEST(SceneErrors, AFolderGivenAsTheSceneIsNamedAsSuch) {
  SceneDesc s;
  std::string error;
  EXPECT_FALSE(loadSceneFile(sourceDir() + "/scenes", s, error));
  EXPECT_EQ(error, sourceDir() + "/scenes: is a directory, not a scene file");
}

}  // namespace
}  // namespace haif::test
