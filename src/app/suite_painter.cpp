#include "app/suite_painter.h"

#ifdef HAIF_HAVE_RENDER
#include "app/frame_builder.h"
#include "render/renderer.h"
#endif

namespace haif {

#ifdef HAIF_HAVE_RENDER
namespace {

class RendererPainter : public SuiteFramePainter {
 public:
  bool begin(const Simulation& sim, int width, int height, std::string& error) override {
    // A renderer per job: jobs differ in frame size, and each registers its own scene's meshes.
    render::RendererOptions options;
    options.width = width;
    options.height = height;
    renderer_ = render::Renderer::create(options, &error);
    if (!renderer_) {
      error = "renderer: " + error;
      return false;
    }
    builder_ = FrameBuilder();
    frame_ = render::FrameInput();
    frame_.overlay.enabled = false;
    return builder_.registerMeshes(*sim.world, sim.scene, *renderer_, error);
  }

  bool paint(const Simulation& sim, std::vector<uint8_t>& rgba, std::string& error) override {
    builder_.build(*sim.world, sim.scene.camera, frame_);
    return renderer_->render(frame_, rgba, &error);
  }

 private:
  std::unique_ptr<render::Renderer> renderer_;
  FrameBuilder builder_;
  render::FrameInput frame_;
};

}  // namespace

std::unique_ptr<SuiteFramePainter> makeSuiteFramePainter() { return std::make_unique<RendererPainter>(); }
#else
std::unique_ptr<SuiteFramePainter> makeSuiteFramePainter() { return nullptr; }
#endif

}  // namespace haif
