// Tiny floats are computed as zero while the engine works.
//
// A pile at rest keeps velocities of 1e-12 m/s and less (rest damping scales a slow body's speed by
// (s/s0)^2 a step), and their squares and products fall below float's normal range (1.2e-38). x86
// computes such subnormal numbers in microcode, ~100 cycles an operation: integrating the 10,780
// resting boxes of `many_pyramids` took 1.24 ms of a step at 2 threads, 0.29 ms with them flushed.
// Every thread that runs a part of the step sets the same mode (World::step on the caller,
// World::parallelFor on each chunk), so results do not depend on the thread count, and the mode the
// thread had is put back after, so code outside the engine sees what it set.
#pragma once

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace haif {

class FlushDenormals {
 public:
#if defined(__SSE__) || defined(_M_X64)
  /// MXCSR's flush-to-zero (results below the normal range are 0) and denormals-are-zero (so are
  /// such inputs) bits.
  static constexpr unsigned kModeBits = 0x8000 | 0x0040;
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kModeBits); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
#else
  FlushDenormals() = default;  // other targets: the default mode (correct, slower on subnormals)
#endif
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

#if defined(__SSE__) || defined(_M_X64)
 private:
  unsigned saved_;
#endif
};

}  // namespace haif
