#include "render/text_renderer.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace haif::render {
namespace {

struct Glyph {
  std::vector<uint8_t> bitmap;  // coverage, width*rows, tightly packed
  int width = 0, rows = 0;
  int left = 0, top = 0;        // bearing from pen position (top is up from the baseline)
  float advance = 0.f;
};

// Decodes one UTF-8 code point and advances i; malformed bytes become U+FFFD.
uint32_t nextCodePoint(const std::string& s, size_t& i) {
  const auto b = static_cast<unsigned char>(s[i++]);
  if (b < 0x80) return b;
  int extra = (b >= 0xf0) ? 3 : (b >= 0xe0) ? 2 : (b >= 0xc0) ? 1 : -1;
  if (extra < 0) return 0xfffd;
  uint32_t cp = b & (0x3f >> extra);
  for (; extra > 0; --extra) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xc0) != 0x80) return 0xfffd;
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3f);
  }
  return cp;
}

}  // namespace

struct TextRenderer::Impl {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  int currentSize = 0;
  std::unordered_map<uint64_t, Glyph> cache;

  ~Impl() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }

  const Glyph& glyph(uint32_t cp, int size) {
    const uint64_t key = (static_cast<uint64_t>(size) << 32) | cp;
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    Glyph g;
    if (size != currentSize) {
      FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(size));
      currentSize = size;
    }
    if (FT_Load_Char(face, cp, FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT) == 0) {
      const FT_GlyphSlot slot = face->glyph;
      g.width = static_cast<int>(slot->bitmap.width);
      g.rows = static_cast<int>(slot->bitmap.rows);
      g.left = slot->bitmap_left;
      g.top = slot->bitmap_top;
      g.advance = static_cast<float>(slot->advance.x) / 64.f;
      g.bitmap.resize(static_cast<size_t>(g.width) * g.rows);
      for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.width; ++c)
          g.bitmap[r * g.width + c] = slot->bitmap.buffer[r * slot->bitmap.pitch + c];
    }
    return cache.emplace(key, std::move(g)).first->second;
  }
};

TextRenderer::TextRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TextRenderer::~TextRenderer() = default;

std::unique_ptr<TextRenderer> TextRenderer::create(const std::string& fontPath, std::string* error) {
  auto impl = std::make_unique<Impl>();
  if (FT_Init_FreeType(&impl->library) != 0) {
    if (error) *error = "FreeType: initialisation failed";
    return nullptr;
  }
  if (FT_New_Face(impl->library, fontPath.c_str(), 0, &impl->face) != 0) {
    if (error) *error = "FreeType: cannot load font '" + fontPath + "'";
    return nullptr;
  }
  return std::unique_ptr<TextRenderer>(new TextRenderer(std::move(impl)));
}

float TextRenderer::draw(Canvas& canvas, float x, float baselineY, const std::string& utf8,
                         int pixelSize, Rgba color) {
  float pen = x;
  const int base = static_cast<int>(std::lround(baselineY));
  for (size_t i = 0; i < utf8.size();) {
    const Glyph& g = impl_->glyph(nextCodePoint(utf8, i), pixelSize);
    canvas.blendMask(static_cast<int>(std::lround(pen)) + g.left, base - g.top, g.bitmap.data(), g.width,
                     g.rows, g.width, color);
    pen += g.advance;
  }
  return pen - x;
}

void TextRenderer::drawVertical(Canvas& canvas, float x, float startY, const std::string& utf8,
                                int pixelSize, Rgba color) {
  // Rotating CCW maps glyph (column c, row r) to canvas (x - top + r, pen - left - c).
  float pen = startY;
  const int bx = static_cast<int>(std::lround(x));
  for (size_t i = 0; i < utf8.size();) {
    const Glyph& g = impl_->glyph(nextCodePoint(utf8, i), pixelSize);
    const int py = static_cast<int>(std::lround(pen));
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.width; ++c) {
        const uint8_t m = g.bitmap[r * g.width + c];
        if (m) canvas.blend(bx - g.top + r, py - g.left - c, color, m / 255.f);
      }
    pen -= g.advance;
  }
}

float TextRenderer::measure(const std::string& utf8, int pixelSize) {
  float w = 0.f;
  for (size_t i = 0; i < utf8.size();) w += impl_->glyph(nextCodePoint(utf8, i), pixelSize).advance;
  return w;
}

float TextRenderer::ascent(int pixelSize) {
  return static_cast<float>(impl_->glyph('H', pixelSize).top);
}

}  // namespace haif::render
