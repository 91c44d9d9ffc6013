#include "tools/engine_run.h"

#include <cstring>

namespace haif {

uint64_t hashPoses(const std::vector<BodySample>& bodies) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    for (int k = 0; k < 4; ++k) {
      h ^= (u >> (8 * k)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  for (const BodySample& b : bodies) {
    mix(b.p.x()), mix(b.p.y()), mix(b.p.z());
    mix(b.q.x()), mix(b.q.y()), mix(b.q.z()), mix(b.q.w());
  }
  return h;
}

}  // namespace haif
