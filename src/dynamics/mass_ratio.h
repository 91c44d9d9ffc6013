// Bodies whose masses differ: sweeps pass a heavy body's push through a light one a sliver per
// sweep, so an island with a contact between such bodies is solved together instead (the small-island
// solve, World::wantsSmallIslandSolve; a joint tree's coupled solve, jointsCarryContacts).
#pragma once

#include <algorithm>

namespace haif {

/// Whether two masses differ `ratio` times or more. Symmetric, so inverse masses serve as well; the
/// caller says which bodies count (a static body's mass is 0, its inverse mass too).
inline bool massesDiffer(float a, float b, float ratio) { return std::max(a, b) >= ratio * std::min(a, b); }

}  // namespace haif
