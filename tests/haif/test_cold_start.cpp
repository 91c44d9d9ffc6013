// New contacts of a pile at rest start from the weight they carry (World::estimateColdImpulses).
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

using test::addGround;
using test::addPyramid2d;

struct PileResult {
  double meanDrop = 0.0, maxDrop = 0.0, kineticEnergy = 0.0;
};

PileResult standPyramid(int base, bool coldStartFromWeight, int steps) {
  WorldSettings ws;
  ws.iterations = 10;
  ws.coldStartFromWeight = coldStartFromWeight;
  World w(ws);
  addGround(w);
  addPyramid2d(w, base);
  std::vector<float> y0;
  for (uint32_t i = 0; i < w.bodyCount(); ++i) y0.push_back(w.bodies().xf[i].p.y());
  for (int s = 0; s < steps; ++s) w.step();
  PileResult r;
  int n = 0;
  for (uint32_t i = 1; i < w.bodyCount(); ++i) {
    const double d = y0[i] - w.bodies().xf[i].p.y();
    r.meanDrop += d;
    r.maxDrop = std::max(r.maxDrop, d);
    ++n;
  }
  r.meanDrop /= n;
  r.kineticEnergy = w.kineticEnergy();
  return r;
}

TEST(ColdStart, ThirtyLayerPyramidStandsStillFromItsFirstStep) {
  // 465 boxes created touching, 10 iterations, 2 s.
  const PileResult r = standPyramid(30, true, 120);
  EXPECT_LT(r.maxDrop, 0.01);       // no layer sinks more than 1 cm in total
  EXPECT_LT(r.kineticEnergy, 0.01); // 465 kg essentially at rest
}

TEST(ColdStart, WithoutTheWeightEstimateThePileFallsIntoItself) {
  // The same pile, contacts starting from zero: the sweeps build the support up a few layers per
  // step while the upper part falls. The estimate is what makes the difference.
  const PileResult cold = standPyramid(30, false, 120);
  const PileResult warm = standPyramid(30, true, 120);
  EXPECT_GT(cold.maxDrop, 5.0 * warm.maxDrop);
}

}  // namespace
}  // namespace haif
