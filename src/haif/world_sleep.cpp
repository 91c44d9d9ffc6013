// Sleep: islands that rested long enough stop being stepped until something touches them.
#include "haif/world_internal.h"

namespace haif {

void World::putIslandToSleep(const Island& isl) {
  int32_t set;
  if (!freeSleepSets_.empty()) {
    set = freeSleepSets_.back();
    freeSleepSets_.pop_back();
  } else {
    set = static_cast<int32_t>(sleepSets_.size());
    sleepSets_.emplace_back();
  }
  auto& members = sleepSets_[set];
  for (uint32_t j = 0; j < isl.bodyCount; ++j) {
    const uint32_t i = islands_.bodies[isl.firstBody + j];
    bodies_.asleep[i] = 1;
    bodies_.sleepSet[i] = set;
    bodies_.v[i].setZero();
    bodies_.w[i].setZero();
    members.push_back(i);
  }
}

void World::detectSleep() {
  for (const Island& isl : islands_.islands) {
    float minRest = 1e30f;
    for (uint32_t j = 0; j < isl.bodyCount; ++j)
      minRest = std::min(minRest, bodies_.restTime[islands_.bodies[isl.firstBody + j]]);
    if (minRest >= settings_.timeToSleep) putIslandToSleep(isl);
  }
}

}  // namespace haif
