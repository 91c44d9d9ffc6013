// Conjugate-gradient momentum between sweeps (contact_solver.h: accelerate) carries the weight of a
// tall stack down in far fewer sweeps than Gauss-Seidel alone.
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace haif {
namespace {

using test::addColumn;
using test::addGround;

struct ColumnResult {
  float worstDeviation = 0.0f;  // largest distance of a box from where it started (m)
  double kineticEnergy = 0.0;   // at the end (J)
};

ColumnResult standColumn(int boxes, bool accelerate, int steps, bool coldStartFromWeight = true) {
  WorldSettings ws;
  ws.iterations = 10;
  ws.accelerate = accelerate;
  ws.coldStartFromWeight = coldStartFromWeight;
  ws.chainSolve = false;  // a column is a chain, solved exactly without sweeps: test the sweeps
  World w(ws);
  addGround(w);
  addColumn(w, boxes);
  ColumnResult r;
  for (int s = 0; s < steps; ++s) {
    w.step();
    for (uint32_t i = 1; i < w.bodyCount(); ++i)
      r.worstDeviation = std::max(r.worstDeviation, (w.bodies().xf[i].p - Vec3(0.0f, 0.5f + float(i - 1), 0.0f)).norm());
  }
  r.kineticEnergy = w.kineticEnergy();
  return r;
}

TEST(AcceleratedSolve, ThirtyBoxColumnStandsAtTenIterations) {
  // Even when every contact starts cold and the sweeps must build the support up.
  const ColumnResult r = standColumn(30, true, 600, false);  // 10 s
  EXPECT_LT(r.worstDeviation, 0.1f);  // 30 contacts, each within slop + a little
  EXPECT_LT(r.kineticEnergy, 1e-3);   // at rest, not bouncing
}

TEST(AcceleratedSolve, HoldsTheColumnBetterThanSweepsAlone) {
  // Over the first two seconds, from cold contacts (no weight estimate, so the sweeps must build the
  // support up themselves): plain sweeps let the 30-box column sag and bounce.
  const ColumnResult plain = standColumn(30, false, 120, false);
  const ColumnResult fast = standColumn(30, true, 120, false);
  EXPECT_LT(fast.worstDeviation, 0.5f * plain.worstDeviation);
}

// Mean solve error (docs/metrics.md) of a box pyramid over `steps` steps at 10 iterations, its
// contacts started cold (a pile that forms while moving): the balanced weight estimate starts a
// pyramid made at rest solved, and leaves the sweeps nothing to show.
double pyramidError(int base, float momentumLayers, int steps) {
  WorldSettings ws;
  ws.iterations = 10;
  ws.coldStartFromWeight = false;
  ws.momentumLayers = momentumLayers;
  ws.sleeping = false;  // every sample a solve of the whole pyramid
  World w(ws);
  addGround(w);
  test::addPyramid2d(w, base);
  w.setSolveErrorInterval(10);
  double sum = 0.0;
  int samples = 0;
  for (int s = 0; s < steps; ++s) {
    w.step();
    const double e = w.lastStats().solveError;
    if (std::isnan(e)) continue;
    sum += e;
    ++samples;
  }
  EXPECT_GT(samples, 0);
  return samples ? sum / samples : 0.0;
}

TEST(AcceleratedSolve, LowPileTakesNoMomentum) {
  // Ten layers: sweeps in top-down order converge as fast alone, and momentum only overshoots
  // (mean solve error 0.18 without, 0.37 with, from cold contacts).
  const double plain = pyramidError(10, WorldSettings{}.momentumLayers, 300);
  const double forced = pyramidError(10, 0.0f, 300);
  EXPECT_LT(plain, 0.9 * forced);
}

TEST(AcceleratedSolve, SameStateForAnyThreadCount) {
  auto run = [](int threads) {
    WorldSettings ws;
    ws.threads = threads;
    World w(ws);
    addGround(w);
    for (int s = 0; s < 8; ++s) addColumn(w, 12, 3.0f * float(s));
    for (int s = 0; s < 120; ++s) w.step();
    return w.stateHash();
  };
  EXPECT_EQ(run(2), run(1));
}

}  // namespace
}  // namespace haif
