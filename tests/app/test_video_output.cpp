// Videos from `haif run --video`: streamed through ffmpeg (checked with ffprobe), PNG frames kept,
// a clear note without ffmpeg, and a clean failure when ffmpeg dies.
#include "haif_process.h"
#include "tools/video.h"
#include "video_probe.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

const char* kSmallScene = R"({"name": "video_stack", "camera": {"eye": [9, 6, 9], "target": [0, 2, 0]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 5}]})";

class VideoOutput : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    scene_ = (dir_ / "scene.json").string();
    std::ofstream(scene_) << kSmallScene;
  }

  int countFiles(const fs::path& d, const std::string& ext) {
    if (!fs::exists(d)) return 0;
    return int(std::count_if(fs::directory_iterator(d), fs::directory_iterator{},
                             [&](const fs::directory_entry& e) { return e.path().extension() == ext; }));
  }

  std::string scene_;
};

TEST_F(VideoOutput, RunVideoHasEveryFrameAtEvenSizeWithTheIndexFirst) {
  if (!test::haveProgram("ffmpeg") || !test::haveProgram("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  const fs::path out = dir_ / "run", video = dir_ / "clips" / "run.mp4";
  // Odd width and height: the encoder pads to even dimensions for yuv420p.
  const auto r = runHaif("run '" + scene_ + "' --frames 24 --frame-every 2 --width 161 --height 91 --error-every 0 " +
                             "--out '" + out.string() + "' --video '" + video.string() + "'",
                         dir_);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const test::VideoInfo v = test::probeVideo(video);
  ASSERT_TRUE(v.ok) << "ffprobe could not read " << video;
  EXPECT_EQ(v.frames, 12);
  EXPECT_EQ(v.width, 162);
  EXPECT_EQ(v.height, 92);
  EXPECT_EQ(v.codec, "h264");
  EXPECT_EQ(v.pixelFormat, "yuv420p");
  EXPECT_TRUE(v.indexFirst) << "moov should precede mdat (+faststart)";
  // The PNG frames are still written, and no temporary video is left beside the video.
  EXPECT_EQ(countFiles(out / "frames", ".png"), 12);
  EXPECT_EQ(countFiles(dir_ / "clips", ".mp4"), 1);
  for (const auto& e : fs::directory_iterator(dir_ / "clips")) EXPECT_NE(e.path().filename().string()[0], '.');
}

// The scheduler state ('R', 'S', 'T' for stopped, ...) of this process's one child (the encoder, by
// then perhaps not yet `ffmpeg`: a child stopped before its exec is held all the same); 0: none.
char childState() {
  for (const auto& e : fs::directory_iterator("/proc")) {
    std::ifstream in(e.path() / "stat");
    std::string text;
    if (!in || !std::getline(in, text)) continue;
    const size_t close = text.rfind(')');  // the name may hold spaces and brackets
    if (close == std::string::npos) continue;
    std::istringstream rest(text.substr(close + 1));
    char state = 0;
    long parent = 0;
    rest >> state >> parent;
    if (parent == long(::getpid())) return state;
  }
  return 0;
}

// Waits up to two seconds for the child's state to become (or stop being) `state`: signals land
// asynchronously.
bool childReaches(char state, bool want) {
  for (int i = 0; i < 200; ++i) {
    if ((childState() == state) == want) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// `haif run --video` holds the encoder while each budgeted step runs (EncodingHold): held, ffmpeg is
// stopped; let go, it goes on; and a video finished while held is still complete.
TEST_F(VideoOutput, AHeldEncoderIsStoppedAndAVideoFinishedWhileHeldIsComplete) {
  if (!test::haveProgram("ffmpeg") || !test::haveProgram("ffprobe")) GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  const fs::path video = dir_ / "held.mp4";
  const int w = 64, h = 48, frames = 8;
  VideoEncoder encoder;
  std::string error;
  ASSERT_TRUE(encoder.open(video.string(), w, h, 30.0, error)) << error;
  std::vector<uint8_t> rgba(size_t(w) * h * 4, 255);
  for (int f = 0; f < frames; ++f) {
    rgba[size_t(f) * 4] = uint8_t(f * 30);
    if (f == frames / 2) {
      encoder.hold(true);
      EXPECT_TRUE(childReaches('T', true)) << "held, ffmpeg should be stopped";
      encoder.hold(false);
      EXPECT_TRUE(childReaches('T', false)) << "let go, ffmpeg should run again";
    }
    ASSERT_TRUE(encoder.write(rgba.data(), error)) << error;
  }
  encoder.hold(true);
  ASSERT_TRUE(childReaches('T', true));
  ASSERT_TRUE(encoder.finish(error)) << error;  // a stopped ffmpeg would never exit
  const test::VideoInfo v = test::probeVideo(video);
  ASSERT_TRUE(v.ok) << "ffprobe could not read " << video;
  EXPECT_EQ(v.frames, frames);
}

TEST_F(VideoOutput, WithoutFfmpegTheFramesAreKeptAndTheMessageSaysSo) {
  const fs::path out = dir_ / "run", video = dir_ / "run.mp4";
  // /bin is enough for the shell; ffmpeg lives in /usr/bin.
  const auto r = runHaif("run '" + scene_ + "' --frames 6 --width 64 --height 48 --error-every 0 --out '" +
                             out.string() + "' --video '" + video.string() + "'",
                         dir_, "PATH=/nonexistent ");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("ffmpeg not found"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((out / "frames").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(video));
  EXPECT_EQ(countFiles(out / "frames", ".png"), 6);
}

TEST_F(VideoOutput, AnFfmpegThatFailsGivesOneErrorAndNoVideo) {
  // A stand-in ffmpeg that reads nothing and fails: haif must not die of SIGPIPE or leave files.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\nexit 3\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const fs::path out = dir_ / "run", video = dir_ / "clips" / "run.mp4";
  const auto r = runHaif("run '" + scene_ + "' --frames 6 --width 256 --height 256 --error-every 0 --out '" +
                             out.string() + "' --video '" + video.string() + "'",
                         dir_, "PATH='" + bin.string() + ":/usr/bin:/bin' ");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
  EXPECT_NE(r.err.find("ffmpeg failed (exit status 3)"), std::string::npos) << r.err;
  // One error line. Progress lines ("run: step 2/6 ...") appear too when a loaded machine takes
  // more than a couple of seconds (shader compilation included), and are not errors.
  std::istringstream lines(r.err);
  int errorLines = 0;
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line.rfind("run: ", 0) != 0) ++errorLines;
  EXPECT_EQ(errorLines, 1) << r.err;
  EXPECT_EQ(countFiles(dir_ / "clips", ".mp4"), 0);
}

}  // namespace
}  // namespace haif
