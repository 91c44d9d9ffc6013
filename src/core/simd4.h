// Four floats as one SIMD value, for the four normal rows of a contact manifold.
//
// GCC vector extensions: one SSE register on x86-64 (three-operand AVX forms with x86-64-v3), plain
// scalar code on other targets. Arithmetic with a scalar operand broadcasts it.
#pragma once

#include "core/simd4_lanes.h"

namespace haif::simd4 {

/// The 4 × 4 block whose rows are r0..r3, as its columns c0..c3 (c0 = {r0[0], r1[0], r2[0], r3[0]}).
inline void transpose(F4 r0, F4 r1, F4 r2, F4 r3, F4& c0, F4& c1, F4& c2, F4& c3) {
  const F4 lo01 = __builtin_shuffle(r0, r1, I4{0, 4, 1, 5}), lo23 = __builtin_shuffle(r2, r3, I4{0, 4, 1, 5});
  const F4 hi01 = __builtin_shuffle(r0, r1, I4{2, 6, 3, 7}), hi23 = __builtin_shuffle(r2, r3, I4{2, 6, 3, 7});
  c0 = __builtin_shuffle(lo01, lo23, I4{0, 1, 4, 5});
  c1 = __builtin_shuffle(lo01, lo23, I4{2, 3, 6, 7});
  c2 = __builtin_shuffle(hi01, hi23, I4{0, 1, 4, 5});
  c3 = __builtin_shuffle(hi01, hi23, I4{2, 3, 6, 7});
}

/// max(0, v) lane by lane, as std::max(0.0f, v) (a NaN lane gives 0).
inline F4 clampNonNegative(F4 v) {
  const F4 zero{};
  return zero < v ? v : zero;
}

inline F4 abs(F4 v) { return v < F4{} ? -v : v; }

/// Lane i of v in every lane. Lanes are moved with shuffles, not read one by one: GCC reads a lane
/// by index through a store to the stack.
template <int i> inline F4 splat(F4 v) { return __builtin_shuffle(v, I4{i, i, i, i}); }

/// Lane i of v as a scalar, by the same shuffle.
template <int i> inline float lane(F4 v) { return splat<i>(v)[0]; }

/// True when every lane of the mask is set.
inline bool all(I4 mask) {
  const I4 m = mask & __builtin_shuffle(mask, I4{2, 3, 0, 1});
  return (m & __builtin_shuffle(m, I4{1, 0, 3, 2}))[0] != 0;
}

/// The lane sums of four vectors: {Σa, Σb, Σc, Σd}, each summed as (x0 + x2) + (x1 + x3).
inline F4 laneSums(F4 a, F4 b, F4 c, F4 d) {
  const F4 ab = __builtin_shuffle(a, b, I4{0, 4, 1, 5}) + __builtin_shuffle(a, b, I4{2, 6, 3, 7});
  const F4 cd = __builtin_shuffle(c, d, I4{0, 4, 1, 5}) + __builtin_shuffle(c, d, I4{2, 6, 3, 7});
  return __builtin_shuffle(ab, cd, I4{0, 1, 4, 5}) + __builtin_shuffle(ab, cd, I4{2, 3, 6, 7});
}

/// Σ of the lanes, in the same order as laneSums.
inline float laneSum(F4 a) {
  const F4 h = a + __builtin_shuffle(a, I4{2, 3, 0, 1});  // x0 + x2, x1 + x3
  return (h + __builtin_shuffle(h, I4{1, 0, 3, 2}))[0];
}

inline float laneMax(F4 a) {
  const F4 b = __builtin_shuffle(a, I4{1, 0, 3, 2});
  const F4 m = a > b ? a : b;  // max of lanes 0, 1 and of lanes 2, 3
  const F4 n = __builtin_shuffle(m, I4{2, 3, 0, 1});
  return (m > n ? m : n)[0];
}

}  // namespace haif::simd4
