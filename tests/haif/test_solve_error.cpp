// The solve error of docs/metrics.md, e = |v_I - v*|_M / |v_0 - v*|_M: in [0, 1], smaller with more iterations.
#include "haif/world.h"

#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace haif {
namespace {

struct ErrorStats {
  double mean = 0.0, max = 0.0;
  int samples = 0, outOfRange = 0, firstOutOfRange = -1;
};

// The stack is swept contact by contact (no exact chain solve, which settles it in one sweep), so
// the error depends on the iteration count the way PGS makes it.
ErrorStats stackError(int iterations, int steps) {
  ErrorStats e;
  double sum = 0.0;
  test::stepGappedColumn(iterations, false, steps, [&](const World& w, int s) {
    const double err = w.lastStats().solveError;
    EXPECT_FALSE(std::isnan(err)) << "step " << s << ": not measured with interval 1";
    if (std::isnan(err)) return;
    if (err < 0.0 || err > 1.0) {
      if (e.firstOutOfRange < 0) e.firstOutOfRange = s;
      ++e.outOfRange;
    }
    sum += err;
    e.max = std::max(e.max, err);
    ++e.samples;
  });
  e.mean = e.samples ? sum / e.samples : 0.0;
  return e;
}

TEST(SolveError, InUnitRange) {
  for (int iterations : {2, 10, 30}) {
    const ErrorStats e = stackError(iterations, 60);
    EXPECT_EQ(e.samples, 60);
    EXPECT_EQ(e.outOfRange, 0) << iterations << " iterations: " << e.outOfRange << " of " << e.samples
                               << " steps outside [0, 1], first at step " << e.firstOutOfRange << ", max " << e.max;
  }
}

TEST(SolveError, FallsWithIterations) {
  const ErrorStats few = stackError(2, 60), many = stackError(30, 60);
  EXPECT_EQ(few.samples, 60);
  EXPECT_LT(many.mean, few.mean) << "2 iterations: " << few.mean << ", 30 iterations: " << many.mean;
  EXPECT_LT(many.mean, 0.5 * few.mean) << "15x the iterations should at least halve the error";
  EXPECT_GT(few.mean, 0.0) << "2 iterations of PGS cannot converge a 10-box stack";
}

TEST(SolveError, NotMeasuredByDefault) {
  World w;
  BodyDef d;
  d.shape = Shape::sphere(0.5f);
  d.mass = 1.0f;
  w.addBody(d);
  w.step();
  EXPECT_TRUE(std::isnan(w.lastStats().solveError));
}

TEST(SolveError, MeasuringDoesNotChangeTheSimulation) {
  // The reference solve is a measurement: the state after the step must be the same with or without it.
  auto hashAfter = [](int every) {
    World w;
    test::addGround(w);
    for (int h = 0; h < 5; ++h) test::addBox(w, Vec3(0.02f * float(h), 0.5f + 1.01f * float(h), 0.0f));
    w.setSolveErrorInterval(every);
    for (int s = 0; s < 60; ++s) w.step();
    return w.stateHash();
  };
  EXPECT_EQ(hashAfter(1), hashAfter(0));
}

}  // namespace
}  // namespace haif
