#include "tools/image_diff.h"

#include <algorithm>
#include <cmath>

namespace haif {

Image::Image(int w, int h, uint8_t r, uint8_t g, uint8_t b, uint8_t a) : width(w), height(h) {
  rgba.resize(size_t(w) * size_t(h) * 4);
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = a;
  }
}

namespace {

// Largest value of the weighted YIQ distance below (a pair of saturated colours); normalises it to [0,1].
constexpr double kMaxYiqDelta = 35215.0;

struct Rgb {
  double r, g, b;
};

// Straight-alpha pixel composited over white, as an image viewer shows it.
Rgb onWhite(const uint8_t* p) {
  const double a = p[3] / 255.0;
  return {255.0 + (p[0] - 255.0) * a, 255.0 + (p[1] - 255.0) * a, 255.0 + (p[2] - 255.0) * a};
}

double lumaY(const Rgb& c) { return 0.29889531 * c.r + 0.58662247 * c.g + 0.11448223 * c.b; }
double chromaI(const Rgb& c) { return 0.59597799 * c.r - 0.27417610 * c.g - 0.32180189 * c.b; }
double chromaQ(const Rgb& c) { return 0.21147017 * c.r - 0.52261711 * c.g + 0.31114694 * c.b; }

bool samePixel(const uint8_t* a, const uint8_t* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
}

// Signed brightness difference a - b (only the luma part of the YIQ distance).
double brightnessDelta(const uint8_t* a, const uint8_t* b) { return lumaY(onWhite(a)) - lumaY(onWhite(b)); }

// A pixel "in a flat area" has at least three exactly equal neighbours; the image border counts as
// one, so a flat corner still qualifies.
bool inFlatArea(const Image& img, int x, int y) {
  const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, img.width - 1);
  const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, img.height - 1);
  int equal = (x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1) ? 1 : 0;
  const uint8_t* c = img.at(x, y);
  for (int ny = y0; ny <= y1; ++ny)
    for (int nx = x0; nx <= x1; ++nx) {
      if (nx == x && ny == y) continue;
      if (samePixel(c, img.at(nx, ny)) && ++equal > 2) return true;
    }
  return false;
}

bool intersects(const PixelRect& r, int x0, int y0, int x1, int y1) {
  return r.x0 < x1 && x0 < r.x1 && r.y0 < y1 && y0 < r.y1;
}

}  // namespace

double colourDistance(const uint8_t* a, const uint8_t* b) {
  if (samePixel(a, b)) return 0.0;
  const Rgb ca = onWhite(a), cb = onWhite(b);
  const double dy = lumaY(ca) - lumaY(cb), di = chromaI(ca) - chromaI(cb), dq = chromaQ(ca) - chromaQ(cb);
  // Weights from the YIQ perceptual-difference metric: luma matters about twice as much as chroma.
  const double delta = 0.5053 * dy * dy + 0.299 * di * di + 0.1957 * dq * dq;
  return std::sqrt(std::min(1.0, delta / kMaxYiqDelta));
}

bool isAntialiased(const Image& img, const Image& other, int x, int y) {
  const int x0 = std::max(x - 1, 0), x1 = std::min(x + 1, img.width - 1);
  const int y0 = std::max(y - 1, 0), y1 = std::min(y + 1, img.height - 1);
  int equal = (x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1) ? 1 : 0;
  const uint8_t* c = img.at(x, y);
  double darkest = 0.0, brightest = 0.0;  // most negative / positive neighbour - centre brightness
  int dx = -1, dy = -1, bx = -1, by = -1;
  for (int ny = y0; ny <= y1; ++ny)
    for (int nx = x0; nx <= x1; ++nx) {
      if (nx == x && ny == y) continue;
      const double d = brightnessDelta(img.at(nx, ny), c);
      if (d == 0.0) {
        // Part of a flat area itself: an edge pixel has at most two neighbours just like it.
        if (++equal > 2) return false;
      } else if (d < darkest) {
        darkest = d, dx = nx, dy = ny;
      } else if (d > brightest) {
        brightest = d, bx = nx, by = ny;
      }
    }
  // An anti-aliased pixel blends two sides: it needs something darker and something brighter next to it.
  if (dx < 0 || bx < 0) return false;
  // ... and one of those sides must be a flat area in both images (the shape's inside or the background).
  return (inFlatArea(img, dx, dy) && inFlatArea(other, dx, dy)) ||
         (inFlatArea(img, bx, by) && inFlatArea(other, bx, by));
}

