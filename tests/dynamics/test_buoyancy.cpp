// Buoyancy (Archimedes): a body lighter than water floats with submerged fraction rho_body / rho_water,
// a heavier one sinks; scenes without water skip the pass.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

constexpr float kSurface = 3.0f;

struct FloatResult {
  float meanY = 0.0f;  ///< mean centre height over the last second
  float finalY = 0.0f;
  uint32_t stages = 0;
};

FloatResult dropInWater(float density, float startY) {
  World w;
  addGround(w);
  WaterVolume water;
  water.box = {Vec3(-5.0f, 0.0f, -5.0f), Vec3(5.0f, kSurface, 5.0f)};
  water.density = 1000.0f;
  water.linearDrag = 2.0f;  // damp the bobbing so 10 s is enough to settle
  w.addWater(water);
  BodyDef d;
  d.shape = Shape::box(Vec3::Constant(0.5f));
  d.density = density;  // mass from density (mass = 0): the volume matters here
  d.xf.p = Vec3(0.0f, startY, 0.0f);
  const uint32_t b = w.addBody(d);
  FloatResult r;
  double sum = 0.0;
  for (int s = 0; s < 600; ++s) {
    w.step();
    if (s >= 540) sum += w.bodies().xf[b].p.y();
    r.stages |= w.lastStats().stages;
  }
  r.meanY = float(sum / 60.0);
  r.finalY = w.bodies().xf[b].p.y();
  return r;
}

TEST(Buoyancy, HalfDensityBoxFloatsHalfSubmerged) {
  const FloatResult r = dropInWater(500.0f, kSurface + 0.3f);
  const float submerged = std::clamp(kSurface - (r.meanY - 0.5f), 0.0f, 1.0f);  // of a 1 m tall box
  EXPECT_NEAR(submerged, 0.5f, 0.05f) << "centre at " << r.meanY << " m, surface at " << kSurface << " m";
  EXPECT_TRUE(r.stages & kStageBuoyancy);
}

TEST(Buoyancy, DenserThanWaterSinksToTheBottom) {
  const FloatResult r = dropInWater(2000.0f, kSurface - 0.5f);
  EXPECT_NEAR(r.finalY, 0.5f, 0.02f) << "a density-2000 box should rest on the bottom (ground)";
}

TEST(Buoyancy, SceneWithoutWaterSkipsThePass) {
  World w;
  addGround(w);
  addBox(w, Vec3(0.0f, 2.0f, 0.0f));
  EXPECT_FALSE(w.hasWater());
  for (int s = 0; s < 60; ++s) {
    w.step();
    ASSERT_FALSE(w.lastStats().stages & kStageBuoyancy) << "step " << s;
    ASSERT_TRUE(w.lastStats().stages & kStageSolve);
  }
}

}  // namespace
}  // namespace haif::test
