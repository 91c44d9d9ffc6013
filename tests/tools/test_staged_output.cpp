// Output folders that appear whole or not at all (tools/staged_output.h): built beside the target,
// moved into place on commit, replacing an earlier output as a whole; discarded without a trace
// otherwise; and never replacing a folder the command did not write.
#include "support/scratch_folder.h"
#include "tools/staged_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;

class StagedOutput : public haif::test::ScratchFolderTest {
 protected:
  // Names in `folder`, sorted.
  static std::vector<std::string> names(const fs::path& folder) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(folder)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
};

TEST_F(StagedOutput, NothingIsAtTheTargetUntilCommit) {
  const fs::path target = dir_ / "run";
  StagedFolder f;
  std::string error;
  ASSERT_TRUE(f.open(target.string(), {"summary.json"}, error)) << error;
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(fs::path(f.path()).parent_path(), dir_) << "built beside the target";
  std::ofstream(fs::path(f.path()) / "summary.json") << "{}";
  ASSERT_TRUE(f.commit(error)) << error;
  EXPECT_EQ(names(target), std::vector<std::string>{"summary.json"});
  EXPECT_EQ(names(dir_), std::vector<std::string>{"run"}) << "no temporary folder left";
}

TEST_F(StagedOutput, AnEarlierOutputIsReplacedAsAWhole) {
  const fs::path target = dir_ / "run";
  fs::create_directories(target / "frames");
  for (const char* n : {"frame_00000.png", "frame_00001.png", "frame_00002.png"}) std::ofstream(target / "frames" / n) << "x";
  std::ofstream(target / "summary.json") << "{\"steps\": 3}";
  StagedFolder f;
  std::string error;
  ASSERT_TRUE(f.open(target.string(), {"summary.json"}, error)) << error;
  fs::create_directories(fs::path(f.path()) / "frames");
  std::ofstream(fs::path(f.path()) / "frames" / "frame_00000.png") << "y";
  std::ofstream(fs::path(f.path()) / "summary.json") << "{\"steps\": 1}";
  ASSERT_TRUE(f.commit(error)) << error;
  EXPECT_EQ(names(target / "frames"), std::vector<std::string>{"frame_00000.png"}) << "no stale frames";
  EXPECT_EQ(names(dir_), std::vector<std::string>{"run"}) << "the old folder is gone";
}

TEST_F(StagedOutput, ADiscardedOutputLeavesNothingNotEvenTheParentsItMade) {
  const fs::path target = dir_ / "a" / "b" / "run";
  {
    StagedFolder f;
    std::string error;
    ASSERT_TRUE(f.open(target.string(), {}, error)) << error;
    EXPECT_TRUE(fs::is_directory(dir_ / "a" / "b"));
    std::ofstream(fs::path(f.path()) / "half_written.png") << "x";
  }  // not committed
  EXPECT_TRUE(names(dir_).empty());
}

TEST_F(StagedOutput, AFolderThisCommandDidNotWriteIsNeverReplaced) {
  const fs::path target = dir_ / "notes";
  fs::create_directories(target);
  std::ofstream(target / "thesis.tex") << "precious";
  StagedFolder f;
  std::string error;
  EXPECT_FALSE(f.open(target.string(), {"summary.json", "stats.csv"}, error));
  EXPECT_NE(error.find("is not an output folder of this command (no summary.json or stats.csv in it)"),
            std::string::npos)
      << error;
  EXPECT_EQ(names(target), std::vector<std::string>{"thesis.tex"});
  EXPECT_EQ(names(dir_), std::vector<std::string>{"notes"});
  // An empty folder may be used.
  fs::create_directories(dir_ / "empty");
  EXPECT_TRUE(checkOutputFolder((dir_ / "empty").string(), {"summary.json"}, error)) << error;
  // A file is not a folder.
  std::ofstream(dir_ / "file") << "x";
  EXPECT_FALSE(checkOutputFolder((dir_ / "file").string(), {}, error));
  EXPECT_NE(error.find("exists and is not a folder"), std::string::npos) << error;
}

TEST_F(StagedOutput, TheCurrentFolderAndItsParentsAreNeverOutputFolders) {
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  std::ofstream("summary.json") << "{}";
  std::string error;
  EXPECT_FALSE(checkOutputFolder(".", {"summary.json"}, error));
  EXPECT_NE(error.find("holds the current folder"), std::string::npos) << error;
  EXPECT_FALSE(checkOutputFolder("..", {}, error));
  EXPECT_FALSE(checkOutputFolder("/", {}, error));
  fs::current_path(cwd);
}

TEST_F(StagedOutput, OutputFilesAreCheckedWithoutCreatingAnything) {
  std::string error;
  EXPECT_TRUE(checkOutputFile((dir_ / "x" / "y" / "v.mp4").string(), error)) << error;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
  EXPECT_FALSE(checkOutputFile(dir_.string(), error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
  std::ofstream(dir_ / "plain") << "x";
  EXPECT_FALSE(checkOutputFile((dir_ / "plain" / "v.mp4").string(), error));
  EXPECT_NE(error.find("is not a folder"), std::string::npos) << error;
}

TEST_F(StagedOutput, InsideComparesNormalisedPaths) {
  std::string rest;
  EXPECT_TRUE(isInside((dir_ / "out" / "v" / "x.mp4").string(), (dir_ / "out/").string(), rest));
  EXPECT_EQ(rest, "v/x.mp4");
  EXPECT_TRUE(isInside((dir_ / "out" / ".." / "out" / "x.mp4").string(), (dir_ / "out").string(), rest));
  EXPECT_FALSE(isInside((dir_ / "outside.mp4").string(), (dir_ / "out").string(), rest));
  EXPECT_FALSE(isInside((dir_ / "out").string(), (dir_ / "out").string(), rest));
}

}  // namespace
}  // namespace haif
