// Sleep: islands that rested long enough stop being stepped until something touches them.
#include "haif/world_internal.h"

namespace haif {

void World::putIslandToSleep(const Island& isl) {
  const int32_t set = sleepSets_.open();
  for (uint32_t j = 0; j < isl.bodyCount; ++j) {
    const uint32_t i = islands_.bodies[isl.firstBody + j];
    bodies_.asleep[i] = 1;
    bodies_.sleepSet[i] = set;
    bodies_.v[i].setZero();
    bodies_.w[i].setZero();
    sleepSets_.add(set, i);
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
