// Reading one entry of "generators" and expanding it into bodies (see generators.h for the layouts).
#pragma once

#include "scene/body_parse.h"

#include <vector>

namespace haif {

/// Most bodies one scene may hold: catches typos such as a count of 1e7 before memory runs out.
inline constexpr int64_t kMaxSceneBodies = 1000000;

/// Expands generator `node` (place "generators[i]") and appends its bodies (where "generators[i] #k")
/// to `out` and their source pointer to ctx.bodyPointers. Throws SceneError on bad parameters.
void expandGenerator(const JsonNode& node, ParseContext& ctx, std::vector<BodyDesc>& out);

}  // namespace haif
