#include "app/scene_clip.h"

#ifdef HAIF_HAVE_RENDER
#include "render/overlay.h"

namespace haif {

bool SceneClip::open(const std::string& scenePath, const std::string& spec, const SceneClipOptions& options,
                     std::string& error) {
  opt_ = options;
  scene_ = makeSimulatedScene(scenePath, spec, opt_.threads, error);
  if (!scene_ || !checkStepsAvailable(*scene_, opt_.frames * opt_.frameEvery, error)) return false;
  render::RendererOptions ro;
  ro.width = opt_.width;
  ro.height = opt_.height;
  renderer_ = render::Renderer::create(ro, &error);
  if (!renderer_) {
    error = "renderer: " + error;
    return false;
  }
  if (!scene_->prepare(*renderer_, error)) {
    error = scenePath + ": " + error;
    return false;
  }
  input_.mode = opt_.view;
  input_.overlay.enabled = opt_.overlay;
  return true;
}

bool SceneClip::next(std::vector<uint8_t>& rgba, std::string& error) {
  {
    const EncodingHold hold(holdWhileStepping_);  // the sink encodes while the frame is drawn
    for (int k = 0; k < opt_.frameEvery; ++k)
      if (!scene_->step(error)) return false;
  }
  scene_->buildFrame(input_);
  return renderer_->render(input_, rgba, &error);
}

std::vector<FrameRegion> SceneClip::timingRegions() const {
  if (!opt_.overlay) return {};
  const render::PanelRect r = render::overlayPanelRect(input_.overlay, opt_.width, opt_.height);
  return {{"overlay", PixelRect{r.x0, r.y0, r.x1, r.y1}}};
}

}  // namespace haif
#endif
