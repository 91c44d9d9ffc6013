// One scene under one set-up, full frame with its overlay panel: a clip of `haif reel`.
#pragma once

#ifdef HAIF_HAVE_RENDER
#include "app/clip.h"
#include "app/simulated_scene.h"

#include <memory>

namespace haif {

struct SceneClipOptions {
  int width = 1280, height = 720;
  int frames = 150;       ///< video frames
  int frameEvery = 1;     ///< steps per video frame
  int threads = 1;
  bool overlay = true;
  render::ViewMode view = render::ViewMode::Normal;
};

class SceneClip : public Clip {
 public:
  bool open(const std::string& scenePath, const std::string& spec, const SceneClipOptions& options,
            std::string& error);
  int frameCount() const override { return opt_.frames; }
  bool next(std::vector<uint8_t>& rgba, std::string& error) override;
  std::vector<FrameRegion> timingRegions() const override;
  int captionBottom() const override { return opt_.height; }

 private:
  SceneClipOptions opt_;
  std::unique_ptr<SimulatedScene> scene_;
  std::unique_ptr<render::Renderer> renderer_;
  render::FrameInput input_;
};

}  // namespace haif
#endif
