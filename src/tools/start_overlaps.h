// Bodies that overlap deeply when a run starts. The solver pushes them apart at up to
// maxPushVelocity, and a deep cross (two cards of a card house through each other, 0.22 m) throws
// a scene apart in ways that look like a solver failure. A scene author wants to hear about it.
#pragma once

#include "haif/world.h"
#include "scene/scene_desc.h"

#include <string>
#include <vector>

namespace haif {

/// Overlap depth (m) from which `haif run` warns about a pair at the start: 4× the solver's 5 mm
/// slop, well past what resting contacts reach.
constexpr float kStartOverlapWarningDepth = 0.02f;

struct StartOverlap {
  uint32_t a = 0, b = 0;  ///< body ids (scene body indices)
  float depth = 0.0f;     ///< deepest point of the pair (m)
};

/// Pairs of `world`'s current contacts deeper than `minDepth`, deepest first (ties by body ids). After
/// the first step the contacts are those of the starting state: collision runs before anything moves.
std::vector<StartOverlap> deepContacts(const World& world, float minDepth);

/// One warning line per pair, at most `maxPairs`, then how many more:
/// "warning: scenes/x.json: bodies[3] "card" and bodies[4] overlap by 0.220 m at the start; ...".
std::string describeStartOverlaps(const SceneDesc& scene, const std::vector<StartOverlap>& overlaps,
                                  size_t maxPairs);

}  // namespace haif
