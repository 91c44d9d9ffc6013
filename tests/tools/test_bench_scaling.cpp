// haif bench --scaling (tools/bench_scaling.h): the generated worlds have the sizes asked for, the
// fitted exponent is the power law's, and the memory a world holds follows its size.
#include "tools/bench_scaling.h"

#include "haif/world.h"
#include "scene/build_world.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace haif;

TEST(BenchScaling, TheExponentOfAPowerLawIsItsPower) {
  for (const double k : {0.5, 1.0, 1.23, 2.0}) {
    std::vector<double> x, y;
    for (const double n : {1e3, 3e3, 1e4, 3e4, 1e5}) {
      x.push_back(n);
      y.push_back(0.7 * std::pow(n, k));
    }
    EXPECT_NEAR(powerLawExponent(x, y), k, 1e-9);
  }
  EXPECT_TRUE(std::isnan(powerLawExponent({1000.0}, {2.0}))) << "one point fits no slope";
  EXPECT_TRUE(std::isnan(powerLawExponent({1000.0, 1000.0}, {2.0, 3.0}))) << "nor one size twice";
  EXPECT_NEAR(powerLawExponent({10.0, 0.0, 100.0}, {1.0, 5.0, 100.0}), 2.0, 1e-12) << "non-positive points are left out";
}

TEST(BenchScaling, EachFamilyHasExactlyTheBodiesAskedFor) {
  for (const char* family : {"stacks", "pile"})
    for (const int n : {100, 1000, 2345}) {
      SceneDesc scene;
      std::string error;
      ASSERT_TRUE(parseSceneText(scalingSceneJson(family, n, 10), "test", scene, error)) << family << " " << n << ": " << error;
      World world(scene.settings.world);
      ASSERT_TRUE(buildWorld(scene, world, error)) << error;
      int dynamic = 0;
      for (uint32_t i = 0; i < world.bodyCount(); ++i) dynamic += world.bodies().kind[i] == BodyKind::Dynamic ? 1 : 0;
      EXPECT_EQ(dynamic, n) << family;
    }
  EXPECT_TRUE(scalingSceneJson("towers", 100, 10).empty());
  ScalingResult r;
  std::string error;
  EXPECT_FALSE(runScalingPoint("towers", 100, 10, 1, r, error));
  EXPECT_NE(error.find("unknown family 'towers'"), std::string::npos) << error;
}

TEST(BenchScaling, AWorldTenTimesLargerHoldsAboutTenTimesTheMemory) {
  ScalingResult small, large;
  std::string error;
  ASSERT_TRUE(runScalingPoint("stacks", 300, 4, 1, small, error)) << error;
  ASSERT_TRUE(runScalingPoint("stacks", 3000, 4, 1, large, error)) << error;
  EXPECT_EQ(small.steps, 4);
  EXPECT_FALSE(small.nan || large.nan);
  EXPECT_GT(small.msMedian, 0.0);
  if (std::isnan(small.worldMb)) GTEST_SKIP() << "this allocator (a sanitizer's) keeps no counts of bytes in use";
  ASSERT_GT(small.worldMb, 0.0);
  // Per-body arrays dominate; fixed costs (the ground, the arenas) make the small world relatively larger.
  EXPECT_GT(large.worldMb / small.worldMb, 5.0);
  EXPECT_LT(large.worldMb / small.worldMb, 15.0);
}
