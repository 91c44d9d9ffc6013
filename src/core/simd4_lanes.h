// Four floats (and four ints) as one SIMD value, with their loads and stores: the part of
// core/simd4.h that GCC and Clang both read (the shuffles there are GCC's; headers that code built
// by Clang includes, such as the broad phase's, take only this).
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

}  // namespace haif::simd4
