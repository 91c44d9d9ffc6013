// validateScene on descriptions built in code (the net behind the loader).
#include "scene/scene_validate.h"

#include <gtest/gtest.h>

#include <limits>

namespace haif {
namespace {

SceneDesc validScene() {
  SceneDesc s;
  s.materials.push_back(MaterialDesc{});
  BodyDesc ground;
  ground.motion = MotionType::Static;
  ground.shape.type = ShapeType::Plane;
  ground.where = "bodies[0]";
  BodyDesc ball;
  ball.shape.type = ShapeType::Sphere;
  ball.position = Vec3(0, 1, 0);
  ball.where = "bodies[1]";
  s.bodies = {ground, ball};
  return s;
}

std::string issueOf(const SceneDesc& s) {
  SceneIssue issue;
  EXPECT_FALSE(validateScene(s, issue));
  return issue.describe(s);
}

TEST(ValidateScene, AcceptsAValidScene) {
  SceneIssue issue;
  EXPECT_TRUE(validateScene(validScene(), issue)) << issue.describe(validScene());
}

TEST(ValidateScene, RejectsEachBrokenInvariant) {
  SceneDesc s = validScene();
  s.settings.world.dt = 0.0f;
  EXPECT_EQ(issueOf(s), "settings.dt: must be > 0 (got 0)");

  s = validScene();
  s.settings.world.contact.omega = 2.0f;
  EXPECT_EQ(issueOf(s), "settings.omega: must be in [1, 2) (got 2)");

  s = validScene();
  s.settings.world.momentumLayers = -1.0f;
  EXPECT_EQ(issueOf(s), "settings.momentum_layers: must be >= 0 (got -1)");

  s = validScene();
  s.settings.world.restDamping = -0.5f;
  EXPECT_EQ(issueOf(s), "settings.rest_damping: must be >= 0 (got -0.5)");

  s = validScene();
  s.settings.world.iterations = 0;
  EXPECT_EQ(issueOf(s), "settings.iterations: must be >= 1 (got 0)");

  s = validScene();
  s.bodies[1].mass = -2.0f;
  EXPECT_EQ(issueOf(s), "bodies[1].mass: must be > 0 for a dynamic body (got -2)");

  s = validScene();
  s.bodies[1].position.x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(issueOf(s).find("bodies[1].position: must be finite"), std::string::npos);

  s = validScene();
  s.bodies[1].shape.type = ShapeType::Plane;
  EXPECT_NE(issueOf(s).find("bodies[1].shape.type: shape 'plane' is static-only"), std::string::npos);

  s = validScene();
  s.bodies[1].shape.radius = -1.0f;
  EXPECT_EQ(issueOf(s), "bodies[1].shape.radius: must be > 0 (got -1)");

  s = validScene();
  s.bodies[1].shape.type = ShapeType::ConvexHull;
  s.bodies[1].shape.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_EQ(issueOf(s), "bodies[1].shape.points: a hull needs at least 4 points (got 3)");

  s = validScene();
  s.bodies[1].material = 3;
  EXPECT_EQ(issueOf(s), "bodies[1].material: material index 3 is out of range");

  s = validScene();
  s.bodies[1].orientation = Quat(2, 0, 0, 0);
  EXPECT_NE(issueOf(s).find("bodies[1].orientation: must be a unit quaternion"), std::string::npos);

  s = validScene();
  s.materials[0].friction = -1.0f;
  EXPECT_EQ(issueOf(s), "materials.default.friction: must be >= 0 (got -1)");

  s = validScene();
  s.bodies[0].linearVelocity = Vec3(1, 0, 0);
  EXPECT_NE(issueOf(s).find("bodies[0].velocity: a static body cannot move"), std::string::npos);

  s = validScene();
  s.water.push_back(WaterDesc{});  // lo == hi
  EXPECT_EQ(issueOf(s), "water[0].max: must be greater than min in every component");
}

TEST(ValidateScene, HullPointsMustSpanAVolume) {
  EXPECT_EQ(hullPointsProblem({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}), "");
  EXPECT_NE(hullPointsProblem({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}).find("one line"), std::string::npos);
  EXPECT_NE(hullPointsProblem({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)}).find("same point"), std::string::npos);
}

}  // namespace
}  // namespace haif
