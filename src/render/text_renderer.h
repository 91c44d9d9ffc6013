// FreeType text drawn onto a Canvas. Glyph bitmaps are cached per pixel size, so steady-state
// frames do no FreeType work. Created only when text is actually needed.
#pragma once

#include <memory>
#include <string>

#include "render/canvas.h"

namespace haif::render {

class TextRenderer {
 public:
  /// Loads the font; nullptr and *error (naming the file) when FreeType cannot open it.
  static std::unique_ptr<TextRenderer> create(const std::string& fontPath, std::string* error);
  ~TextRenderer();

  /// Draws UTF-8 text with its baseline at y starting at x; returns the advance in pixels.
  float draw(Canvas& canvas, float x, float baselineY, const std::string& utf8, int pixelSize, Rgba color);
  /// Draws text rotated 90 degrees counter-clockwise (reads bottom to top) with its baseline on
  /// column x and its start at row y.
  void drawVertical(Canvas& canvas, float x, float startY, const std::string& utf8, int pixelSize,
                    Rgba color);
  /// Width in pixels the text would advance.
  float measure(const std::string& utf8, int pixelSize);
  /// Distance from baseline to the top of capitals (approximately), in pixels.
  float ascent(int pixelSize);

 private:
  struct Impl;
  explicit TextRenderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace haif::render
