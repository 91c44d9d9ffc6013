// The off-screen renderer: FrameInput in, RGBA pixels (top row first) out. It owns its GL context
// and every GL object; nothing here knows about the physics. Not thread-safe: use one Renderer
// per thread (each has its own context, made current by create()/render()).
#pragma once

#include "render/gl_context.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/frame_input.h"

#ifndef HAIF_SHADER_DIR
#define HAIF_SHADER_DIR "shaders"
#endif
#ifndef HAIF_FONT_PATH
#define HAIF_FONT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

namespace haif::render {

/// Settings fixed for the lifetime of a Renderer.
struct RendererOptions {
  int width = 1280;                        ///< image width in pixels
  int height = 720;                        ///< image height in pixels
  int msaaSamples = 4;                     ///< multisample count (clamped to what GL offers; 1 = off)
  int shadowMapSize = 1024;                ///< shadow map side in texels (fitted to the casters); 0 = no shadows
  std::string shaderDir = HAIF_SHADER_DIR; ///< directory holding scene/shadow/sky .vert/.frag
  std::string fontPath = HAIF_FONT_PATH;   ///< TrueType font for the overlay (loaded on first use)
  float groundMinHalfExtent = 50.f;        ///< a static Box with x or z half extent >= this is the ground
  bool cullHiddenBoxFaces = true;  ///< skip box faces lying inside another box (HiddenBoxFaces); same picture
  bool cullOccludedBoxes = true;   ///< skip boxes and box faces nearer boxes hide (BoxOcclusion); same picture
  bool timePhases = false;  ///< measure each phase of render() (adds a glFinish per phase: for profiling only)
  GlBackend gl = preferredGlBackend();  ///< OSMesa, EGL or auto (gl_context.h)
};

/// Wall time of each phase of the last render() in ms; all zero unless RendererOptions::timePhases.
struct RenderPhaseTimes {
  double prepare = 0;   ///< classify, sort, hidden faces, occlusion, uploads
  double shadow = 0;    ///< shadow map pass
  double scene = 0;     ///< main pass: bodies and ground (and the lazy depth clear)
  double sky = 0;       ///< sky behind everything
  double resolve = 0;   ///< MSAA resolve
  double readback = 0;  ///< glReadPixels
  double flip = 0;      ///< bottom-up rows to top-down
  double overlay = 0;   ///< text and charts

  /// Every phase with its name, in render order (the names reports use).
  std::array<std::pair<const char*, double>, 8> inOrder() const {
    return {{{"prepare", prepare}, {"shadow", shadow}, {"scene", scene}, {"sky", sky}, {"resolve", resolve},
             {"readback", readback}, {"flip", flip}, {"overlay", overlay}}};
  }
};

class Renderer {
 public:
  /// Creates the GL context, loads shaders from options.shaderDir and allocates all buffers.
  /// Returns nullptr and sets *error (naming the file and GLSL log for shader problems) on failure.
  static std::unique_ptr<Renderer> create(const RendererOptions& options, std::string* error);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads a mesh once for ConvexHull/TriangleMesh instances with this meshId (a repeated id
  /// replaces the old mesh). positions: xyz per vertex in body-local metres; indices: 3 per
  /// triangle, counter-clockwise seen from outside. False with *error if nothing drawable remains.
  bool registerMesh(uint32_t meshId, const std::vector<float>& positions,
                    const std::vector<uint32_t>& indices, std::string* error);
  /// True once registerMesh succeeded for meshId.
  bool hasMesh(uint32_t meshId) const;

  /// Draws one frame into rgba (resized to width*height*4; row 0 = top of the image). Returns
  /// false with *error for an unregistered meshId, a font that will not load, or a GL failure.
  bool render(const FrameInput& frame, std::vector<uint8_t>& rgba, std::string* error);
  /// render() then writePng() to path (atomically: temporary file + rename).
  bool renderToPng(const FrameInput& frame, const std::string& path, std::string* error);

  int width() const;   ///< image width in pixels
  int height() const;  ///< image height in pixels
  int msaaSamples() const;  ///< samples actually used
  /// Phase timings of the last render() (zeros unless options.timePhases).
  const RenderPhaseTimes& lastPhaseTimes() const;

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace haif::render