void structuralSimilarity(const Image& a, const Image& b, const std::vector<PixelRect>& masks, int window,
                          double& mean, double& worst) {
  mean = 1.0;
  worst = 1.0;
  const int w = a.width, h = a.height;
  window = std::max(2, std::min(window, std::min(w, h)));
  if (window > w || window > h) return;  // smaller than 2x2: nothing to measure
  std::vector<float> la(size_t(w) * size_t(h)), lb(la.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      la[size_t(y) * size_t(w) + size_t(x)] = float(lumaY(onWhite(a.at(x, y))));
      lb[size_t(y) * size_t(w) + size_t(x)] = float(lumaY(onWhite(b.at(x, y))));
    }
  // Stabilisers of the SSIM formula for 8-bit data (K1 = 0.01, K2 = 0.03).
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  const int stride = std::max(1, window / 2);
  double sum = 0.0;
  int64_t count = 0;
  const double n = double(window) * window;
  auto windowAt = [&](int wx, int wy) {
    for (const PixelRect& m : masks)
      if (intersects(m, wx, wy, wx + window, wy + window)) return;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sdd = 0;
    for (int y = wy; y < wy + window; ++y) {
      const float* ra = &la[size_t(y) * size_t(w)];
      const float* rb = &lb[size_t(y) * size_t(w)];
      for (int x = wx; x < wx + window; ++x) {
        const double va = ra[x], vb = rb[x], d = va - vb;
        sa += va, sb += vb, saa += va * va, sbb += vb * vb, sdd += d * d;
      }
    }
    // SSIM = l · cs with l = (2 μa μb + c1) / (μa² + μb² + c1) and cs = (2 cov + c2) / (σa² + σb² + c2),
    // written as 1 − (μa − μb)² / (μa² + μb² + c1) and 1 − σ²(a − b) / (σa² + σb² + c2): the same
    // values, but windows that agree give exactly 1 whatever the rounding (fused multiply-adds gave
    // 0.99999999999998 for identical images).
    const double ma = sa / n, mb = sb / n, dm = ma - mb;
    const double va = std::max(0.0, saa / n - ma * ma), vb = std::max(0.0, sbb / n - mb * mb);
    const double vd = std::max(0.0, sdd / n - dm * dm);
    const double s = (1.0 - dm * dm / (ma * ma + mb * mb + c1)) * (1.0 - vd / (va + vb + c2));
    sum += s;
    ++count;
    worst = std::min(worst, s);
  };
  // Window origins on a regular grid, plus the last row/column so the right and bottom edges count.
  std::vector<int> xs, ys;
  for (int x = 0; x + window <= w; x += stride) xs.push_back(x);
  if (xs.back() != w - window) xs.push_back(w - window);
  for (int y = 0; y + window <= h; y += stride) ys.push_back(y);
  if (ys.back() != h - window) ys.push_back(h - window);
  for (int y : ys)
    for (int x : xs) windowAt(x, y);
  if (count > 0) mean = sum / double(count);
}

DiffResult compareImages(const Image& ref, const Image& test, const DiffOptions& opt, Image* diffImage) {
  DiffResult r;
  const int w = ref.width, h = ref.height;
  std::vector<uint8_t> masked(size_t(w) * size_t(h), 0);
  for (const PixelRect& m : opt.masks)
    for (int y = std::max(0, m.y0); y < std::min(h, m.y1); ++y)
      for (int x = std::max(0, m.x0); x < std::min(w, m.x1); ++x) masked[size_t(y) * size_t(w) + size_t(x)] = 1;
  if (diffImage) *diffImage = Image(w, h);
  int cx0 = w, cy0 = h, cx1 = 0, cy1 = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* a = ref.at(x, y);
      const bool isMasked = masked[size_t(y) * size_t(w) + size_t(x)] != 0;
      enum { kSame, kDifferent, kAntialiased } kind = kSame;
      if (!isMasked) {
        ++r.comparedPixels;
        const double d = colourDistance(a, test.at(x, y));
        r.maxDistance = std::max(r.maxDistance, d);
        if (d > opt.threshold) {
          if (opt.detectAntialiasing && (isAntialiased(ref, test, x, y) || isAntialiased(test, ref, x, y))) {
            kind = kAntialiased;
            ++r.antialiasedPixels;
          } else {
            kind = kDifferent;
            ++r.differentPixels;
            cx0 = std::min(cx0, x), cy0 = std::min(cy0, y), cx1 = std::max(cx1, x + 1), cy1 = std::max(cy1, y + 1);
          }
        }
      }
      if (!diffImage) continue;
      uint8_t* o = diffImage->at(x, y);
      if (kind == kDifferent) {
        o[0] = 230, o[1] = 20, o[2] = 20;
      } else if (kind == kAntialiased) {
        o[0] = 250, o[1] = 200, o[2] = 0;
      } else {
        // The reference in grey, faded towards white, so the red stands out but the picture reads.
        const double g = 255.0 + (lumaY(onWhite(a)) - 255.0) * opt.fade;
        const uint8_t v = uint8_t(std::lround(std::clamp(g, 0.0, 255.0)));
        if (isMasked) o[0] = uint8_t(v * 0.80), o[1] = uint8_t(v * 0.86), o[2] = v;  // blue tint
        else o[0] = o[1] = o[2] = v;
      }
      o[3] = 255;
    }
  if (cx1 > cx0) r.changed = PixelRect{cx0, cy0, cx1, cy1};
  r.diffRatio = r.comparedPixels > 0 ? double(r.differentPixels) / double(r.comparedPixels) : 0.0;
  structuralSimilarity(ref, test, opt.masks, opt.ssimWindow, r.ssim, r.ssimMin);
  return r;
}

}  // namespace haif
