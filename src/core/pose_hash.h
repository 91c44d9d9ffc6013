// FNV-1a over the bits of body poses: the `state_hash` of docs/metrics.md. Equal states give equal
// hashes; one definition serves the World and the engine-comparison tools (Bullet runs hash the
// same way, so hashes of the two engines are computed alike).
#pragma once

#include "core/math.h"

#include <cstdint>
#include <cstring>

namespace haif {

class PoseHash {
 public:
  void add(const Vec3& p, const Quat& q) {
    mix(p.x()), mix(p.y()), mix(p.z());
    mix(q.x()), mix(q.y()), mix(q.z()), mix(q.w());
  }
  uint64_t value() const { return h_; }

 private:
  void mix(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    for (int k = 0; k < 4; ++k) {
      h_ ^= (u >> (8 * k)) & 0xffu;
      h_ *= 1099511628211ull;
    }
  }
  uint64_t h_ = 1469598103934665603ull;
};

}  // namespace haif
