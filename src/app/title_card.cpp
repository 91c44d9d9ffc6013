#include "app/title_card.h"

#ifdef HAIF_HAVE_RENDER
#include "render/renderer.h"

#include <algorithm>
#include <cmath>

namespace haif {

namespace {

float uiScale(int height) { return std::clamp(height / 720.f, 0.5f, 3.f); }

// Draws `s` centred on column cx with its baseline at y, shrinking the size until it fits maxWidth.
void centred(render::Canvas& canvas, render::TextRenderer& text, const std::string& s, float cx, float y, int size,
             float maxWidth, render::Rgba colour) {
  while (size > 8 && text.measure(s, size) > maxWidth) --size;
  text.draw(canvas, cx - text.measure(s, size) * 0.5f, y, s, size, colour);
}

}  // namespace

bool TitleCardClip::open(const std::string& title, const std::string& subtitle, int width, int height, int frames,
                         std::string& error) {
  auto text = render::TextRenderer::create(render::RendererOptions{}.fontPath, &error);
  if (!text) return false;
  width_ = width;
  height_ = height;
  frames_ = frames;
  card_.assign(size_t(width) * size_t(height) * 4, 255);
  // Vertical gradient from deep navy to slate: the same palette as the overlay panels.
  for (int y = 0; y < height; ++y) {
    const float t = float(y) / float(std::max(1, height - 1));
    const uint8_t r = uint8_t(14 + 18 * t), g = uint8_t(18 + 22 * t), b = uint8_t(28 + 34 * t);
    for (int x = 0; x < width; ++x) {
      uint8_t* p = &card_[(size_t(y) * size_t(width) + size_t(x)) * 4];
      p[0] = r, p[1] = g, p[2] = b;
    }
  }
  render::Canvas canvas(card_.data(), width, height);
  const float s = uiScale(height), cx = width * 0.5f, maxW = width * 0.86f;
  const int big = std::max(14, int(std::lround(58.f * s))), small = std::max(10, int(std::lround(24.f * s)));
  const float titleBase = height * 0.46f;
  centred(canvas, *text, title, cx, titleBase, big, maxW, render::Rgba{240, 242, 247, 255});
  // Accent rule in the comparison colours (blue and orange halves).
  const float ruleY = titleBase + 22.f * s, half = std::min(width * 0.18f, 180.f * s);
  canvas.fillRect(cx - half, ruleY, cx, ruleY + std::max(2.f, 3.f * s), render::Rgba{77, 163, 255, 255});
  canvas.fillRect(cx, ruleY, cx + half, ruleY + std::max(2.f, 3.f * s), render::Rgba{255, 159, 64, 255});
  if (!subtitle.empty())
    centred(canvas, *text, subtitle, cx, ruleY + 24.f * s + text->ascent(small), small, maxW,
            render::Rgba{170, 178, 194, 255});
  return true;
}

bool TitleCardClip::next(std::vector<uint8_t>& rgba, std::string&) {
  rgba = card_;
  return true;
}

void drawCaption(render::Canvas& canvas, render::TextRenderer& text, const std::string& caption, int bottom) {
  if (caption.empty()) return;
  const float s = uiScale(canvas.height());
  int size = std::max(10, int(std::lround(22.f * s)));
  const float maxW = canvas.width() * 0.9f;
  while (size > 8 && text.measure(caption, size) > maxW) --size;
  const float pad = std::round(10.f * s), margin = std::round(14.f * s);
  const float w = text.measure(caption, size) + 2 * pad, h = size * 1.2f + 2 * pad;
  const float x0 = (canvas.width() - w) * 0.5f, y1 = float(bottom) - margin, y0 = y1 - h;
  canvas.fillRect(x0, y0, x0 + w, y1, render::Rgba{10, 12, 18, 185});
  text.draw(canvas, x0 + pad, y0 + pad + size * 0.6f + text.ascent(size) * 0.5f, caption, size,
            render::Rgba{245, 246, 250, 255});
}

}  // namespace haif
#endif
