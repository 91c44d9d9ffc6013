// Scratch folders for tests that write files: one per test, under the system temp folder.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>
#include <unistd.h>

namespace haif::test {

/// Removes, when the test process ends, every scratch folder it made, so that runs of the suite
/// leave nothing under the temp folder (ctest runs each test in a process of its own). Set
/// HAIF_KEEP_SCRATCH to keep them for a look after a failure.
class ScratchCleanup {
 public:
  static void add(const std::filesystem::path& dir) { instance().dirs_.push_back(dir); }
  ~ScratchCleanup() {
    if (std::getenv("HAIF_KEEP_SCRATCH") != nullptr) return;
    std::error_code ignored;
    for (const auto& d : dirs_) std::filesystem::remove_all(d, ignored);
  }

 private:
  static ScratchCleanup& instance() {
    static ScratchCleanup cleanup;
    return cleanup;
  }
  std::vector<std::filesystem::path> dirs_;
};

/// A unique scratch folder under the system temp folder, removed when the process ends.
inline std::filesystem::path scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ScratchCleanup::add(dir);
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
