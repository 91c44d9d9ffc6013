// The heads-up panel drawn in software onto a rendered frame: text lines plus two compact charts
// (iterations with I_min/I_max, step time stacked against the budget).
#pragma once

#include "render/canvas.h"
#include "render/frame_input.h"
#include "render/text_renderer.h"

namespace haif::render {

/// Pixel rectangle [x0,x1) x [y0,y1) the panel covers, top row first.
struct PanelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Where the panel goes for this overlay and image size (also what drawOverlay touches).
PanelRect overlayPanelRect(const Overlay& overlay, int imageWidth, int imageHeight);

/// Human-readable name of a view mode ("normal", "island", "sleep", "heat").
const char* viewModeName(ViewMode mode);

/// Draws the panel into canvas (nothing outside overlayPanelRect changes).
void drawOverlay(Canvas& canvas, TextRenderer& text, const Overlay& overlay, ViewMode mode);

}  // namespace haif::render
