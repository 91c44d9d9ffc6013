#include "tools/engine_run.h"

#include "core/pose_hash.h"

namespace haif {

uint64_t hashPoses(const std::vector<BodySample>& bodies) {
  PoseHash h;
  for (const BodySample& b : bodies) h.add(b.p, b.q);
  return h.value();
}

}  // namespace haif
