// Sort keys: a float and an index packed into one unsigned integer, so that a plain integer sort
// gives the order "by value, ties by index" (a total order: deterministic). Sorting these directly
// was about twice as fast as sorting indices through a comparison that looks the values up.
#pragma once

#include <cstdint>
#include <cstring>

namespace haif {

/// The float's bits, remapped so that unsigned order is numeric order (-0 and +0 map alike).
inline uint32_t orderedBits(float value) {
  value += 0.0f;  // -0 becomes +0: equal values tie, as they compare
  uint32_t u;
  std::memcpy(&u, &value, sizeof u);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

/// Sorts by value ascending, then index ascending.
inline uint64_t ascendingKey(float value, uint32_t index) { return (uint64_t(orderedBits(value)) << 32) | index; }

/// Sorts by value descending, then index ascending.
inline uint64_t descendingKey(float value, uint32_t index) { return (uint64_t(~orderedBits(value)) << 32) | index; }

/// The index a key was made with.
inline uint32_t keyIndex(uint64_t key) { return uint32_t(key); }

}  // namespace haif
