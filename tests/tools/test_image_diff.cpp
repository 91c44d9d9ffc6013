// The pixel comparison behind `haif diff`, on synthetic images where the right answer is known.
#include "tools/image_diff.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace haif {
namespace {

// A picture with structure everywhere (so SSIM windows are not flat): smooth gradients plus a
// checker of 8x8 tiles.
Image texturedImage(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.at(x, y);
      const bool tile = ((x / 8) + (y / 8)) % 2 == 0;
      p[0] = uint8_t(40 + (x * 150) / w);
      p[1] = uint8_t(tile ? 170 : 90);
      p[2] = uint8_t(60 + (y * 120) / h);
    }
  return img;
}

void fillBlock(Image& img, int x0, int y0, int x1, int y1, uint8_t r, uint8_t g, uint8_t b) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      uint8_t* p = img.at(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
}

TEST(ColourDistance, ZeroForEqualLargeForBlackAndWhiteAndSmallForNearColours) {
  const uint8_t black[4] = {0, 0, 0, 255}, white[4] = {255, 255, 255, 255};
  const uint8_t grey[4] = {128, 128, 128, 255}, nearGrey[4] = {131, 128, 127, 255};
  EXPECT_EQ(colourDistance(grey, grey), 0.0);
  EXPECT_GT(colourDistance(black, white), 0.9);
  EXPECT_LE(colourDistance(black, white), 1.0);
  EXPECT_LT(colourDistance(grey, nearGrey), 0.05);
  EXPECT_GT(colourDistance(grey, nearGrey), 0.0);
  // A transparent pixel shows as the white behind it.
  const uint8_t clear[4] = {0, 0, 0, 0};
  EXPECT_LT(colourDistance(clear, white), 1e-9);
  // Equal luma, different hue still counts: red and a green of the same brightness differ.
  const uint8_t red[4] = {200, 60, 60, 255}, green[4] = {70, 130, 60, 255};
  EXPECT_GT(colourDistance(red, green), 0.1);
}

TEST(CompareImages, IdenticalImagesAreClean) {
  const Image a = texturedImage(96, 64);
  Image diff;
  const DiffResult r = compareImages(a, a, DiffOptions{}, &diff);
  EXPECT_EQ(r.differentPixels, 0);
  EXPECT_EQ(r.antialiasedPixels, 0);
  EXPECT_EQ(r.comparedPixels, 96 * 64);
  EXPECT_EQ(r.diffRatio, 0.0);
  EXPECT_NEAR(r.ssim, 1.0, 1e-12);
  EXPECT_TRUE(r.changed.empty());
  ASSERT_EQ(diff.width, 96);
  ASSERT_EQ(diff.height, 64);
  // No red anywhere in the diff image: every pixel is the faded grey reference.
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x) EXPECT_EQ(diff.at(x, y)[0], diff.at(x, y)[2]);
}

TEST(CompareImages, OneChangedBlockIsFoundWhereItIs) {
  const Image a = texturedImage(120, 80);
  Image b = a;
  fillBlock(b, 70, 30, 82, 41, 250, 20, 200);  // 12 x 11 magenta block
  Image diff;
  const DiffResult r = compareImages(a, b, DiffOptions{}, &diff);
  EXPECT_EQ(r.differentPixels, 12 * 11);
  EXPECT_EQ(r.changed.x0, 70);
  EXPECT_EQ(r.changed.y0, 30);
  EXPECT_EQ(r.changed.x1, 82);
  EXPECT_EQ(r.changed.y1, 41);
  EXPECT_NEAR(r.diffRatio, 132.0 / (120 * 80), 1e-12);
  EXPECT_LT(r.ssim, 0.999);
  EXPECT_LT(r.ssimMin, 0.5);  // the window over the block is nothing like the reference
  // Red inside the block in the diff image, grey outside.
  const uint8_t* in = diff.at(75, 35);
  EXPECT_GT(in[0], 200);
  EXPECT_LT(in[1], 60);
  const uint8_t* out = diff.at(10, 10);
  EXPECT_EQ(out[0], out[1]);
  // The comparison is symmetric in what it counts.
  const DiffResult back = compareImages(b, a, DiffOptions{});
  EXPECT_EQ(back.differentPixels, r.differentPixels);
}

TEST(CompareImages, ThresholdDecidesWhatCountsAsDifferent) {
  const Image a = texturedImage(64, 64);
  Image b = a;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) b.at(x, y)[2] = uint8_t(b.at(x, y)[2] + 6);  // slight tint everywhere
  DiffOptions loose, strict;
  strict.threshold = 0.005;
  EXPECT_EQ(compareImages(a, b, loose).differentPixels, 0);
  EXPECT_EQ(compareImages(a, b, strict).differentPixels, 64 * 64);
}

