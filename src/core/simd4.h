// Four floats as one SIMD value, for the four normal rows of a contact manifold.
//
// GCC vector extensions: one SSE register on x86-64 (three-operand AVX forms with x86-64-v3), plain
// scalar code on other targets. Arithmetic with a scalar operand broadcasts it.
#pragma once

#include <cstdint>
#include <cstring>

namespace haif::simd4 {

using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));

inline F4 load(const float* p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store(float* p, F4 v) { std::memcpy(p, &v, sizeof v); }

/// max(0, v) lane by lane, as std::max(0.0f, v) (a NaN lane gives 0).
inline F4 clampNonNegative(F4 v) {
  const F4 zero{};
  return zero < v ? v : zero;
}

inline F4 abs(F4 v) { return v < F4{} ? -v : v; }

/// True when every lane of the mask is set.
inline bool all(I4 mask) { return (mask[0] & mask[1] & mask[2] & mask[3]) != 0; }

/// The lane sums of four vectors: {Σa, Σb, Σc, Σd}, each summed as (x0 + x2) + (x1 + x3).
inline F4 laneSums(F4 a, F4 b, F4 c, F4 d) {
  const F4 ab = __builtin_shuffle(a, b, I4{0, 4, 1, 5}) + __builtin_shuffle(a, b, I4{2, 6, 3, 7});
  const F4 cd = __builtin_shuffle(c, d, I4{0, 4, 1, 5}) + __builtin_shuffle(c, d, I4{2, 6, 3, 7});
  return __builtin_shuffle(ab, cd, I4{0, 1, 4, 5}) + __builtin_shuffle(ab, cd, I4{2, 3, 6, 7});
}

/// Σ of the lanes, in the same order as laneSums.
inline float laneSum(F4 a) { return (a[0] + a[2]) + (a[1] + a[3]); }

inline float laneMax(F4 a) {
  const float m01 = a[0] > a[1] ? a[0] : a[1], m23 = a[2] > a[3] ? a[2] : a[3];
  return m01 > m23 ? m01 : m23;
}

}  // namespace haif::simd4
