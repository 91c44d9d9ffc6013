// Every scene file shipped in scenes/ loads and is sensible; defaults and basic keys are applied.
#include "scene_test_util.h"

#include "scene/build_world.h"
#include "scene/scene_validate.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace haif::test {
namespace {

TEST(SceneFiles, EveryShippedSceneLoadsAndValidates) {
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(sourceDir() + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    if (entry.path().filename() == "reel.json") continue;  // the demo reel's playlist (docs/reel_format.md)
    if (entry.path().parent_path().filename() == "suites") continue;  // haif suite files (docs/suites.md)
    ++files;
    SceneDesc scene;
    std::string error;
    ASSERT_TRUE(loadSceneFile(entry.path().string(), scene, error)) << error;
    EXPECT_FALSE(scene.bodies.empty()) << entry.path();
    EXPECT_GT(countMotion(scene, MotionType::Dynamic), 0) << entry.path();
    EXPECT_TRUE(scene.camera.given) << entry.path() << " should frame its scene with a camera";
    SceneIssue issue;
    EXPECT_TRUE(validateScene(scene, issue)) << issue.describe(scene);
  }
  EXPECT_GE(files, 11);
}

TEST(SceneFiles, ShowcaseScenesHaveTheirPromisedContent) {
  const SceneDesc demo = loadReferenceScene("demo.json");
  EXPECT_GE(demo.bodies.size(), 300u);
  EXPECT_LE(demo.bodies.size(), 600u);
  int hulls = 0, spheres = 0, capsules = 0;
  for (const BodyDesc& b : demo.bodies) {
    hulls += b.shape.type == ShapeType::ConvexHull;
    spheres += b.shape.type == ShapeType::Sphere;
    capsules += b.shape.type == ShapeType::Capsule;
  }
  EXPECT_GE(hulls, 2);
  EXPECT_GT(spheres, 0);
  EXPECT_GT(capsules, 0);
  EXPECT_EQ(demo.settings.frames, 300);

  const SceneDesc pit = loadReferenceScene("ball_pit.json");
  EXPECT_EQ(countMotion(pit, MotionType::Dynamic), 400);
  EXPECT_EQ(countMotion(pit, MotionType::Static), 5);  // four walls and the ground

  const SceneDesc dominoes = loadReferenceScene("domino_run.json");
  EXPECT_EQ(countMotion(dominoes, MotionType::Dynamic), 54 + 10);

  const SceneDesc tower = loadReferenceScene("tower_collapse.json");
  bool fastHeavyBall = false;
  for (const BodyDesc& b : tower.bodies)
    fastHeavyBall |= b.shape.type == ShapeType::Sphere && b.mass >= 100.0f && b.linearVelocity.norm() > 10.0f;
  EXPECT_TRUE(fastHeavyBall);

  // The tumbler: one kinematic drum (a compound) turning about its axis, 2000+ bodies inside it.
  const SceneDesc tumbler = loadReferenceScene("tumbler.json");
  ASSERT_FALSE(tumbler.bodies.empty());
  const BodyDesc& drum = tumbler.bodies[0];
  EXPECT_EQ(drum.motion, MotionType::Kinematic);
  EXPECT_EQ(drum.shape.type, ShapeType::Compound);
  EXPECT_GE(drum.shape.parts.size(), 16u);
  EXPECT_GT(drum.angularVelocity.norm(), 0.3f);
  EXPECT_GE(countMotion(tumbler, MotionType::Dynamic), 2000);

  const SceneDesc compounds = loadReferenceScene("compound_showcase.json");
  int compoundBodies = 0;
  for (const BodyDesc& b : compounds.bodies) compoundBodies += b.shape.type == ShapeType::Compound;
  EXPECT_GE(compoundBodies, 60);
}

TEST(SceneFiles, DefaultsAreApplied) {
  const SceneDesc s = parseOk(R"({"bodies": [{"shape": {"type": "sphere"}}]})");
  EXPECT_EQ(s.name, "test");  // file stem
  EXPECT_EQ(s.sourcePath, "mem/test.json");
  EXPECT_FLOAT_EQ(s.settings.world.dt, 1.0f / 60.0f);
  EXPECT_FLOAT_EQ(s.settings.world.gravity.y(), -9.81f);
  EXPECT_EQ(s.settings.world.iterations, 10);
  EXPECT_FALSE(s.settings.world.sleeping);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_FLOAT_EQ(s.materials[0].friction, 0.6f);
  EXPECT_FLOAT_EQ(s.materials[0].restitution, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[0].density, 1000.0f);
  EXPECT_FALSE(s.camera.given);
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodyDesc& b = s.bodies[0];
  EXPECT_EQ(b.motion, MotionType::Dynamic);
  EXPECT_FLOAT_EQ(b.shape.radius, 0.5f);
  EXPECT_FLOAT_EQ(b.mass, 0.0f);  // from density
  EXPECT_EQ(b.material, 0u);
  EXPECT_EQ(b.where, "bodies[0]");
  EXPECT_TRUE(b.position.isZero());
  EXPECT_TRUE(b.orientation.coeffs().isApprox(Quat::Identity().coeffs()));
}

// A material's rolling resistance reaches the bodies made of it, with the radius they roll on.
TEST(SceneFiles, RollingResistanceReachesTheBodies) {
  const SceneDesc s = parseOk(R"({
    "materials": {"felt": {"rolling_resistance": 0.04}},
    "bodies": [{"shape": {"type": "sphere", "radius": 0.3}, "material": "felt"},
               {"shape": {"type": "capsule", "radius": 0.2, "half_height": 0.5}, "position": [2, 0, 0], "material": "felt"},
               {"shape": {"type": "box"}, "position": [4, 0, 0], "material": "felt"},
               {"shape": {"type": "sphere"}, "position": [6, 0, 0]}]
  })");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_FLOAT_EQ(s.materials[1].rollingResistance, 0.04f);
  EXPECT_EQ(s.materials[0].rollingResistance, 0.0f);
  World w;
  std::string error;
  ASSERT_TRUE(buildWorld(s, w, error)) << error;
  const BodyStore& b = w.bodies();
  EXPECT_FLOAT_EQ(b.rollingResistance[0], 0.04f);
  EXPECT_FLOAT_EQ(b.rollingRadius[0], 0.3f);
  EXPECT_FLOAT_EQ(b.rollingRadius[1], 0.2f);
  EXPECT_FLOAT_EQ(b.rollingResistance[2], 0.04f);
  EXPECT_EQ(b.rollingRadius[2], 0.0f);  // a box does not roll
  EXPECT_EQ(b.rollingResistance[3], 0.0f);
}

