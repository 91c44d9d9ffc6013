// Cross-fades between clips: held-back tails blend linearly into the next clip's first frames,
// the output is shorter by the overlap, and without fades every frame passes through unchanged.
#include "tools/crossfade_writer.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

// Remembers the first byte of every frame it is given.
class CaptureSink : public FrameSink {
 public:
  bool write(const uint8_t* rgba, std::string&) override {
    firstBytes.push_back(rgba[0]);
    return true;
  }
  bool finish(std::string&) override { return true; }
  std::string where() const override { return "memory"; }
  std::vector<int> firstBytes;
};

void writeClip(CrossfadeWriter& w, int fadeIn, int holdOut, std::initializer_list<uint8_t> values) {
  std::string error;
  ASSERT_TRUE(w.beginClip(fadeIn, holdOut, error)) << error;
  for (uint8_t v : values) {
    std::vector<uint8_t> frame(4 * 3 * 2, v);
    ASSERT_TRUE(w.write(frame.data(), error)) << error;
  }
}

TEST(CrossfadeWriter, TailBlendsIntoTheNextClip) {
  CaptureSink sink;
  CrossfadeWriter w(sink, 3, 2);
  writeClip(w, 0, 2, {10, 20, 30, 0, 0});
  writeClip(w, 2, 0, {90, 180, 200, 200, 200});
  std::string error;
  ASSERT_TRUE(w.finish(error)) << error;
  // 0 -> 90 at 1/3 and 0 -> 180 at 2/3; 10 frames in, 8 out.
  EXPECT_EQ(sink.firstBytes, (std::vector<int>{10, 20, 30, 30, 120, 200, 200, 200}));
  EXPECT_EQ(w.framesOut(), 8);
}

TEST(CrossfadeWriter, HardCutsPassFramesThrough) {
  CaptureSink sink;
  CrossfadeWriter w(sink, 3, 2);
  writeClip(w, 0, 0, {1, 2, 3});
  writeClip(w, 0, 0, {4, 5});
  std::string error;
  ASSERT_TRUE(w.finish(error)) << error;
  EXPECT_EQ(sink.firstBytes, (std::vector<int>{1, 2, 3, 4, 5}));
}

TEST(CrossfadeWriter, HeldFramesOfTheLastClipAreFlushed) {
  CaptureSink sink;
  CrossfadeWriter w(sink, 3, 2);
  writeClip(w, 0, 3, {7, 8, 9, 10});
  EXPECT_EQ(sink.firstBytes, (std::vector<int>{7}));  // three held back for a fade that never comes
  std::string error;
  ASSERT_TRUE(w.finish(error)) << error;
  EXPECT_EQ(sink.firstBytes, (std::vector<int>{7, 8, 9, 10}));
}

}  // namespace
}  // namespace haif
