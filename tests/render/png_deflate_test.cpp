// PngDeflater: every stream inflates (with zlib's own decoder) to exactly the image's "sub"-filtered
// scanlines, for images that take each of its paths: all literals, long runs, rows repeating the row
// above, rows too wide for a match one row back, several blocks, alpha, and a skewed histogram
// whose plain Huffman code would be deeper than deflate's 15 bits.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "render/png_deflate.h"

namespace haif::render {
namespace {

struct Image {
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;  // 4 bytes a pixel, top row first
  uint8_t* at(int x, int y) { return &rgba[4 * (size_t(y) * size_t(w) + size_t(x))]; }
};

Image makeImage(int w, int h) {
  Image im;
  im.w = w;
  im.h = h;
  im.rgba.assign(size_t(w) * size_t(h) * 4, 255);
  return im;
}

// Compresses im, inflates the stream with zlib and undoes the filter; the pixels must come back
// exactly. Returns the compressed size.
size_t roundTrip(const Image& im, int channels) {
  PngDeflater deflater;
  std::vector<uint8_t> stream{0xAB};  // compress appends: what was there stays
  deflater.compress(im.rgba.data(), im.w, im.h, channels, 4, stream);
  EXPECT_EQ(stream[0], 0xAB);
  const size_t rowBytes = 1 + size_t(im.w) * size_t(channels);
  std::vector<uint8_t> raw(rowBytes * size_t(im.h) + 1);
  uLongf size = raw.size();
  const int rc = uncompress(raw.data(), &size, stream.data() + 1, uLong(stream.size() - 1));
  EXPECT_EQ(rc, Z_OK);  // a bad code, distance or checksum fails here
  EXPECT_EQ(size, rowBytes * size_t(im.h));
  if (rc != Z_OK) return 0;
  size_t wrong = 0;
  for (int y = 0; y < im.h; ++y) {
    const uint8_t* row = raw.data() + size_t(y) * rowBytes;
    EXPECT_EQ(row[0], 1) << "row " << y << " filter type";
    for (int x = 0; x < im.w; ++x)
      for (int c = 0; c < channels; ++c) {
        const uint8_t left = x > 0 ? im.rgba[4 * (size_t(y) * size_t(im.w) + size_t(x - 1)) + size_t(c)] : 0;
        wrong += uint8_t(row[1 + size_t(x) * size_t(channels) + size_t(c)] + left) !=
                 im.rgba[4 * (size_t(y) * size_t(im.w) + size_t(x)) + size_t(c)];
      }
  }
  EXPECT_EQ(wrong, 0u);
  return stream.size() - 1;
}

TEST(PngDeflate, NoiseIsAllLiteralsAndRoundTrips) {
  Image im = makeImage(97, 53);
  std::mt19937 rng(7);
  for (auto& b : im.rgba) b = uint8_t(rng());
  const size_t size = roundTrip(im, 4);
  // Noise does not compress, but the literal codes keep it near its raw size.
  EXPECT_LT(size, size_t(im.w * im.h * 4) * 105 / 100);
}

TEST(PngDeflate, FlatAndRepeatingRowsCompressToAlmostNothing) {
  Image flat = makeImage(640, 360);
  for (int y = 0; y < flat.h; ++y)
    for (int x = 0; x < flat.w; ++x) {
      uint8_t* p = flat.at(x, y);
      p[0] = 90, p[1] = 140, p[2] = 200;
    }
  const size_t raw = size_t(flat.w * flat.h * 3);
  EXPECT_LT(roundTrip(flat, 3), raw / 100);

  // A texture that changes every pixel but repeats every row: only the match one row back finds it.
  Image stripes = makeImage(300, 200);
  std::mt19937 rng(3);
  std::vector<uint8_t> row(size_t(stripes.w) * 3);
  for (auto& b : row) b = uint8_t(rng());
  for (int y = 0; y < stripes.h; ++y)
    for (int x = 0; x < stripes.w; ++x)
      for (int c = 0; c < 3; ++c) stripes.at(x, y)[c] = row[size_t(x) * 3 + size_t(c)];
  // The first row is noise (~900 bytes); the other 199 are matches of up to 258 bytes, ~3 bytes
  // each. Without that match they would cost as much as the first: ~180 KB.
  EXPECT_LT(roundTrip(stripes, 3), size_t(stripes.w * 3 * stripes.h) / 50);
}

TEST(PngDeflate, GradientsAndEdgesAcrossManyBlocks) {
  // 1280x720 RGB is 2.7 MB of scanlines: about 21 blocks, matches reaching into the block before.
  Image im = makeImage(1280, 720);
  for (int y = 0; y < im.h; ++y)
    for (int x = 0; x < im.w; ++x) {
      uint8_t* p = im.at(x, y);
      const bool box = (x / 40 + y / 30) % 3 == 0;
      p[0] = uint8_t(box ? 200 : x / 5);
      p[1] = uint8_t(box ? 60 : y / 3);
      p[2] = uint8_t((x * y) >> 9);
    }
  const size_t size = roundTrip(im, 3);
  EXPECT_LT(size, size_t(im.w * im.h * 3) / 4);
}

TEST(PngDeflate, AlphaChannelKeptWithFourChannels) {
  Image im = makeImage(33, 17);
  for (int y = 0; y < im.h; ++y)
    for (int x = 0; x < im.w; ++x) {
      uint8_t* p = im.at(x, y);
      p[0] = uint8_t(x * 9), p[1] = uint8_t(y * 13), p[2] = 7, p[3] = uint8_t(x * y);
    }
  roundTrip(im, 4);
}

TEST(PngDeflate, TinyAndWideImages) {
  roundTrip(makeImage(1, 1), 3);
  roundTrip(makeImage(1, 40), 3);
  roundTrip(makeImage(2, 2), 4);
  // A row of 12000 RGB pixels is 36001 bytes, beyond deflate's 32 KiB window: no match one row back.
  Image wide = makeImage(12000, 3);
  for (int y = 0; y < wide.h; ++y)
    for (int x = 0; x < wide.w; ++x) wide.at(x, y)[0] = uint8_t((x * 31) ^ (x >> 3));
  roundTrip(wide, 3);
}

TEST(PngDeflate, SkewedHistogramStaysWithinFifteenBitCodes) {
  // Filtered bytes with Fibonacci-like counts over 26 values: a plain Huffman code for them is 25
  // bits deep, so the code must be limited to 15 bits and stay complete for zlib to decode it.
  std::vector<uint8_t> filtered;
  uint32_t a = 1, b = 1;
  for (int s = 0; s < 26; ++s) {
    filtered.insert(filtered.end(), a, uint8_t(s * 7 + 1));
    const uint32_t next = a + b;
    a = b;
    b = next;
  }
  std::mt19937 rng(11);
  std::shuffle(filtered.begin(), filtered.end(), rng);
  const int w = 1000, h = int(filtered.size() / 3 / w);
  Image im = makeImage(w, h);
  size_t k = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c, ++k)  // undo the filter, so the deflater sees these bytes
        im.at(x, y)[c] = uint8_t(filtered[k] + (x > 0 ? im.at(x - 1, y)[c] : 0));
  roundTrip(im, 3);
}

}  // namespace
}  // namespace haif::render