TEST(SceneFiles, KeysAreReadIntoTheDescription) {
  const SceneDesc s = parseOk(R"({
    "name": "custom",
    "settings": {"dt": 0.01, "gravity": -3, "iterations": 7, "omega": 1.3, "beta": 0.1, "slop": 0.01, "skin": 0.0002, "sleeping": true, "frames": 50,
                 "chain_solve": false, "exact_mass_ratio": 0, "deep_layers_per_sweep": 5, "moving_layers_per_sweep": 0.7, "tolerance_thickness": 0.02, "reuse_manifolds": false, "momentum_layers": 4, "rest_damping": 0.02},
    "materials": {"ice": {"friction": 0.05, "restitution": 0.1, "density": 900}, "default": {"friction": 0.9}},
    "camera": {"eye": [1, 2, 3], "target": [0, 1, 0], "up": [0, 2, 0], "fov_deg": 60},
    "bodies": [
      {"name": "a", "type": "kinematic", "shape": {"type": "box", "size": [2, 4, 6]}, "position": [1, 2, 3],
       "orientation": [0, 0, 2, 0], "velocity": [1, 0, 0], "angular_velocity": [0, 1, 0], "material": "ice", "damping": 0.5},
      {"shape": {"type": "capsule", "radius": 0.2, "half_height": 0.7}, "orientation": {"euler_deg": [0, 90, 0]}, "mass": 3,
       "damping": {"linear": 0.1, "angular": 0.2}},
      {"type": "static", "shape": {"type": "plane", "normal": [0, 3, 0], "offset": 1}},
      {"type": "static", "shape": {"type": "mesh", "vertices": [[0,0,0],[1,0,0],[0,0,1]], "indices": [0, 2, 1]}}
    ],
    "water": [{"min": [-1, -1, -1], "max": [1, 0, 1], "density": 1020, "linear_drag": 2, "angular_drag": 1}]
  })");
  EXPECT_EQ(s.name, "custom");
  EXPECT_FLOAT_EQ(s.settings.world.dt, 0.01f);
  EXPECT_TRUE(s.settings.world.gravity.isApprox(Vec3(0, -3, 0)));
  EXPECT_EQ(s.settings.world.iterations, 7);
  EXPECT_FLOAT_EQ(s.settings.world.contact.omega, 1.3f);
  EXPECT_TRUE(s.settings.world.sleeping);
  EXPECT_FALSE(s.settings.world.chainSolve);
  EXPECT_EQ(s.settings.world.exactMassRatio, 0.0f);
  EXPECT_EQ(s.settings.world.deepLayersPerSweep, 5.0f);
  EXPECT_EQ(s.settings.world.movingLayersPerSweep, 0.7f);
  EXPECT_EQ(s.settings.world.toleranceThickness, 0.02f);
  EXPECT_FALSE(s.settings.world.reuseManifolds);
  EXPECT_FLOAT_EQ(s.settings.world.momentumLayers, 4.0f);
  EXPECT_FLOAT_EQ(s.settings.world.momentumLayers, 4.0f);  // and on to the world
  EXPECT_FLOAT_EQ(s.settings.world.restDamping, 0.02f);
  EXPECT_FLOAT_EQ(s.settings.world.contact.skin, 0.0002f);
  EXPECT_EQ(s.settings.frames, 50);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_FLOAT_EQ(s.materials[0].friction, 0.9f);  // "default" redefined
  EXPECT_EQ(s.materials[1].name, "ice");
  EXPECT_TRUE(s.camera.given);
  EXPECT_TRUE(s.camera.up.isApprox(Vec3::UnitY()));
  EXPECT_FLOAT_EQ(s.camera.fovYDeg, 60.0f);
  ASSERT_EQ(s.bodies.size(), 4u);
  const BodyDesc& a = s.bodies[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.motion, MotionType::Kinematic);
  EXPECT_TRUE(a.shape.halfExtents.isApprox(Vec3(1, 2, 3)));
  EXPECT_NEAR(a.orientation.z(), 1.0f, 1e-6f);  // [x, y, z, w] normalised
  EXPECT_NEAR(a.orientation.w(), 0.0f, 1e-6f);
  EXPECT_EQ(a.material, 1u);
  EXPECT_FLOAT_EQ(a.linearDamping, 0.5f);
  EXPECT_FLOAT_EQ(a.angularDamping, 0.5f);
  const BodyDesc& b = s.bodies[1];
  EXPECT_FLOAT_EQ(b.mass, 3.0f);
  EXPECT_FLOAT_EQ(b.angularDamping, 0.2f);
  // 90 degrees about y turns +x into -z.
  EXPECT_TRUE((b.orientation * Vec3::UnitX()).isApprox(Vec3(0, 0, -1), 1e-5f));
  EXPECT_TRUE(s.bodies[2].shape.planeNormal.isApprox(Vec3::UnitY()));
  EXPECT_EQ(s.bodies[3].shape.meshIndices.size(), 3u);
  ASSERT_EQ(s.water.size(), 1u);
  EXPECT_FLOAT_EQ(s.water[0].density, 1020.0f);
  EXPECT_FLOAT_EQ(s.water[0].hi.y(), 0.0f);
}

