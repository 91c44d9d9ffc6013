// Inputs that once broke the commands (issue 26): 20,000 nested brackets crashed every command that
// reads a scene; a folder given as the scene read as "1:1 syntax error"; a scene name that is a path
// wrote outside output/; a replay of a fixed run did not reproduce it, and a replay log of another
// scene, or a shorter one, was accepted. Each is now one clear line, a non-zero exit (below 128: no
// signal) and nothing written.
#include "haif_process.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

const char* kStack = R"({"name": "hardening_stack", "camera": {"eye": [9, 6, 9], "target": [0, 2, 0]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 4}]})";

class BadInputHardening : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    std::ofstream(dir_ / "stack.json") << kStack;
    // A deep array inside a comment: no code reads it, the scanner of value positions did.
    std::ofstream(dir_ / "deep.json") << "{\"_comment\": " << std::string(20000, '[') << std::string(20000, ']')
                                      << ", \"generators\": [{\"type\": \"ground\"}]}";
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Non-zero exit without a signal, one line on stderr holding every needle.
  static void expectOneLineFailure(const test::ProcessResult& r, std::initializer_list<std::string> needles) {
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
  }

  // Names in the scratch folder other than the test's own files.
  std::vector<std::string> written() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (n != "stack.json" && n != "deep.json" && n != "stdout.txt" && n != "stderr.txt" && n != "reel.json")
        out.push_back(n);
    }
    return out;
  }
};

TEST_F(BadInputHardening, DeepNestingIsOneErrorInEveryCommandThatReadsAScene) {
  const std::string where = path("deep.json") + ":1:269: syntax error: nested deeper than 256 levels of [ and {";
  expectOneLineFailure(runHaif("run '" + path("deep.json") + "' --no-render --frames 2 --out '" + path("out") + "'", dir_),
                       {where});
  expectOneLineFailure(runHaif("stress '" + path("deep.json") + "' --out '" + path("out") + "'", dir_), {where});
  expectOneLineFailure(runHaif("compare '" + path("deep.json") + "' --left fixed:2 --right fixed:4 --frames 2 --width 128 "
                               "--height 200 --out '" + path("out.mp4") + "'",
                               dir_),
                       {where});
  // A playlist nested too deep, and a playlist naming the deep scene.
  std::ofstream(dir_ / "reel.json") << "{\"items\": " << std::string(300, '[') << std::string(300, ']') << "}";
  expectOneLineFailure(runHaif("reel '" + path("reel.json") + "' --check", dir_),
                       {path("reel.json") + ":1:", "nested deeper than 256 levels"});
  std::ofstream(dir_ / "reel.json") << R"({"items": [{"type": "scene", "scene": "deep.json", "seconds": 1}]})";
  expectOneLineFailure(runHaif("reel '" + path("reel.json") + "' --check", dir_), {"nested deeper than 256 levels"});
  EXPECT_TRUE(written().empty());
}

TEST_F(BadInputHardening, AFolderGivenAsTheSceneOrPlaylistSaysSo) {
  expectOneLineFailure(runHaif("run '" + dir_.string() + "' --no-render --frames 2 --out '" + path("out") + "'", dir_),
                       {dir_.string() + ": is a directory, not a scene file"});
  expectOneLineFailure(runHaif("reel '" + dir_.string() + "' --check", dir_),
                       {dir_.string() + ": is a directory, not a playlist"});
  EXPECT_TRUE(written().empty());
}

TEST_F(BadInputHardening, ASceneNameThatIsAPathWritesNothingOutsideOutput) {
  fs::create_directories(dir_ / "a" / "b");
  const std::string text = "{\n  \"name\": \"../../../escaped\",\n  \"generators\": [{\"type\": \"ground\"}]\n}\n";
  std::ofstream(dir_ / "a" / "b" / "escape.json") << text;
  // From a/b, output/../../../escaped would be dir_/escaped.
  const auto r = runHaif("run escape.json --no-render --frames 2", dir_, "cd '" + (dir_ / "a" / "b").string() + "' && ");
  expectOneLineFailure(r, {"escape.json:2:11: name: must be a plain name, not a path (got '../../../escaped')"});
  EXPECT_FALSE(fs::exists(dir_ / "escaped"));
  EXPECT_FALSE(fs::exists(dir_ / "a" / "b" / "output"));
}

TEST_F(BadInputHardening, ReplayOfAFixedRunReproducesItsStateHash) {
  const std::string scene = std::string(HAIF_SOURCE_DIR) + "/scenes/tower_collapse.json";
  const auto a = runHaif("run '" + scene + "' --no-render --frames 30 --threads 2 --out '" + path("fixed") + "'", dir_);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const auto b = runHaif("run '" + scene + "' --no-render --frames 30 --threads 1 --replay '" + path("fixed") +
                             "/stats.csv' --out '" + path("replayed") + "'",
                         dir_);
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const auto summary = [&](const std::string& run) {
    return nlohmann::json::parse(test::readWholeFile(dir_ / run / "summary.json"));
  };
  EXPECT_EQ(summary("replayed")["state_hash"], summary("fixed")["state_hash"]);
  EXPECT_EQ(summary("fixed")["scene_hash"], summary("replayed")["scene_hash"]);
  EXPECT_EQ(summary("fixed")["scene_hash"].get<std::string>().size(), 16u);
}

TEST_F(BadInputHardening, AReplayLogOfAnotherSceneOrShorterThanTheRunIsRefused) {
  const auto a = runHaif("run '" + path("stack.json") + "' --no-render --frames 5 --out '" + path("log") + "'", dir_);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const std::string other = std::string(HAIF_SOURCE_DIR) + "/scenes/stacks_100.json";
  const std::string log = path("log") + "/stats.csv";
  expectOneLineFailure(
      runHaif("run '" + other + "' --no-render --frames 5 --replay '" + log + "' --out '" + path("r1") + "'", dir_),
      {log + ": a log of scene 'hardening_stack'", "not of " + other});
  expectOneLineFailure(
      runHaif("run '" + path("stack.json") + "' --no-render --frames 6 --replay '" + log + "' --out '" + path("r2") + "'",
              dir_),
      {log + ": the log holds 5 steps, fewer than the 6 to run"});
  expectOneLineFailure(runHaif("compare '" + path("stack.json") + "' --left fixed:10 --right replay:" + log +
                                   " --frames 6 --width 128 --height 200 --out '" + path("c.mp4") + "'",
                               dir_),
                       {"right side: replay:" + log + ": the log holds 5 steps, fewer than the 6 to show"});
  EXPECT_FALSE(fs::exists(dir_ / "r1"));
  EXPECT_FALSE(fs::exists(dir_ / "r2"));
  EXPECT_FALSE(fs::exists(dir_ / "c.mp4"));
  // The same length is fine.
  EXPECT_EQ(runHaif("run '" + path("stack.json") + "' --no-render --frames 5 --replay '" + log + "' --out '" +
                        path("r3") + "'",
                    dir_)
                .exitCode,
            0);
}

}  // namespace
}  // namespace haif
