// Every command that writes builds its output beside the target and moves it into place when it is
// complete (tools/staged_output.h), so (issue 26): a rerun into an existing folder keeps no stale
// frames; bad options create nothing; a run that fails late, or a diff that meets a corrupt PNG,
// leaves no partial output and the earlier output untouched; SIGINT and SIGTERM remove what was
// begun and say so in one line.
#include "haif_process.h"
#include "video_probe.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

const char* kStack = R"({"name": "staging_stack", "camera": {"eye": [9, 6, 9], "target": [0, 2, 0]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 4}]})";

class OutputStaging : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    scene_ = (dir_ / "stack.json").string();
    std::ofstream(scene_) << kStack;
  }

  test::ProcessResult run(const std::string& out, const std::string& options, const std::string& env = "") {
    return runHaif("run '" + scene_ + "' --width 64 --height 48 --error-every 0 --out '" + (dir_ / out).string() + "' " +
                       options,
                   dir_ / "log", env);
  }

  static std::vector<std::string> names(const fs::path& folder) {
    std::vector<std::string> out;
    if (!fs::exists(folder)) return out;
    for (const auto& e : fs::directory_iterator(folder)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  static int pngCount(const fs::path& folder) {
    const auto n = names(folder);
    return int(std::count_if(n.begin(), n.end(), [](const std::string& s) { return s.size() > 4 && s.substr(s.size() - 4) == ".png"; }));
  }
  // Hidden names (temporaries) in the scratch folder.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> out;
    for (const std::string& n : names(dir_))
      if (n[0] == '.') out.push_back(n);
    return out;
  }
  static int summarySteps(const fs::path& run) {
    return nlohmann::json::parse(test::readWholeFile(run / "summary.json"))["steps"].get<int>();
  }

  std::string scene_;
};

TEST_F(OutputStaging, ARerunReplacesTheFolderAndKeepsNoStaleFrames) {
  ASSERT_EQ(run("out", "--frames 8").exitCode, 0);
  ASSERT_EQ(pngCount(dir_ / "out" / "frames"), 8);
  const auto r = run("out", "--frames 3");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(pngCount(dir_ / "out" / "frames"), 3) << "frames 3-7 of the earlier run must be gone";
  EXPECT_EQ(summarySteps(dir_ / "out"), 3);
  EXPECT_TRUE(leftovers().empty());
  // And a diff of it against a fresh 3-frame run finds the same frame lists.
  ASSERT_EQ(run("fresh", "--frames 3").exitCode, 0);
  const auto d = runHaif("diff '" + (dir_ / "out").string() + "' '" + (dir_ / "fresh").string() + "' --out '" +
                             (dir_ / "diff").string() + "'",
                         dir_ / "log");
  EXPECT_EQ(d.exitCode, 0) << d.err;
}

TEST_F(OutputStaging, BadOptionsAreRefusedBeforeAnythingIsCreated) {
  for (const std::string& bad : {std::string("--view nope"), std::string("--overlay-corner middle"),
                                 "--video '" + (dir_ / "clip.avi").string() + "'",
                                 "--video '" + dir_.string() + "'"}) {
    const auto r = run("out", "--frames 3 " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << bad << " created the output folder";
    EXPECT_TRUE(leftovers().empty()) << bad;
  }
}

TEST_F(OutputStaging, AFolderTheCommandDidNotWriteIsRefusedAndKept) {
  fs::create_directories(dir_ / "notes");
  std::ofstream(dir_ / "notes" / "todo.txt") << "keep me";
  const auto r = run("notes", "--frames 3");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("is not an output folder of this command"), std::string::npos) << r.err;
  EXPECT_EQ(names(dir_ / "notes"), std::vector<std::string>{"todo.txt"});
}

