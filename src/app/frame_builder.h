// Glue between the simulation and the renderer: fills a render::FrameInput from a World.
#pragma once

#ifdef HAIF_HAVE_RENDER
#include "haif/world.h"
#include "render/renderer.h"
#include "scene/scene_desc.h"

#include <map>
#include <string>

namespace haif {

/// Parses a --view value (normal, island, sleep, heat); false for anything else.
bool parseViewMode(const std::string& text, render::ViewMode& out);

class FrameBuilder {
 public:
  /// Registers the hull and mesh geometry of the world's bodies with the renderer (once).
  bool registerMeshes(const World& world, render::Renderer& renderer, std::string& error);
  /// Fills `frame` (reusing its vectors) with the bodies' current transforms and state.
  void build(const World& world, const CameraDesc& camera, render::FrameInput& frame) const;

 private:
  std::map<const void*, uint32_t> meshIds_;  // geometry pointer -> render mesh id
  std::vector<uint32_t> meshOfBody_;
};

}  // namespace haif
#endif