TEST(CompareImages, APixelCountsOnlyWhenItExceedsTheThreshold) {
  // Boundary values (the README: a pixel differs when its distance *exceeds* the threshold): at
  // threshold 0 identical images have no different pixel, and a pixel exactly at the threshold is
  // not counted. Counting at >= instead made every pixel of two identical images differ.
  const Image a = texturedImage(32, 32);
  DiffOptions exact;
  exact.threshold = 0.0;
  exact.detectAntialiasing = false;
  EXPECT_EQ(compareImages(a, a, exact).differentPixels, 0);
  Image b = a;
  b.at(5, 7)[0] = uint8_t(b.at(5, 7)[0] + 40);
  DiffOptions at = exact;
  at.threshold = colourDistance(a.at(5, 7), b.at(5, 7));
  EXPECT_EQ(compareImages(a, b, at).differentPixels, 0);
  DiffOptions below = exact;
  below.threshold = at.threshold * 0.999;
  EXPECT_EQ(compareImages(a, b, below).differentPixels, 1);
}

TEST(CompareImages, AntialiasedEdgeIsForgivenButCountsWithoutTolerance) {
  // A black square on white; the new image has a grey column beside its right edge, as an
  // anti-aliased rasteriser would draw a half-covered pixel column.
  Image a(64, 64, 255, 255, 255);
  fillBlock(a, 20, 20, 40, 40, 0, 0, 0);
  Image b = a;
  fillBlock(b, 40, 20, 41, 40, 128, 128, 128);
  const DiffResult tolerant = compareImages(a, b, DiffOptions{});
  EXPECT_EQ(tolerant.differentPixels, 0);
  EXPECT_EQ(tolerant.antialiasedPixels, 20);
  DiffOptions strict;
  strict.detectAntialiasing = false;
  const DiffResult counted = compareImages(a, b, strict);
  EXPECT_EQ(counted.differentPixels, 20);
  EXPECT_EQ(counted.changed.x0, 40);
  EXPECT_EQ(counted.changed.x1, 41);
  // A grey block in the middle of the white area is not an edge: it is never forgiven.
  Image c = a;
  fillBlock(c, 48, 48, 52, 52, 128, 128, 128);
  EXPECT_EQ(compareImages(a, c, DiffOptions{}).differentPixels, 16);
}

TEST(CompareImages, MaskedRegionsAreLeftOut) {
  const Image a = texturedImage(100, 60);
  Image b = a;
  fillBlock(b, 10, 10, 30, 20, 0, 255, 0);  // inside the mask
  fillBlock(b, 60, 40, 64, 44, 0, 255, 0);  // outside it
  DiffOptions opt;
  opt.masks.push_back(PixelRect{5, 5, 40, 25});
  Image diff;
  const DiffResult r = compareImages(a, b, opt, &diff);
  EXPECT_EQ(r.comparedPixels, 100 * 60 - 35 * 20);
  EXPECT_EQ(r.differentPixels, 16);
  EXPECT_EQ(r.changed.x0, 60);
  EXPECT_EQ(r.changed.y0, 40);
  // SSIM ignores every window that touches the mask, so only the small block lowers it.
  DiffOptions both = opt;
  both.masks.push_back(PixelRect{56, 36, 68, 48});
  const DiffResult clean = compareImages(a, b, both);
  EXPECT_EQ(clean.differentPixels, 0);
  EXPECT_NEAR(clean.ssim, 1.0, 1e-12);
  // Masked pixels are tinted blue in the diff image.
  const uint8_t* m = diff.at(20, 15);
  EXPECT_GT(m[2], m[0]);
}

TEST(StructuralSimilarity, FallsWithNoiseAndStaysHighForTinyChanges) {
  const Image a = texturedImage(80, 80);
  Image noisy = a, shifted = a;
  uint32_t s = 12345;
  for (size_t i = 0; i < noisy.rgba.size(); i += 4) {
    s = s * 1664525u + 1013904223u;  // a fixed LCG: the same noise every run
    const int n = int((s >> 24) % 81) - 40;
    for (int k = 0; k < 3; ++k) noisy.rgba[i + k] = uint8_t(std::clamp(int(noisy.rgba[i + k]) + n, 0, 255));
  }
  for (size_t i = 0; i < shifted.rgba.size(); i += 4) shifted.rgba[i] = uint8_t(shifted.rgba[i] + 1);
  double mean = 0, worst = 0;
  structuralSimilarity(a, noisy, {}, 8, mean, worst);
  EXPECT_LT(mean, 0.9);
  EXPECT_LE(worst, mean);
  structuralSimilarity(a, shifted, {}, 8, mean, worst);
  EXPECT_GT(mean, 0.999);
}

}  // namespace
}  // namespace haif
