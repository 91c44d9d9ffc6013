// The Renderer's frame, phase by phase, its read back, and the public class. The phases' parts are
// defined by concept: renderer_instances.cpp (what a frame draws), renderer_passes.cpp (the GL
// passes), renderer_resources.cpp (GL objects and buffers).
#include "render/renderer.h"

#include <algorithm>
#include <cstring>

#include "render/overlay.h"
#include "render/png_io.h"
#include "render/renderer_impl.h"

namespace haif::render {
namespace {

constexpr GLenum kPackInvertMesa = 0x8758;  // GL_PACK_INVERT_MESA (GL_MESA_pack_invert)

}  // namespace

// With timePhases: finishes the GL work queued so far and books the time since the last mark.
void Renderer::Impl::mark(double* phase) {
  if (!opt.timePhases) return;
  gl.Finish();
  const auto now = std::chrono::steady_clock::now();
  if (phase) *phase = std::chrono::duration<double, std::milli>(now - phaseStart).count();
  phaseStart = now;
}

bool Renderer::Impl::render(const FrameInput& f, std::vector<uint8_t>& out, std::string* error) {
  if (!ctx->makeCurrent(error)) return false;
  phases = RenderPhaseTimes{};
  mark(nullptr);
  SceneBounds bounds;
  float meanRadius = 0.5f;
  if (!classify(f, &bounds, &meanRadius, error)) return false;
  const ViewSetup view = computeView(f.camera, bounds, opt.width, opt.height, &framing);
  buildInstances(f, view);
  const size_t groupsBeforeMarkers = groups.size();
  buildContactMarkers(f, meanRadius);
  uploadInstances();
  uploadShadowStream();
  // Up to 6 camera faces per box (faces seen edge-on are kept), so one size fits both streams.
  reserveQuadIndices(std::max(boxStream.shadowFaces(), 6 * dynamicBoxes));
  mark(&phases.prepare);

  // Contact markers (the groups after groupsBeforeMarkers) cast no shadow.
  const ShadowView shadow = drawShadowMap(bounds, groupsBeforeMarkers);
  mark(&phases.shadow);

  // ---- what the camera sees of the boxes, while the rasteriser threads draw the shadow map ----
  gl.Flush();
  buildCameraFaces(f, view);
  uploadCameraStream();
  double cameraFacesMs = 0.0;
  mark(&cameraFacesMs);
  phases.prepare += cameraFacesMs;

  drawScene(view, bounds, shadow);
  mark(&phases.scene);
  drawSky(view);
  mark(&phases.sky);

  // ---- resolve + read back ----
  GLuint readFbo = msaaFbo;
  if (samples > 1) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaaFbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo);
    gl.BlitFramebuffer(0, 0, opt.width, opt.height, 0, 0, opt.width, opt.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    readFbo = resolveFbo;
  }
  mark(&phases.resolve);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  // GL row 0 is the bottom of the image; callers get the top row first.
  const size_t rowBytes = static_cast<size_t>(opt.width) * 4;
  out.resize(rowBytes * opt.height);
  if (packInvert) gl.PixelStorei(kPackInvertMesa, GL_TRUE);
  gl.ReadPixels(0, 0, opt.width, opt.height, GL_RGBA, GL_UNSIGNED_BYTE, packInvert ? out.data() : readback.data());
  if (packInvert) gl.PixelStorei(kPackInvertMesa, GL_FALSE);
  if (!checkGl("rendering", error)) return false;
  mark(&phases.readback);
  if (!packInvert)
    for (int y = 0; y < opt.height; ++y)
      std::memcpy(out.data() + rowBytes * y, readback.data() + rowBytes * (opt.height - 1 - y), rowBytes);
  mark(&phases.flip);

  if (f.overlay.enabled) {
    if (!text) {
      text = TextRenderer::create(opt.fontPath, error);
      if (!text) return false;
    }
    Canvas canvas(out.data(), opt.width, opt.height);
    drawOverlay(canvas, *text, f.overlay, f.mode);
  }
  mark(&phases.overlay);
  return true;
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

std::unique_ptr<Renderer> Renderer::create(const RendererOptions& options, std::string* error) {
  auto impl = std::make_unique<Impl>();
  impl->opt = options;
  if (!impl->init(error)) return nullptr;
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

bool Renderer::registerMesh(uint32_t meshId, const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::string* error) {
  const MeshData data = makeFlatMesh(positions, indices);
  if (data.indices.empty()) {
    if (error) *error = "renderer: mesh " + std::to_string(meshId) + " has no valid triangle";
    return false;
  }
  if (!impl_->ctx->makeCurrent(error)) return false;
  impl_->upload(data, impl_->meshes[meshId]);
  return impl_->checkGl("mesh upload", error);
}

bool Renderer::hasMesh(uint32_t meshId) const { return impl_->meshes.count(meshId) != 0; }

bool Renderer::render(const FrameInput& frame, std::vector<uint8_t>& rgba, std::string* error) {
  return impl_->render(frame, rgba, error);
}

bool Renderer::renderToPng(const FrameInput& frame, const std::string& path, std::string* error) {
  std::vector<uint8_t> rgba;
  return render(frame, rgba, error) && writePng(path, impl_->opt.width, impl_->opt.height, rgba.data(), error);
}

int Renderer::width() const { return impl_->opt.width; }
int Renderer::height() const { return impl_->opt.height; }
int Renderer::msaaSamples() const { return impl_->samples; }
const RenderPhaseTimes& Renderer::lastPhaseTimes() const { return impl_->phases; }

}  // namespace haif::render
