// haif reel end to end: a small playlist becomes one video with the frame count the timeline
// promises (cross-fades overlap neighbours), title cards are drawn, captions show, and playlist
// mistakes are one line naming the file, the place and the problem, before anything is rendered.
#include "haif_process.h"
#include "render/png_io.h"
#include "video_probe.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

const char* kScene = R"({"name": "reel_stack", "camera": {"eye": [9, 6, 9], "target": [0, 2.5, 0]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 4}]})";

class ReelCommand : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    std::ofstream(dir_ / "stack.json") << kScene;
  }

  std::string playlist(const std::string& text) {
    const fs::path p = dir_ / "reel.json";
    std::ofstream(p) << text;
    return p.string();
  }
};

// 10 fps, 0.2 s fades = 2 frames, capped at half of either neighbour:
// title 3 frames, scene 4 frames, card 2 frames, compare 4 frames -> fades 1, 1, 1 -> 13 - 3 = 10 frames.
const char* kPlaylist = R"({
  "width": 256, "height": 200, "fps": 10, "crossfade_s": 0.2, "title_card_s": 0.2,
  "items": [
    {"type": "title", "text": "Reel test", "subtitle": "a subtitle", "seconds": 0.3},
    {"type": "scene", "scene": "stack.json", "solver": "fixed:10", "seconds": 0.4, "caption": "a caption"},
    {"type": "compare", "scene": "stack.json", "left": "fixed:10", "right": "model:2", "seconds": 0.4,
     "title": "Compared", "view": "island"}
  ]})";

TEST_F(ReelCommand, PlaylistBecomesOneVideoWithTheTimelinesFrameCount) {
  if (!test::haveProgram("ffmpeg") || !test::haveProgram("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  const std::string list = playlist(kPlaylist);
  const auto check = runHaif("reel '" + list + "' --check", dir_);
  ASSERT_EQ(check.exitCode, 0) << check.err;
  EXPECT_NE(check.out.find("10 frames"), std::string::npos) << check.out;

  const fs::path video = dir_ / "reel.mp4";
  const auto r = runHaif("reel '" + list + "' --threads 1 --out '" + video.string() + "'", dir_);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const test::VideoInfo v = test::probeVideo(video);
  ASSERT_TRUE(v.ok);
  EXPECT_EQ(v.frames, 10);
  EXPECT_EQ(v.width, 256);
  EXPECT_EQ(v.height, 200);
  EXPECT_TRUE(v.indexFirst);

  // Frame 0 is the title card: dark all over, with light title text in the middle rows only.
  const fs::path still = dir_ / "first.png";
  const std::string cmd = "ffmpeg -loglevel error -y -i '" + video.string() + "' -frames:v 1 '" + still.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
  std::string error;
  ASSERT_TRUE(render::readPng(still.string(), &w, &h, &rgba, &error)) << error;
  int bright = 0, brightOutsideMiddle = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = &rgba[4 * (size_t(y) * size_t(w) + size_t(x))];
      if (p[0] + p[1] + p[2] > 500) {
        ++bright;
        if (y < h / 4 || y > 3 * h / 4) ++brightOutsideMiddle;
      }
    }
  EXPECT_GT(bright, 30) << "the title text";
  EXPECT_EQ(brightOutsideMiddle, 0);
  EXPECT_LT(rgba[0] + rgba[1] + rgba[2], 120) << "dark background";
}

TEST_F(ReelCommand, ShippedReelPlaylistChecksOut) {
  const auto r = runHaif(std::string("reel '") + HAIF_SOURCE_DIR + "/scenes/reel.json' --check", dir_);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("compare"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("island"), std::string::npos) << r.out;
}

TEST_F(ReelCommand, PlaylistMistakesAreOneLineWithFileAndPlace) {
  struct Case {
    const char* items;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases = {
      {R"([{"type": "scene", "scene": "missing.json"}])", {"reel.json:1:", "items[0].scene", "missing.json"}},
      {R"([{"type": "movie", "scene": "stack.json"}])", {"items[0].type", "title, scene or compare", "movie"}},
      {R"([{"type": "scene", "scene": "stack.json", "seconds": -1}])", {"items[0].seconds", "-1"}},
      {R"([{"type": "scene", "scene": "stack.json", "captoin": "x"}])", {"captoin", "caption"}},
      {R"([{"type": "compare", "scene": "stack.json", "left": "fixed:10", "right": "bullet:ten"}])",
       {"items[0].right", "bullet needs an iteration count"}},
      {R"([{"type": "scene", "scene": "stack.json", "solver": "fixed:0"}])", {"items[0].solver", "fixed:0"}},
      {R"([])", {"items", "empty"}},
      {R"([{"type": "title"}])", {"items[0]", "text"}},
  };
  for (const Case& c : cases) {
    const std::string list = playlist(std::string("{\"items\": ") + c.items + "}");
    const auto r = runHaif("reel '" + list + "' --out '" + (dir_ / "x.mp4").string() + "'", dir_);
    EXPECT_EQ(r.exitCode, 1) << c.items << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& n : c.needles)
      EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in " << r.err;
  }
  const auto syntax = runHaif("reel '" + playlist("{\"items\": [}") + "'", dir_);
  EXPECT_EQ(syntax.exitCode, 1);
  EXPECT_NE(syntax.err.find("reel.json:1:12: syntax error"), std::string::npos) << syntax.err;
  EXPECT_EQ(runHaif("reel '" + (dir_ / "none.json").string() + "'", dir_).exitCode, 1);
  EXPECT_EQ(runHaif("reel", dir_).exitCode, 2);
  EXPECT_FALSE(fs::exists(dir_ / "x.mp4"));
}

}  // namespace
}  // namespace haif
