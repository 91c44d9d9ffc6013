// FlushDenormals (core/flush_denormals.h): while a step runs, results below float's normal range are
// zero on every thread of the step, and the caller's floating-point mode is put back after.
#include "core/flush_denormals.h"

#include "support/physics_test_util.h"

#include <cmath>

namespace haif::test {
namespace {

int subnormalSpeeds(const World& w) {
  int count = 0;
  const BodyStore& b = w.bodies();
  for (uint32_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k)
      count += (std::fpclassify(b.v[i][k]) == FP_SUBNORMAL) + (std::fpclassify(b.w[i][k]) == FP_SUBNORMAL);
  return count;
}

// A pyramid at rest: rest damping scales a slow box's speed by (s/s0)^2 a step, so its speeds fall
// through 1e-38 within a few steps of settling. Kept, every product with them would be computed in
// microcode; flushed, they are zero, at 1 thread and at 2.
TEST(FlushDenormals, ARestingPyramidKeepsNoSubnormalSpeeds) {
  uint64_t hash[2];
  for (const int threads : {1, 2}) {
    World w;
    w.setThreads(threads);
    addGround(w);
    addPyramid2d(w, 10);
    int seen = 0;
    for (int s = 0; s < 240; ++s) {
      w.step();
      seen += subnormalSpeeds(w);
    }
    EXPECT_EQ(seen, 0) << threads;
    hash[threads - 1] = w.stateHash();
  }
  EXPECT_EQ(hash[0], hash[1]);
}

#if defined(__SSE__) || defined(_M_X64)
// A caller that keeps subnormals (the default) still has them after a step, and one that flushes
// them still does: the step sets its mode for itself only.
TEST(FlushDenormals, TheCallersModeIsPutBackAfterAStep) {
  const unsigned start = _mm_getcsr();
  for (const unsigned mode : {start & ~FlushDenormals::kModeBits, start | FlushDenormals::kModeBits}) {
    _mm_setcsr(mode);
    World w;
    w.setThreads(2);
    addGround(w);
    addPyramid2d(w, 4);
    for (int s = 0; s < 30; ++s) w.step();
    constexpr unsigned kFlags = 0x3F;  // sticky exception flags, which the caller's own arithmetic sets
    EXPECT_EQ(_mm_getcsr() & ~kFlags, mode & ~kFlags);
  }
  _mm_setcsr(start);
  volatile float tiny = 1e-20f;  // squared: 1e-40, subnormal
  EXPECT_GT(tiny * tiny * 1e20f, 0.0f) << "the default mode keeps subnormals";
}
#endif

}  // namespace
}  // namespace haif::test
