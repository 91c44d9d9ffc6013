// Two set-ups of one scene side by side: each half rendered with its own overlay under a label
// naming the set-up, and a strip along the bottom that plots both sides' step time and iteration
// count on shared axes.
//
//   +-------------------+-------------------+
//   | fixed:10  (label) | adaptive:4        |
//   | scene + overlay   | scene + overlay   |
//   +-------------------+-------------------+
//   | step time: both   | iterations: both  |   strip
//   +-------------------+-------------------+
#pragma once

#ifdef HAIF_HAVE_RENDER
#include "app/clip.h"
#include "app/simulated_scene.h"
#include "render/text_renderer.h"

#include <memory>

namespace haif {

struct ComparisonOptions {
  int width = 1280, height = 720;  ///< whole frame
  int frames = -1;                 ///< video frames (-1: the scene file's count / frameEvery)
  int frameEvery = 1;              ///< steps per video frame
  int threads = 1;                 ///< solver threads of each side
  bool overlay = true;             ///< each side's overlay panel
  render::ViewMode view = render::ViewMode::Normal;
};

class ComparisonClip : public Clip {
 public:
  /// Loads the scene twice, once per set-up, and creates both renderers. One error line on failure.
  bool open(const std::string& scenePath, const std::string& leftSpec, const std::string& rightSpec,
            const ComparisonOptions& options, std::string& error);

  int frameCount() const override { return frames_; }
  bool next(std::vector<uint8_t>& rgba, std::string& error) override;
  std::vector<FrameRegion> timingRegions() const override;
  int captionBottom() const override { return labelH_ + sideH_; }

  const SimulatedScene& left() const { return *side_[0]; }
  const SimulatedScene& right() const { return *side_[1]; }

 private:
  void drawLabels(render::Canvas& canvas);
  void drawStrip(render::Canvas& canvas);

  ComparisonOptions opt_;
  std::unique_ptr<SimulatedScene> side_[2];
  std::unique_ptr<render::Renderer> renderer_[2];
  std::unique_ptr<render::TextRenderer> text_;
  render::FrameInput input_[2];
  std::vector<uint8_t> pixels_[2];
  int frames_ = 0, emitted_ = 0, totalSteps_ = 0;
  int labelH_ = 0, sideH_ = 0, stripH_ = 0, sideW_[2] = {0, 0};
};

}  // namespace haif
#endif
