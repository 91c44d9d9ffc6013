// Frame folders for `haif diff`: locating frames, pairing them, refusing bad input with a clear message,
// and the stats.csv comparison that leaves timing columns out.
#include "render/png_io.h"
#include "support/scratch_folder.h"
#include "tools/diff_report.h"
#include "tools/frame_diff.h"
#include "tools/stats_diff.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;

class FrameDiff : public haif::test::ScratchFolderTest {
 protected:
  void writeFrame(const fs::path& folder, const std::string& name, const Image& img) {
    fs::create_directories(folder);
    std::string error;
    ASSERT_TRUE(render::writePng((folder / name).string(), img.width, img.height, img.rgba.data(), &error)) << error;
  }
};

TEST_F(FrameDiff, RunFolderResolvesToItsFramesAndReadsMasks) {
  writeFrame(dir_ / "run" / "frames", "frame_00001.png", Image(40, 30, 10, 20, 30));
  writeFrame(dir_ / "run" / "frames", "frame_00000.png", Image(40, 30, 10, 20, 30));
  FrameMasks m;
  m.width = 40, m.height = 30;
  m.regions.push_back({"overlay", PixelRect{1, 2, 20, 12}});
  std::ofstream(dir_ / "run" / "frames" / kFrameMasksFile) << frameMasksJson(m);
  FrameFolder f;
  std::string error;
  ASSERT_TRUE(openFrameFolder((dir_ / "run").string(), "reference", f, error)) << error;
  EXPECT_EQ(f.runDir, (dir_ / "run").string());
  EXPECT_EQ(f.frames, (std::vector<std::string>{"frame_00000.png", "frame_00001.png"}));
  EXPECT_EQ(f.width, 40);
  EXPECT_EQ(f.height, 30);
  ASSERT_TRUE(f.hasMasks);
  ASSERT_EQ(f.masks.regions.size(), 1u);
  EXPECT_EQ(f.masks.regions[0].name, "overlay");
  EXPECT_EQ(f.masks.regions[0].rect.x1, 20);
  EXPECT_EQ(f.masks.regions[0].rect.y1, 12);
}

TEST_F(FrameDiff, BadInputIsClearlySaid) {
  FrameFolder f;
  std::string error;
  EXPECT_FALSE(openFrameFolder((dir_ / "nowhere").string(), "reference", f, error));
  EXPECT_NE(error.find("no such folder"), std::string::npos) << error;
  EXPECT_NE(error.find("nowhere"), std::string::npos) << error;

  fs::create_directories(dir_ / "empty");
  EXPECT_FALSE(openFrameFolder((dir_ / "empty").string(), "new", f, error));
  EXPECT_NE(error.find("no PNG frames"), std::string::npos) << error;

  std::ofstream(dir_ / "empty" / kFrameMasksFile) << "{\"width\": 4, \"height\": 4, \"regions\": [{\"x0\": 1}]}";
  writeFrame(dir_ / "empty", "frame_00000.png", Image(4, 4));
  EXPECT_FALSE(openFrameFolder((dir_ / "empty").string(), "new", f, error));
  EXPECT_NE(error.find("regions[0].y0"), std::string::npos) << error;
}

TEST_F(FrameDiff, SizeAndFrameListMismatchesAreRefused) {
  writeFrame(dir_ / "a", "frame_00000.png", Image(40, 30));
  writeFrame(dir_ / "a", "frame_00001.png", Image(40, 30));
  writeFrame(dir_ / "b", "frame_00000.png", Image(40, 30));
  writeFrame(dir_ / "b", "frame_00001.png", Image(42, 30));
  writeFrame(dir_ / "c", "frame_00000.png", Image(40, 30));
  FrameFolder a, b, c;
  std::string error;
  ASSERT_TRUE(openFrameFolder((dir_ / "a").string(), "reference", a, error)) << error;
  ASSERT_TRUE(openFrameFolder((dir_ / "b").string(), "new", b, error)) << error;
  ASSERT_TRUE(openFrameFolder((dir_ / "c").string(), "new", c, error)) << error;
  EXPECT_FALSE(checkFramePairs(a, b, error));
  EXPECT_NE(error.find("size mismatch at frame_00001.png"), std::string::npos) << error;
  EXPECT_NE(error.find("40x30"), std::string::npos) << error;
  EXPECT_NE(error.find("42x30"), std::string::npos) << error;
  EXPECT_FALSE(checkFramePairs(a, c, error));
  EXPECT_NE(error.find("frame_00001.png is missing from the new side"), std::string::npos) << error;
  EXPECT_TRUE(checkFramePairs(a, a, error));
}

