// CostModel files: save/load round trip; bad files give an error naming the file and line.
#include "haif/cost_model.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("haif_cost_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

TEST(CostModel, SaveLoadRoundTrip) {
  CostModel m;
  m.msPerRowIteration = 1.25e-5;
  m.msPerRowPrepare = 3.5e-5;
  m.msPerContactPoint = 1.75e-4;
  m.msPerBody = 6.25e-4;
  m.parallelEfficiency = 0.7;
  const std::string path = tempFile("model.txt").string();
  std::string error;
  ASSERT_TRUE(m.save(path, error)) << error;
  CostModel back;  // defaults differ from every value above
  ASSERT_TRUE(back.load(path, error)) << error;
  EXPECT_DOUBLE_EQ(back.msPerRowIteration, m.msPerRowIteration);
  EXPECT_DOUBLE_EQ(back.msPerRowPrepare, m.msPerRowPrepare);
  EXPECT_DOUBLE_EQ(back.msPerContactPoint, m.msPerContactPoint);
  EXPECT_DOUBLE_EQ(back.msPerBody, m.msPerBody);
  EXPECT_DOUBLE_EQ(back.parallelEfficiency, m.parallelEfficiency);
  EXPECT_FALSE(fs::exists(path + ".tmp")) << "temporary file left behind";
  fs::remove_all(fs::path(path).parent_path());
}

void expectLoadError(const std::string& text, const std::string& where, const std::string& what) {
  const std::string path = tempFile("bad.txt").string();
  std::ofstream(path) << text;
  CostModel m;
  m.msPerBody = 1.0e-3;
  std::string error;
  EXPECT_FALSE(m.load(path, error)) << text;
  EXPECT_NE(error.find(path + ":" + where), std::string::npos) << "error: " << error;
  EXPECT_NE(error.find(what), std::string::npos) << "error: " << error;
  EXPECT_DOUBLE_EQ(m.msPerBody, 1.0e-3) << "a failed load must not change the model";
  fs::remove_all(fs::path(path).parent_path());
}

TEST(CostModel, BadNumberNamesFileAndLine) {
  expectLoadError("# comment\nms_per_body 0.001\nms_per_row_iteration abc\n", "3:", "ms_per_row_iteration");
}

TEST(CostModel, UnknownKeyNamesFileAndLine) {
  expectLoadError("ms_per_body 0.002\n\nms_per_bodies 0.1\n", "3:", "ms_per_bodies");
}

TEST(CostModel, NegativeOrZeroIsRejected) {
  expectLoadError("ms_per_body -1\n", "1:", "ms_per_body");
  expectLoadError("parallel_efficiency 0\n", "1:", "parallel_efficiency");
}

TEST(CostModel, MissingFileNamesTheFile) {
  CostModel m;
  std::string error;
  EXPECT_FALSE(m.load("/nonexistent/haif/cost.txt", error));
  EXPECT_NE(error.find("/nonexistent/haif/cost.txt"), std::string::npos) << error;
}

TEST(CostModel, UnwritablePathIsAnError) {
  CostModel m;
  std::string error;
  EXPECT_FALSE(m.save("/proc/haif_no/cost.txt", error));
  EXPECT_NE(error.find("/proc/haif_no/cost.txt"), std::string::npos) << error;
}

}  // namespace
}  // namespace haif
