#include "render/canvas.h"

#include <algorithm>
#include <cmath>

namespace haif::render {

Canvas::Canvas(uint8_t* rgba, int width, int height) : rgba_(rgba), width_(width), height_(height) {
  resetClip();
}

void Canvas::setClip(int x0, int y0, int x1, int y1) {
  clipX0_ = std::clamp(x0, 0, width_);
  clipY0_ = std::clamp(y0, 0, height_);
  clipX1_ = std::clamp(x1, clipX0_, width_);
  clipY1_ = std::clamp(y1, clipY0_, height_);
}

void Canvas::clear(Rgba c) {
  for (int i = 0; i < width_ * height_; ++i) {
    uint8_t* p = rgba_ + 4 * i;
    p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
  }
}

void Canvas::blend(int x, int y, Rgba c, float coverage) {
  if (x < clipX0_ || y < clipY0_ || x >= clipX1_ || y >= clipY1_) return;
  const float a = std::clamp(coverage, 0.f, 1.f) * (c.a / 255.f);
  if (a <= 0.f) return;
  uint8_t* p = rgba_ + 4 * (static_cast<size_t>(y) * width_ + x);
  // Each value lies between two bytes, so +0.5 and truncation round it (lround is a libm call,
  // and the overlay blends every pixel of its panel each frame).
  p[0] = static_cast<uint8_t>(p[0] + (c.r - p[0]) * a + 0.5f);
  p[1] = static_cast<uint8_t>(p[1] + (c.g - p[1]) * a + 0.5f);
  p[2] = static_cast<uint8_t>(p[2] + (c.b - p[2]) * a + 0.5f);
  p[3] = static_cast<uint8_t>(p[3] + (255 - p[3]) * a + 0.5f);
}

void Canvas::fillRect(float x0, float y0, float x1, float y1, Rgba c) {
  if (x1 < x0) std::swap(x0, x1);
  if (y1 < y0) std::swap(y0, y1);
  const int ix0 = std::max(static_cast<int>(std::floor(x0)), clipX0_);
  const int iy0 = std::max(static_cast<int>(std::floor(y0)), clipY0_);
  const int ix1 = std::min(static_cast<int>(std::ceil(x1)), clipX1_);
  const int iy1 = std::min(static_cast<int>(std::ceil(y1)), clipY1_);
  for (int y = iy0; y < iy1; ++y) {
    const float cy = std::min(y1, y + 1.f) - std::max(y0, static_cast<float>(y));
    for (int x = ix0; x < ix1; ++x) {
      const float cx = std::min(x1, x + 1.f) - std::max(x0, static_cast<float>(x));
      if (cx < 1.f) {
        blend(x, y, c, cx * cy);
        continue;
      }
      // Whole columns: the same arithmetic as blend() with the coverage worked out once.
      int xe = x;
      while (xe + 1 < ix1 && std::min(x1, xe + 2.f) - static_cast<float>(xe + 1) >= 1.f) ++xe;
      const float a = std::clamp(cy, 0.f, 1.f) * (c.a / 255.f);
      if (a > 0.f) {
        uint8_t* p = rgba_ + 4 * (static_cast<size_t>(y) * width_ + x);
        for (int k = x; k <= xe; ++k, p += 4) {
          p[0] = static_cast<uint8_t>(p[0] + (c.r - p[0]) * a + 0.5f);
          p[1] = static_cast<uint8_t>(p[1] + (c.g - p[1]) * a + 0.5f);
          p[2] = static_cast<uint8_t>(p[2] + (c.b - p[2]) * a + 0.5f);
          p[3] = static_cast<uint8_t>(p[3] + (255 - p[3]) * a + 0.5f);
        }
      }
      x = xe;
    }
  }
}

void Canvas::line(float x0, float y0, float x1, float y1, float width, Rgba c) {
  const float h = width * 0.5f;
  const float pad = h + 1.f;
  const int bx0 = std::max(static_cast<int>(std::floor(std::min(x0, x1) - pad)), clipX0_);
  const int by0 = std::max(static_cast<int>(std::floor(std::min(y0, y1) - pad)), clipY0_);
  const int bx1 = std::min(static_cast<int>(std::ceil(std::max(x0, x1) + pad)), clipX1_);
  const int by1 = std::min(static_cast<int>(std::ceil(std::max(y0, y1) + pad)), clipY1_);
  const float dx = x1 - x0, dy = y1 - y0;
  const float len2 = dx * dx + dy * dy;
  for (int y = by0; y < by1; ++y)
    for (int x = bx0; x < bx1; ++x) {
      // Distance from the pixel centre to the segment; coverage ramps over one pixel.
      const float px = x + 0.5f - x0, py = y + 0.5f - y0;
      const float t = len2 > 0.f ? std::clamp((px * dx + py * dy) / len2, 0.f, 1.f) : 0.f;
      const float ex = px - t * dx, ey = py - t * dy;
      const float d = std::sqrt(ex * ex + ey * ey);
      const float cov = std::min(h + 0.5f - d, 1.f);
      // Thin lines keep their total ink: scale by width when narrower than a pixel.
      if (cov > 0.f) blend(x, y, c, width < 1.f ? cov * width : cov);
    }
}

void Canvas::dashedLine(float x0, float y0, float x1, float y1, float width, float dash, float gap,
                        Rgba c) {
  const float dx = x1 - x0, dy = y1 - y0;
  const float len = std::sqrt(dx * dx + dy * dy);
  if (len <= 0.f || dash <= 0.f) return;
  const float ux = dx / len, uy = dy / len;
  for (float s = 0.f; s < len; s += dash + gap) {
    const float e = std::min(s + dash, len);
    line(x0 + ux * s, y0 + uy * s, x0 + ux * e, y0 + uy * e, width, c);
  }
}

void Canvas::verticalSpan(int x, float yTop, float yBottom, Rgba c) {
  if (yBottom <= yTop) return;
  fillRect(static_cast<float>(x), yTop, x + 1.f, yBottom, c);
}

void Canvas::blendMask(int x, int y, const uint8_t* mask, int maskWidth, int maskHeight, int pitch,
                       Rgba c) {
  for (int j = 0; j < maskHeight; ++j)
    for (int i = 0; i < maskWidth; ++i) {
      const uint8_t m = mask[j * pitch + i];
      if (m) blend(x + i, y + j, c, m / 255.f);
    }
}

}  // namespace haif::render
