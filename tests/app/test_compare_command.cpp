// haif compare end to end: the video's frame count and size (ffprobe), each side's label colour where
// the layout puts it, the PNG fallback without ffmpeg (whose frames diff clean across two runs), and
// clear errors for bad specs, Bullet in a build without it, and missing options.
#include "haif_process.h"
#include "render/png_io.h"
#include "video_probe.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

const char* kScene = R"({"name": "compare_stack", "camera": {"eye": [9, 6, 9], "target": [0, 2.5, 0]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 6}]})";

class CompareCommand : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    scene_ = (dir_ / "scene.json").string();
    std::ofstream(scene_) << kScene;
  }

  test::ProcessResult compare(const std::string& args, const std::string& env = "") {
    return runHaif("compare '" + scene_ + "' " + args, dir_, env);
  }
  void expectOneLineError(const test::ProcessResult& r, std::initializer_list<std::string> needles) {
    EXPECT_NE(r.exitCode, 0);
    EXPECT_LT(r.exitCode, 128) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in " << r.err;
  }

  std::string scene_;
};

TEST_F(CompareCommand, VideoHasEveryFrameAtTheRequestedSizeWithBothSidesLabelled) {
  if (!test::haveProgram("ffmpeg") || !test::haveProgram("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  const fs::path video = dir_ / "out" / "cmp.mp4";
  const auto r = compare("--left fixed:10 --right fixed:2 --frames 12 --width 320 --height 240 --threads 1 --out '" +
                         video.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("fixed:10"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fixed:2"), std::string::npos) << r.out;
  const test::VideoInfo v = test::probeVideo(video);
  ASSERT_TRUE(v.ok);
  EXPECT_EQ(v.frames, 12);
  EXPECT_EQ(v.width, 320);
  EXPECT_EQ(v.height, 240);
  EXPECT_EQ(v.codec, "h264");
  EXPECT_EQ(v.pixelFormat, "yuv420p");
  EXPECT_TRUE(v.indexFirst);

  // The last frame: the label bar under each side's name carries that side's colour (left blue,
  // right orange), and the two halves are split by a dark divider at the centre.
  const fs::path still = dir_ / "last.png";
  const std::string cmd =
      "ffmpeg -loglevel error -y -sseof -0.1 -i '" + video.string() + "' -frames:v 1 '" + still.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
  std::string error;
  ASSERT_TRUE(render::readPng(still.string(), &w, &h, &rgba, &error)) << error;
  ASSERT_EQ(w, 320);
  auto px = [&](int x, int y) { return &rgba[4 * (size_t(y) * size_t(w) + size_t(x))]; };
  // At 240 px high the label band is 18 px with a 2 px colour bar at its bottom.
  const uint8_t* leftBar = px(80, 16);
  const uint8_t* rightBar = px(240, 16);
  EXPECT_GT(leftBar[2], leftBar[0] + 60) << "left bar should be blue";
  EXPECT_GT(rightBar[0], rightBar[2] + 60) << "right bar should be orange";
  const uint8_t* divider = px(160, 100);
  EXPECT_LT(int(divider[0]) + divider[1] + divider[2], 200) << "dark divider between the sides";
}

TEST_F(CompareCommand, WithoutFfmpegPngFramesAndMasksAreWrittenAndDiffClean) {
  const fs::path a = dir_ / "a" / "cmp.mp4", b = dir_ / "b" / "cmp.mp4";
  const std::string common = "--left fixed:8 --right model:2 --frames 4 --width 256 --height 200 --threads 1 --out ";
  const auto ra = compare(common + "'" + a.string() + "'", "PATH=/nonexistent ");
  ASSERT_EQ(ra.exitCode, 0) << ra.err;
  EXPECT_NE(ra.err.find("ffmpeg not found"), std::string::npos) << ra.err;
  EXPECT_NE(ra.err.find("cmp_frames"), std::string::npos) << ra.err;
  EXPECT_FALSE(fs::exists(a));
  const fs::path frames = dir_ / "a" / "cmp_frames";
  for (const char* f : {"frame_00000.png", "frame_00003.png", "masks.json"}) EXPECT_TRUE(fs::exists(frames / f)) << f;
  EXPECT_FALSE(fs::exists(frames / "frame_00004.png"));
  const auto masks = nlohmann::json::parse(test::readWholeFile(frames / "masks.json"));
  ASSERT_EQ(masks["regions"].size(), 3u);  // two overlays and the chart strip
  EXPECT_EQ(masks["regions"][2]["name"], "chart strip");
  EXPECT_EQ(masks["regions"][2]["y1"], 200);
  EXPECT_GE(masks["regions"][1]["x0"].get<int>(), 128);  // the right side's overlay is in the right half

  // Fixed and model modes are deterministic: a second comparison matches the first outside the masks.
  ASSERT_EQ(compare(common + "'" + b.string() + "'", "PATH=/nonexistent ").exitCode, 0);
  const auto d = runHaif("diff '" + frames.string() + "' '" + (dir_ / "b" / "cmp_frames").string() + "' --out '" +
                             (dir_ / "d").string() + "'",
                         dir_);
  EXPECT_EQ(d.exitCode, 0) << d.out << d.err;
}

TEST_F(CompareCommand, BadSpecsAndMissingOptionsAreClearErrors) {
  const std::string out = " --frames 2 --width 256 --height 200 --out '" + (dir_ / "x.mp4").string() + "'";
#ifndef HAIF_HAVE_BULLET
  expectOneLineError(compare("--left fixed:10 --right bullet:10" + out), {"bullet:10", "not built with Bullet"});
#endif
  expectOneLineError(compare("--left fixed:10 --right bullet:abc" + out), {"bullet needs an iteration count"});
  expectOneLineError(compare("--left fixed:x --right fixed:2" + out), {"left side", "fixed:x", "fixed:10"});
  expectOneLineError(compare("--left turbo:3 --right fixed:2" + out), {"unknown mode 'turbo'", "bullet"});
  expectOneLineError(compare("--left fixed:10" + out), {"--left and --right are required"});
  expectOneLineError(compare("--left fixed:10 --right fixed:2 --out x.avi"), {"--out", ".mp4"});
  expectOneLineError(
      runHaif("compare '" + (dir_ / "nope.json").string() + "' --left fixed:1 --right fixed:2" + out, dir_),
      {"nope.json"});
  EXPECT_FALSE(fs::exists(dir_ / "x.mp4"));
}

#ifdef HAIF_HAVE_BULLET
// With the Bullet adapter built, bullet:N is a side like any other.
TEST_F(CompareCommand, BulletSideRuns) {
  const fs::path video = dir_ / "vs_bullet.mp4";
  const auto r = compare("--left fixed:10 --right bullet:10 --frames 3 --width 256 --height 200 --out '" +
                         video.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(video) || fs::exists(dir_ / "vs_bullet_frames")) << r.err;
}
#endif

}  // namespace
}  // namespace haif