TEST_F(FrameDiff, FoldersAreComparedPairByPairWithDiffImages) {
  Image base(48, 32, 200, 210, 220);
  Image changed = base;
  for (int y = 8; y < 16; ++y)
    for (int x = 30; x < 40; ++x) changed.at(x, y)[0] = 20;
  writeFrame(dir_ / "a", "frame_00000.png", base);
  writeFrame(dir_ / "a", "frame_00001.png", base);
  writeFrame(dir_ / "b", "frame_00000.png", base);
  writeFrame(dir_ / "b", "frame_00001.png", changed);
  FrameFolder a, b;
  std::string error;
  ASSERT_TRUE(openFrameFolder((dir_ / "a").string(), "reference", a, error)) << error;
  ASSERT_TRUE(openFrameFolder((dir_ / "b").string(), "new", b, error)) << error;
  fs::create_directories(dir_ / "out");
  std::vector<FrameVerdict> verdicts;
  int calls = 0;
  ASSERT_TRUE(diffFrameFolders(a, b, DiffOptions{}, FrameThresholds{}, (dir_ / "out").string(), verdicts, error,
                               [&](int) { ++calls; }))
      << error;
  EXPECT_EQ(calls, 2);
  ASSERT_EQ(verdicts.size(), 2u);
  EXPECT_TRUE(verdicts[0].pass);
  EXPECT_FALSE(verdicts[1].pass);
  EXPECT_EQ(verdicts[1].result.differentPixels, 80);
  EXPECT_EQ(verdicts[1].result.changed.x0, 30);
  EXPECT_EQ(verdicts[1].result.changed.y0, 8);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "frame_00001.png"));

  DiffReport report;
  report.reference = a;
  report.test = b;
  report.frames = verdicts;
  EXPECT_FALSE(report.pass());
  const std::string html = diffReportHtml(report, (dir_ / "out").string());
  // Failures first: frame 1 is listed before frame 0.
  EXPECT_LT(html.find("<td>frame_00001.png"), html.find("<td>frame_00000.png"));
  // The command that accepts the new frames sits above the table.
  EXPECT_LT(html.find("rm -rf &#39;" + a.given), html.find("<table>"));
  EXPECT_NE(report.updateCommand().find("cp -a '" + b.given + "' '" + a.given + "'"), std::string::npos);
}

TEST(StatsDiff, TimingColumnsAreIgnoredAndPhysicsColumnsCompared) {
  const std::string header = "step,total_ms,deadline_miss,iterations_chosen,residual\n";
  const std::string a = header + "0,1.5,0,10,0.01\n1,1.7,1,10,0.02\n";
  const std::string sameButSlower = header + "0,9.5,1,10,0.01\n1,8.0,0,10,0.02\n";
  const std::string differs = header + "0,1.5,0,10,0.01\n1,1.7,1,2,0.52\n";
  StatsDiff d;
  std::string error;
  ASSERT_TRUE(compareStatsCsv(a, sameButSlower, "a.csv", "b.csv", d, error)) << error;
  EXPECT_TRUE(d.equal());
  EXPECT_EQ(d.ignoredColumns, (std::vector<std::string>{"total_ms", "deadline_miss"}));
  ASSERT_TRUE(compareStatsCsv(a, differs, "a.csv", "b.csv", d, error)) << error;
  EXPECT_FALSE(d.equal());
  ASSERT_EQ(d.differing.size(), 2u);
  EXPECT_EQ(d.differing[0].column, "iterations_chosen");
  EXPECT_EQ(d.differing[0].firstRow, 1);
  EXPECT_EQ(d.differing[0].reference, "10");
  EXPECT_EQ(d.differing[0].test, "2");
  EXPECT_NEAR(d.differing[1].maxAbsDiff, 0.5, 1e-12);
  EXPECT_FALSE(compareStatsCsv(a, "step,x\n0\n", "a.csv", "b.csv", d, error));
  EXPECT_NE(error.find("b.csv:2"), std::string::npos) << error;
}

}  // namespace
}  // namespace haif
