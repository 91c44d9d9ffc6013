// AsyncPngWriter: every frame written exactly and in order, bounded queue, recycled buffers,
// atomic files, and errors reported.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "render/async_png_writer.h"
#include "render/png_io.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

constexpr int kW = 64, kH = 40;

std::vector<uint8_t> frameFor(int index) {
  std::vector<uint8_t> rgba(static_cast<size_t>(kW) * kH * 4);
  for (size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = (i % 4 == 3) ? 255 : static_cast<uint8_t>(index * 37 + i * 11 + (i / (4 * kW)) * 5);
  return rgba;
}

std::string framePath(const std::string& dir, int index) { return dir + "/frame_" + std::to_string(index) + ".png"; }

TEST(AsyncPngWriter, WritesEveryFrameExactlyInOrderWithABoundedQueue) {
  const std::string dir = test::tempDir() + "/async_frames";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const int maxPending = 2, frames = 12;
  AsyncPngWriter writer(maxPending);
  std::string error;
  std::vector<uint8_t> buffer;
  size_t recycled = 0;
  for (int i = 0; i < frames; ++i) {
    buffer = frameFor(i);
    ASSERT_TRUE(writer.submit(framePath(dir, i), kW, kH, buffer, &error)) << error;
    recycled += buffer.capacity() >= static_cast<size_t>(kW) * kH * 4;
    // submit() returns only with at most maxPending frames queued (the one being written
    // included), so everything older is already complete on disk: the queue is bounded and FIFO.
    if (i >= maxPending) {
      int w = 0, h = 0;
      EXPECT_TRUE(readPngSize(framePath(dir, i - maxPending), &w, &h, &error)) << "frame " << i - maxPending;
    }
  }
  ASSERT_TRUE(writer.finish(&error)) << error;
  EXPECT_GT(recycled, 0u) << "pixel buffers should come back for reuse";
  for (int i = 0; i < frames; ++i) {
    int w = 0, h = 0;
    std::vector<uint8_t> back;
    ASSERT_TRUE(readPng(framePath(dir, i), &w, &h, &back, &error)) << error;
    EXPECT_EQ(w, kW);
    EXPECT_EQ(h, kH);
    EXPECT_TRUE(back == frameFor(i)) << "frame " << i << " differs";
  }
  // Atomic writes: only the final names are left, no temporary files.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().extension(), ".png") << e.path();
  }
  EXPECT_EQ(files, frames);
  EXPECT_GT(writer.medianWriteMs(), 0.0);
}

TEST(AsyncPngWriter, AFailedWriteIsReportedAndStopsFurtherFrames) {
  AsyncPngWriter writer(2);
  std::string error;
  std::vector<uint8_t> buffer = frameFor(0);
  ASSERT_TRUE(writer.submit("/nonexistent_dir_haif/frame_0.png", kW, kH, buffer, &error)) << error;
  EXPECT_FALSE(writer.finish(&error));
  EXPECT_NE(error.find("/nonexistent_dir_haif/frame_0.png"), std::string::npos) << error;
  // Later frames are refused with the same error instead of being written out of sequence.
  const std::string dir = test::tempDir();
  buffer = frameFor(1);
  std::string again;
  EXPECT_FALSE(writer.submit(dir + "/after_error.png", kW, kH, buffer, &again));
  EXPECT_EQ(again, error);
  EXPECT_FALSE(std::filesystem::exists(dir + "/after_error.png"));
}

// A filmed run holds the writer while each budgeted step runs: it starts no frame then, and the
// hold never blocks the run (a full queue and finish() lift it).
TEST(AsyncPngWriter, AHeldWriterStartsNoFrameAndAFullQueueOrFinishLiftsTheHold) {
  const std::string dir = test::tempDir() + "/async_held";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const int maxPending = 2;
  AsyncPngWriter writer(maxPending);
  std::string error;
  writer.hold(true);
  std::vector<uint8_t> buffer = frameFor(0);
  ASSERT_TRUE(writer.submit(framePath(dir, 0), kW, kH, buffer, &error)) << error;
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // a 64x40 frame takes well under 1 ms
  EXPECT_FALSE(std::filesystem::exists(framePath(dir, 0))) << "held, the writer should not start a frame";
  writer.hold(false);
  ASSERT_TRUE(writer.finish(&error)) << error;
  EXPECT_TRUE(std::filesystem::exists(framePath(dir, 0)));
  // Held with more frames than the queue holds: submit() must not wait for a thread that waits for it.
  writer.hold(true);
  for (int i = 1; i <= maxPending + 2; ++i) {
    buffer = frameFor(i);
    ASSERT_TRUE(writer.submit(framePath(dir, i), kW, kH, buffer, &error)) << error;
  }
  writer.hold(true);
  ASSERT_TRUE(writer.finish(&error)) << error;  // finish() while held
  for (int i = 0; i <= maxPending + 2; ++i) {
    int w = 0, h = 0;
    std::vector<uint8_t> back;
    ASSERT_TRUE(readPng(framePath(dir, i), &w, &h, &back, &error)) << error;
    EXPECT_TRUE(back == frameFor(i)) << "frame " << i << " differs";
  }
}

TEST(AsyncPngWriter, DestructorFlushesQueuedFrames) {
  const std::string dir = test::tempDir() + "/async_flush";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    AsyncPngWriter writer(3);
    std::string error;
    for (int i = 0; i < 3; ++i) {
      std::vector<uint8_t> buffer = frameFor(i);
      ASSERT_TRUE(writer.submit(framePath(dir, i), kW, kH, buffer, &error)) << error;
    }
  }
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::filesystem::exists(framePath(dir, i))) << i;
}

}  // namespace
}  // namespace haif::render
