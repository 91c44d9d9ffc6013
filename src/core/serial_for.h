// The one-thread stand-in for the `parallelFor(n, grain, f)` that the step's stages take
// (TurnProjection, IslandBuilder, IslandSplitter): f(0, n) on the calling thread.
#pragma once

#include <cstdint>

namespace haif {

inline constexpr auto serialFor = [](uint32_t n, uint32_t /*grain*/, auto&& f) {
  if (n > 0) f(0u, n);
};

}  // namespace haif
