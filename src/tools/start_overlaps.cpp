#include "tools/start_overlaps.h"

#include <algorithm>
#include <cstdio>

namespace haif {

std::vector<StartOverlap> deepContacts(const World& world, float minDepth) {
  std::vector<StartOverlap> out;
  for (const Contact& c : world.contacts()) {
    const float depth = c.manifold.deepest();
    if (depth > minDepth) out.push_back({std::min(c.a, c.b), std::max(c.a, c.b), depth});
  }
  std::sort(out.begin(), out.end(), [](const StartOverlap& x, const StartOverlap& y) {
    if (x.depth != y.depth) return x.depth > y.depth;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  return out;
}

namespace {

std::string bodyLabel(const SceneDesc& scene, uint32_t id) {
  if (id >= scene.bodies.size()) return "body " + std::to_string(id);
  const BodyDesc& b = scene.bodies[id];
  std::string label = b.where.empty() ? "body " + std::to_string(id) : b.where;
  if (!b.name.empty()) label += " \"" + b.name + "\"";
  return label;
}

}  // namespace

std::string describeStartOverlaps(const SceneDesc& scene, const std::vector<StartOverlap>& overlaps,
                                  size_t maxPairs) {
  std::string text;
  const std::string file = scene.sourcePath.empty() ? scene.name : scene.sourcePath;
  for (size_t i = 0; i < overlaps.size() && i < maxPairs; ++i) {
    char depth[32];
    std::snprintf(depth, sizeof depth, "%.3f", double(overlaps[i].depth));
    text += "warning: " + file + ": " + bodyLabel(scene, overlaps[i].a) + " and " + bodyLabel(scene, overlaps[i].b) +
            " overlap by " + depth + " m at the start; the solver pushes them apart, which can throw the scene" +
            " around: check their positions and sizes\n";
  }
  if (overlaps.size() > maxPairs)
    text += "warning: " + file + ": and " + std::to_string(overlaps.size() - maxPairs) +
            " more pairs overlap by more than " + std::to_string(int(kStartOverlapWarningDepth * 1000.0f)) +
            " mm at the start\n";
  return text;
}

}  // namespace haif
