// Comparing two rendered images for visual regression: a per-pixel perceptual colour difference
// (YIQ distance, the idea behind pixelmatch) that forgives anti-aliased edges, plus SSIM on luma.
// Pure pixel work: no files, no rendering.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// RGBA8 pixels, top row first.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  ///< width * height * 4 bytes

  Image() = default;
  Image(int w, int h, uint8_t r = 0, uint8_t g = 0, uint8_t b = 0, uint8_t a = 255);
  uint8_t* at(int x, int y) { return &rgba[4 * (size_t(y) * size_t(width) + size_t(x))]; }
  const uint8_t* at(int x, int y) const { return &rgba[4 * (size_t(y) * size_t(width) + size_t(x))]; }
};

/// Pixel rectangle [x0,x1) x [y0,y1), top row first.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

/// How two images are compared.
struct DiffOptions {
  double threshold = 0.1;       ///< colour distance in [0,1] above which a pixel differs (YIQ, 1 = black vs white)
  bool detectAntialiasing = true;  ///< pixels that are anti-aliased edges in either image do not count
  std::vector<PixelRect> masks; ///< regions left out of every metric
  int ssimWindow = 8;           ///< SSIM window side in pixels (windows overlap by half)
  double fade = 0.2;            ///< diff image: how much of the reference shows through (0 = white)
};

/// What compareImages found.
struct DiffResult {
  int64_t comparedPixels = 0;     ///< pixels outside every mask
  int64_t differentPixels = 0;    ///< compared pixels whose colour distance exceeds the threshold
  int64_t antialiasedPixels = 0;  ///< over the threshold but forgiven as anti-aliasing
  double diffRatio = 0.0;         ///< differentPixels / comparedPixels (0 when nothing is compared)
  double maxDistance = 0.0;       ///< largest colour distance of a compared pixel, in [0,1]
  double ssim = 1.0;              ///< mean SSIM over windows that touch no mask (1 = identical)
  double ssimMin = 1.0;           ///< worst window
  PixelRect changed;              ///< bounding box of the differing pixels (empty if none)
};

/// Perceptual colour distance of two RGBA pixels in [0,1] (alpha blended onto white first).
double colourDistance(const uint8_t* a, const uint8_t* b);

/// True when pixel (x, y) of `img` looks like an anti-aliased edge pixel: it lies between a darker
/// and a brighter neighbour, each of which sits in a flat area of both `img` and `other`.
bool isAntialiased(const Image& img, const Image& other, int x, int y);

/// Mean (and worst) SSIM of the luma of a and b over windows that avoid `masks`.
void structuralSimilarity(const Image& a, const Image& b, const std::vector<PixelRect>& masks, int window,
                          double& mean, double& worst);

/// Compares `reference` and `test` (same size, checked by the caller). When `diffImage` is given it
/// receives the reference faded towards white with differing pixels red, forgiven anti-aliasing
/// yellow and masked regions tinted blue.
DiffResult compareImages(const Image& reference, const Image& test, const DiffOptions& options,
                         Image* diffImage = nullptr);

}  // namespace haif
