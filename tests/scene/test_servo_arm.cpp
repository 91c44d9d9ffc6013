// Servos along a jointed arm (dynamics/motor_mass.h). A motor row swept with the mass of its own two
// bodies asks too little of an arm whose links carry more links: the sweeps reached the servo's speed
// a fraction at a time, the servo lagged its path, its position error grew its speed, and it
// overshot. robot_arm's 2 kg hand swung at up to 16 m/s at 4 iterations (2.9 m/s where the solve has
// converged) and the speed bound caught a body ~370 times in a minute.
#include "scene_test_util.h"

#include "haif/iteration_controller.h"
#include "haif/world.h"
#include "scene/build_world.h"

#include <algorithm>
#include <memory>
#include <string>

namespace haif::test {
namespace {

struct ArmRun {
  float fastestHand = 0.0f;   // m/s, over the run
  uint32_t speedLimited = 0;  // bodies slowed to the speed bound, summed over the run
};

ArmRun runRobotArm(int iterations, int steps) {
  const SceneDesc scene = loadReferenceScene("robot_arm.json");
  World w(scene.settings.world);
  std::string error;
  EXPECT_TRUE(buildWorld(scene, w, error)) << error;
  w.settings().iterations = iterations;
  w.setController(std::make_unique<FixedController>(iterations));
  uint32_t hand = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].name == "hand") hand = uint32_t(i);
  ArmRun run;
  for (int s = 0; s < steps; ++s) {
    w.step();
    run.fastestHand = std::max(run.fastestHand, w.bodies().v[hand].norm());
    run.speedLimited += w.lastStats().speedLimited;
  }
  return run;
}

// The arm follows its path at 4 and 10 iterations as it does at 60: its hand no faster than a
// quarter above the converged run's fastest, and nothing thrown hard enough to meet the speed bound.
TEST(ServoArm, TheRobotArmFollowsItsPathAtFewIterations) {
  const ArmRun converged = runRobotArm(60, 300);
  ASSERT_GT(converged.fastestHand, 1.0f);  // the path moves it
  for (const int iterations : {4, 10}) {
    const ArmRun run = runRobotArm(iterations, 300);
    EXPECT_LT(run.fastestHand, 1.25f * converged.fastestHand) << iterations << " iterations";
    EXPECT_EQ(run.speedLimited, 0u) << iterations << " iterations";
  }
}

}  // namespace
}  // namespace haif::test