TEST(SceneFiles, EulerAnglesApplyXThenYThenZ) {
  const SceneDesc s = parseOk(R"({"bodies": [{"shape": {"type": "sphere"}, "orientation": {"euler_deg": [90, 90, 0]}}]})");
  // x first: +y -> +z; then y: +z -> +x.
  EXPECT_TRUE((s.bodies[0].orientation * Vec3::UnitY()).isApprox(Vec3::UnitX(), 1e-5f));
  EXPECT_NEAR(s.bodies[0].orientation.norm(), 1.0f, 1e-6f);
}

TEST(SceneFiles, MeshAndHullAssetsLoadRelativeToTheSceneFile) {
  SceneDesc s;
  std::string error;
  const std::string text = R"({"bodies": [
    {"type": "static", "shape": {"type": "mesh", "asset": "data/tetra.obj", "scale": [2, 2, 2]}},
    {"shape": {"type": "hull", "asset": "data/tetra.obj", "scale": 0.5}}]})";
  ASSERT_TRUE(parseSceneText(text, sourceDir() + "/tests/scene/scene.json", s, error)) << error;
  const ShapeDesc& mesh = s.bodies[0].shape;
  EXPECT_EQ(mesh.asset, "data/tetra.obj");
  EXPECT_EQ(mesh.meshVertices.size(), 4u);
  EXPECT_EQ(mesh.meshIndices.size(), 12u);
  float maxCoord = 0.0f;
  for (const Vec3& v : mesh.meshVertices) maxCoord = std::max(maxCoord, v.maxCoeff());
  EXPECT_FLOAT_EQ(maxCoord, 2.0f);  // scaled
  EXPECT_EQ(s.bodies[1].shape.points.size(), 4u);
  EXPECT_TRUE(s.bodies[1].shape.meshVertices.empty());
}

TEST(SceneFiles, OutputIsUntouchedOnError) {
  SceneDesc s;
  s.name = "keep";
  std::string error;
  EXPECT_FALSE(parseSceneText(R"({"bodies": [{"shape": {"type": "cube"}}]})", "x.json", s, error));
  EXPECT_EQ(s.name, "keep");
  EXPECT_TRUE(s.bodies.empty());
}

}  // namespace
}  // namespace haif::test

namespace haif::test {
namespace {

TEST(SceneFiles, TheDocumentedExampleLoads) {
  std::ifstream in(sourceDir() + "/docs/scene_format.md");
  ASSERT_TRUE(in) << "docs/scene_format.md";
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const size_t begin = text.find("```json\n", text.find("## Example"));
  ASSERT_NE(begin, std::string::npos);
  const size_t end = text.find("```", begin + 8);
  const SceneDesc s = parseOk(text.substr(begin + 8, end - begin - 8));
  EXPECT_EQ(s.name, "small");
  EXPECT_EQ(s.bodies.size(), 2u + 1u + 5u);
  ASSERT_EQ(s.joints.size(), 1u);
  EXPECT_EQ(s.joints[0].bodyB, 0);
}

}  // namespace
}  // namespace haif::test
