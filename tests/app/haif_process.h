// Running the built haif command from a test: exit status, stdout and stderr.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace haif::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string readWholeFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs `haif ARGS` through the shell (ARGS are shell words) with `envPrefix` (e.g. "PATH=/x ")
/// in front; output is captured in files under `scratch`.
inline ProcessResult runHaif(const std::string& args, const std::filesystem::path& scratch,
                             const std::string& envPrefix = "") {
  std::filesystem::create_directories(scratch);
  const auto out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string cmd = envPrefix + "'" + std::string(HAIF_BINARY) + "' " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = readWholeFile(out);
  r.err = readWholeFile(err);
  return r;
}

/// A unique scratch folder under the system temp folder.
inline std::filesystem::path scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// A test with a scratch folder of its own, dir_, named after its suite and test (and the process),
/// made empty before the test and removed after it.
class ScratchFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = scratchDir(std::string("haif_") + info->test_suite_name() + "_" + info->name());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

}  // namespace haif::test
