// The jointed scenes of issue 7 load, build and run; chain_heavy meets its bar from the scene file.
#include "scene/build_world.h"
#include "scene_test_util.h"

#include <cmath>

namespace haif::test {
namespace {

struct SceneRun {
  float maxJointError = 0.0f;
  double rmsJointError = 0.0;
  bool finite = true;
};

SceneRun runScene(const SceneDesc& scene, int steps, int iterations) {
  WorldSettings s = worldSettingsFor(scene);
  s.iterations = iterations;
  World w(s);
  std::string error;
  EXPECT_TRUE(buildWorld(scene, w, error)) << error;
  SceneRun r;
  double sq = 0.0;
  uint64_t n = 0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    for (uint32_t j = 0; j < w.jointCount(); ++j) {
      if (w.joint(j).broken) continue;
      const float e = w.jointError(j).linear;
      r.maxJointError = std::max(r.maxJointError, e);
      sq += double(e) * e;
      ++n;
    }
  }
  for (uint32_t b = 0; b < w.bodyCount(); ++b) r.finite = r.finite && isFinite(w.bodies().xf[b].p);
  r.rmsJointError = n ? std::sqrt(sq / double(n)) : 0.0;
  return r;
}

TEST(JointSceneFiles, ChainHeavyIsExactlyTheIssueLayout) {
  const SceneDesc s = loadReferenceScene("chain_heavy.json");
  ASSERT_EQ(s.joints.size(), 31u);
  int links = 0;
  for (const BodyDesc& b : s.bodies) {
    if (b.name.rfind("link", 0) == 0) {
      ++links;
      EXPECT_FLOAT_EQ(b.mass, 1.0f) << b.name;
    }
    if (b.name == "weight") {
      EXPECT_FLOAT_EQ(b.mass, 100.0f);
    }
  }
  EXPECT_EQ(links, 30);
  EXPECT_EQ(s.joints[0].bodyA, -1) << "the top link is fixed to the world";
  EXPECT_EQ(s.bodies[size_t(s.joints.back().bodyB)].name, "weight");
}

TEST(JointSceneFiles, ChainHeavyStaysTogetherOverTenSecondsAtTenIterations) {
  const SceneRun r = runScene(loadReferenceScene("chain_heavy.json"), 600, 10);
  EXPECT_TRUE(r.finite);
  EXPECT_LE(r.maxJointError, 0.05f);
}

TEST(JointSceneFiles, EveryJointedSceneRuns) {
  for (const char* name : {"rope_bridge.json", "robot_arm.json", "ragdolls.json", "newtons_cradle.json",
                           "wrecking_ball.json"}) {
    SCOPED_TRACE(name);
    const SceneDesc s = loadReferenceScene(name);
    EXPECT_GT(s.joints.size(), 0u);
    const SceneRun r = runScene(s, 120, s.settings.iterations);
    EXPECT_TRUE(r.finite);
    EXPECT_LT(r.maxJointError, 0.05f);
  }
}

}  // namespace
}  // namespace haif::test
