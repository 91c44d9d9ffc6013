// PNG writing/reading: exact round trip, atomic write, clear errors.
#include <gtest/gtest.h>

#include <filesystem>

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

}  // namespace
}  // namespace haif::render
