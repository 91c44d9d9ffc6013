// PNG writing/reading: exact round trip, atomic write, clear errors.
#include <gtest/gtest.h>

#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "render/png_io.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

// Writes rgba (w x h) to path and reads it back into back, checking the size read.
void writeAndReadBack(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba,
                      std::vector<uint8_t>& back) {
  std::string error;
  ASSERT_TRUE(writePng(path, w, h, rgba.data(), &error)) << error;
  int rw = 0, rh = 0;
  ASSERT_TRUE(readPng(path, &rw, &rh, &back, &error)) << error;
  ASSERT_EQ(rw, w);
  ASSERT_EQ(rh, h);
}

TEST(PngIo, RoundTripKeepsEveryPixelAndTopRowFirst) {
  const int w = 37, h = 21;  // odd sizes catch stride mistakes
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &rgba[4 * (static_cast<size_t>(y) * w + x)];
      p[0] = static_cast<uint8_t>(x * 7), p[1] = static_cast<uint8_t>(y * 11), p[2] = static_cast<uint8_t>(x ^ y),
      p[3] = static_cast<uint8_t>(255 - y);
    }
  const std::string path = test::tempDir() + "/roundtrip.png";
  std::vector<uint8_t> back;
  ASSERT_NO_FATAL_FAILURE(writeAndReadBack(path, w, h, rgba, back));
  EXPECT_EQ(back, rgba);
  // Nothing but the final file is left behind.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(test::tempDir()))
    files += e.path().filename().string().rfind("roundtrip.png", 0) == 0;
  EXPECT_EQ(files, 1);
}

// Opaque images take the RGB path (alpha dropped on write); reading must give alpha 255 back and
// every colour byte unchanged, including at a full frame size.
TEST(PngIo, OpaqueFrameRoundTripsExactly) {
  const int w = 1280, h = 720;
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
  uint32_t seed = 12345;
  for (size_t i = 0; i < rgba.size(); ++i) {
    seed = seed * 1664525u + 1013904223u;
    rgba[i] = (i % 4 == 3) ? 255 : static_cast<uint8_t>((i % 7 == 0) ? seed >> 24 : (i / 4) % 251);
  }
  const std::string path = test::tempDir() + "/opaque.png";
  std::vector<uint8_t> back;
  ASSERT_NO_FATAL_FAILURE(writeAndReadBack(path, w, h, rgba, back));
  EXPECT_TRUE(back == rgba);
  // Stored as RGB: well under the 3.7 MB of raw RGBA even with the noise in it.
  EXPECT_LT(std::filesystem::file_size(path), rgba.size() * 3 / 4 + 4096);
}

TEST(PngIo, UnwritableDirectoryFailsWithPathInError) {
  std::vector<uint8_t> rgba(4 * 4 * 4, 128);
  std::string error;
  EXPECT_FALSE(writePng("/nonexistent_dir_haif/x.png", 4, 4, rgba.data(), &error));
  EXPECT_NE(error.find("/nonexistent_dir_haif/x.png"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists("/nonexistent_dir_haif"));
}

TEST(PngIo, ReadingAMissingFileFails) {
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  std::string error;
  EXPECT_FALSE(readPng(test::tempDir() + "/does_not_exist.png", &w, &h, &px, &error));
  EXPECT_NE(error.find("does_not_exist.png"), std::string::npos);
}

// A header may claim up to 1,000,000 x 1,000,000 pixels (libpng's limit): the 4 TB buffer for it was
// allocated before any image data was read, and `haif diff` died of std::bad_alloc.
TEST(PngIo, AHugeClaimedSizeIsRefusedBeforeAnythingIsAllocated) {
  const std::string path = test::tempDir() + "/huge.png";
  std::vector<uint8_t> rgba(4 * 4 * 4, 200);
  std::string error;
  ASSERT_TRUE(writePng(path, 4, 4, rgba.data(), &error)) << error;
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // IHDR's width and height (bytes 16-23) now say 1,000,000 x 1,000,000, with its CRC recomputed.
  const uint8_t big[4] = {0x00, 0x0F, 0x42, 0x40};
  for (int i = 0; i < 4; ++i) bytes[size_t(16 + i)] = char(big[i]), bytes[size_t(20 + i)] = char(big[i]);
  uint32_t crc = uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17));
  for (int i = 0; i < 4; ++i) bytes[size_t(29 + i)] = char((crc >> (24 - 8 * i)) & 0xff);
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  EXPECT_FALSE(decodePng(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "huge.png", &w, &h, &px, &error));
  EXPECT_NE(error.find("huge.png': 1000000x1000000 pixels is larger than 67108864 pixels"), std::string::npos) << error;
  EXPECT_TRUE(px.empty());
  // The same bytes from memory and from the file read alike.
  ASSERT_TRUE(writePng(path, 4, 4, rgba.data(), &error)) << error;
  std::ifstream in(path, std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), {});
  ASSERT_TRUE(decodePng(reinterpret_cast<const uint8_t*>(good.data()), good.size(), "good.png", &w, &h, &px, &error))
      << error;
  EXPECT_EQ(px, rgba);
}

}  // namespace
}  // namespace haif::render
