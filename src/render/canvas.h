// Software 2D drawing on an RGBA8 image (top row first): anti-aliased lines, rectangles, spans and
// coverage masks. Used for the overlay panel and the standalone charts, so neither needs GL.
// Blending happens on the stored (sRGB) values, as UI drawing usually does.
#pragma once

#include <cstdint>

namespace haif::render {

/// sRGB colour with straight alpha (opacity).
struct Rgba {
  uint8_t r = 0, g = 0, b = 0, a = 255;
};

class Canvas {
 public:
  /// A view onto width*height*4 bytes owned by the caller; row 0 is the top.
  Canvas(uint8_t* rgba, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  uint8_t* data() { return rgba_; }

  /// Limits drawing to [x0,x1) x [y0,y1) (intersected with the image).
  void setClip(int x0, int y0, int x1, int y1);
  void resetClip() { setClip(0, 0, width_, height_); }

  /// Sets every pixel to c (no blending).
  void clear(Rgba c);
  /// Blends c into one pixel with extra coverage in [0,1].
  void blend(int x, int y, Rgba c, float coverage);
  /// Axis-aligned rectangle in pixel coordinates with fractional (anti-aliased) borders.
  void fillRect(float x0, float y0, float x1, float y1, Rgba c);
  /// Line of the given width with round ends, anti-aliased by distance to the segment.
  void line(float x0, float y0, float x1, float y1, float width, Rgba c);
  /// Dashed line: dash and gap lengths in pixels.
  void dashedLine(float x0, float y0, float x1, float y1, float width, float dash, float gap, Rgba c);
  /// Column x filled between yTop and yBottom (yTop < yBottom), anti-aliased at both ends.
  void verticalSpan(int x, float yTop, float yBottom, Rgba c);
  /// 8-bit coverage mask (e.g. a glyph) placed with its top-left corner at (x, y).
  void blendMask(int x, int y, const uint8_t* mask, int maskWidth, int maskHeight, int pitch, Rgba c);

 private:
  uint8_t* rgba_;
  int width_, height_;
  int clipX0_ = 0, clipY0_ = 0, clipX1_ = 0, clipY1_ = 0;
};

}  // namespace haif::render
