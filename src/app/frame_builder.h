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
/// Applies a --gl value (osmesa, egl, auto) to every renderer the command creates; false with
/// `error` for anything else.
bool applyGlOption(const std::string& text, std::string& error);

class FrameBuilder {
 public:
  /// Registers the hull and mesh geometry of the world's bodies with the renderer (once), and the
  /// render meshes of the scene's bodies (drawn in place of their collision shapes; body i of the scene
  /// is body i of the world).
  bool registerMeshes(const World& world, const SceneDesc& scene, render::Renderer& renderer, std::string& error);
  /// Fills `frame` (reusing its vectors) with the bodies' current transforms and state.
  void build(const World& world, const CameraDesc& camera, render::FrameInput& frame) const;

 private:
  /// Registers a hull's or mesh's geometry once (other shapes need none).
  bool registerGeometry(const Shape& s, render::Renderer& renderer, std::string& error);
  /// Kind, pose, size and mesh of one drawn shape at `xf`.
  void placeShape(const Shape& s, const Transform& xf, render::Instance& in) const;
  static void setPose(const Vec3& p, const Quat& q, render::Instance& in);

  std::map<const void*, uint32_t> meshIds_;  // geometry pointer -> render mesh id
  std::vector<uint32_t> renderMeshOfBody_;  // the scene's render mesh drawn for a body (0: its shape)
  std::vector<std::vector<uint32_t>> drawnParts_;  // per compound body: the parts the scene draws
  uint32_t renderMeshes_ = 0;
};

}  // namespace haif
#endif
