// Title cards and captions of `haif reel`, drawn in software with the FreeType text renderer.
#pragma once

#ifdef HAIF_HAVE_RENDER
#include "app/clip.h"
#include "render/text_renderer.h"

#include <memory>

namespace haif {

/// A still card: a large title, an accent rule and a smaller subtitle on a dark gradient.
class TitleCardClip : public Clip {
 public:
  bool open(const std::string& title, const std::string& subtitle, int width, int height, int frames,
            std::string& error);
  int frameCount() const override { return frames_; }
  bool next(std::vector<uint8_t>& rgba, std::string& error) override;
  std::vector<FrameRegion> timingRegions() const override { return {}; }
  int captionBottom() const override { return height_; }

 private:
  std::vector<uint8_t> card_;  // drawn once, repeated
  int width_ = 0, height_ = 0, frames_ = 0;
};

/// Draws `caption` centred on a translucent band whose bottom edge is `bottom` (pixels from the top).
/// Long captions shrink to fit the width.
void drawCaption(render::Canvas& canvas, render::TextRenderer& text, const std::string& caption, int bottom);

}  // namespace haif
#endif