// ffmpeg that reads every frame and then fails: the run fails after everything else was written.
TEST_F(OutputStaging, ARunThatFailsAtTheEndLeavesTheEarlierOutputAsItWas) {
  ASSERT_EQ(run("out", "--frames 5 --no-render").exitCode, 0);
  const std::string before = test::readWholeFile(dir_ / "out" / "summary.json");
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\ncat >/dev/null\nexit 4\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const auto r = run("out", "--frames 4 --video '" + (dir_ / "out" / "v.mp4").string() + "'",
                     "PATH='" + bin.string() + ":/usr/bin:/bin' ");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_NE(r.err.find("ffmpeg failed (exit status 4)"), std::string::npos) << r.err;
  EXPECT_EQ(names(dir_ / "out"), (std::vector<std::string>{"stats.csv", "summary.json"})) << "no frames/ or charts/";
  EXPECT_EQ(test::readWholeFile(dir_ / "out" / "summary.json"), before);
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(OutputStaging, ADiffThatMeetsACorruptFrameWritesNothing) {
  ASSERT_EQ(run("ref", "--frames 4").exitCode, 0);
  ASSERT_EQ(run("new", "--frames 4").exitCode, 0);
  // A header that reads, then garbage: found only while the frames are compared.
  const fs::path bad = dir_ / "new" / "frames" / "frame_00003.png";
  std::string bytes = test::readWholeFile(bad);
  bytes.resize(60);
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes << std::string(200, '\x5a');
  const auto d = runHaif("diff '" + (dir_ / "ref").string() + "' '" + (dir_ / "new").string() + "' --out '" +
                             (dir_ / "diff").string() + "'",
                         dir_ / "log");
  EXPECT_EQ(d.exitCode, 2) << d.err;
  EXPECT_NE(d.err.find("frame_00003.png"), std::string::npos) << d.err;
  EXPECT_EQ(std::count(d.err.begin(), d.err.end(), '\n'), 1) << d.err;
  EXPECT_FALSE(fs::exists(dir_ / "diff"));
  EXPECT_TRUE(leftovers().empty());
}

// Starts haif in the background (stderr to a file) and returns its pid.
pid_t startHaif(const std::vector<std::string>& args, const fs::path& errFile) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    std::vector<char*> argv{const_cast<char*>(HAIF_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(HAIF_BINARY, argv.data());
    ::_exit(127);
  }
  return pid;
}

// Waits until `ready` holds (or 60 s pass); on a timeout stops `pid`, which would run on for hours.
template <class F>
bool waitFor(pid_t pid, F ready) {
  for (int i = 0; i < 600; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  return false;
}

void expectInterrupted(pid_t pid, int sig, const fs::path& errFile) {
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << " instead of exiting";
  EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
  const std::string err = test::readWholeFile(errFile);
  const std::string name = sig == SIGINT ? "SIGINT" : "SIGTERM";
  EXPECT_NE(err.find("haif run: interrupted (" + name + "): stopped before it finished"), std::string::npos) << err;
  // One line besides the progress lines ("run: step 300/1000000 ...") a long run prints.
  std::istringstream lines(err);
  int other = 0;
  for (std::string line; std::getline(lines, line);) other += line.rfind("run: ", 0) == 0 ? 0 : 1;
  EXPECT_EQ(other, 1) << err;
}

TEST_F(OutputStaging, AnInterruptRemovesTheUnfinishedRunAndSaysSo) {
  const fs::path out = dir_ / "out", errFile = dir_ / "err.txt";
  const pid_t pid = startHaif({"run", scene_, "--frames", "1000000", "--width", "64", "--height", "48",
                               "--error-every", "0", "--threads", "1", "--out", out.string()},
                              errFile);
  // Interrupted while frames are being written into the temporary folder.
  ASSERT_TRUE(waitFor(pid, [&] {
    for (const std::string& n : names(dir_))
      if (n[0] == '.' && pngCount(dir_ / n / "frames") >= 3) return true;
    return false;
  }));
  expectInterrupted(pid, SIGINT, errFile);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(leftovers().empty()) << leftovers()[0];
}

TEST_F(OutputStaging, SigtermStopsFfmpegAndRemovesTheUnfinishedVideo) {
  if (!test::haveProgram("ffmpeg")) GTEST_SKIP() << "ffmpeg not installed";
  const fs::path out = dir_ / "out", video = dir_ / "clip.mp4", errFile = dir_ / "err.txt";
  const pid_t pid = startHaif({"run", scene_, "--frames", "1000000", "--width", "64", "--height", "48",
                               "--error-every", "0", "--threads", "1", "--out", out.string(), "--video",
                               video.string()},
                              errFile);
  ASSERT_TRUE(waitFor(pid, [&] {
    const auto n = names(dir_);
    return std::any_of(n.begin(), n.end(), [](const std::string& s) { return s.find(".clip.tmp") == 0; });
  }));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  expectInterrupted(pid, SIGTERM, errFile);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(video));
  EXPECT_TRUE(leftovers().empty()) << leftovers()[0];
  // No ffmpeg of ours is left running ("[.]" keeps pgrep's own shell from matching).
  EXPECT_NE(std::system(("pgrep -f '" + video.parent_path().string() + "/[.]clip[.]tmp' >/dev/null").c_str()), 0);
}

}  // namespace
}  // namespace haif
