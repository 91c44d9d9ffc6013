// haif diff end to end: two equal runs diff clean, fewer solver iterations are flagged, a painted
// region is found where it is, masks hide what they cover, and bad input exits 2 with a clear line.
#include "haif_process.h"
#include "render/png_io.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace haif {
namespace {

namespace fs = std::filesystem;
using test::runHaif;

// Two stacks of 12 boxes, seen in the left half of the frame (the overlay panel is on the right): with
// 2 solver iterations they visibly sag within a second and a half when solved contact by contact with
// the step's count (solved as chains, or given sweeps for their depth while they land, they would
// stand at 2 iterations as well as at 10).
const char* kStackScene = R"({"name": "diff_stacks", "settings": {"iterations": 10, "chain_solve": false,
  "moving_layers_per_sweep": 0},
  "camera": {"eye": [17, 8, 11], "target": [3, 5, -3]},
  "generators": [{"type": "ground"}, {"type": "stack", "count": 12, "position": [1.5, 0, 0]},
                 {"type": "stack", "count": 12, "position": [-1.5, 0, 0]}]})";

class DiffCommand : public ::testing::Test {
 protected:
  // The runs are shared by every test: rendering is the slow part.
  static void SetUpTestSuite() {
    dir_ = test::scratchDir("haif_diff_cmd");
    scene_ = (dir_ / "stacks.json").string();
    std::ofstream(scene_) << kStackScene;
    makeRun("ref", "--iterations 10");
    makeRun("same", "--iterations 10");
    makeRun("fewer", "--iterations 2");
    makeRun("wide", "--iterations 10 --width 320");
    makeRun("adaptive", "--mode adaptive --budget-ms 4");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static void makeRun(const std::string& name, const std::string& options) {
    const auto r = runHaif("run '" + scene_ + "' --frames 90 --frame-every 15 --width 384 --height 192 " +
                               "--overlay-corner tr --error-every 0 --out '" + (dir_ / name).string() + "' " + options,
                           dir_ / ("log_" + name));
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }

  test::ProcessResult diff(const std::string& a, const std::string& b, const std::string& out,
                           const std::string& extra = "") {
    return runHaif("diff '" + a + "' '" + b + "' --out '" + (dir_ / out).string() + "' " + extra,
                   dir_ / ("log_" + out));
  }

  static nlohmann::json report(const std::string& out) {
    return nlohmann::json::parse(test::readWholeFile(dir_ / out / "report.json"));
  }

  static std::string path(const std::string& name) { return (dir_ / name).string(); }

  // A copy of a run's PNG frames (not its masks.json) with a block painted into one frame.
  static void paintedCopy(const std::string& to, const std::string& frame, int x0, int y0, int x1, int y1) {
    fs::create_directories(dir_ / to);
    for (const auto& e : fs::directory_iterator(dir_ / "ref" / "frames"))
      if (e.path().extension() == ".png")
        fs::copy_file(e.path(), dir_ / to / e.path().filename(), fs::copy_options::overwrite_existing);
    int w = 0, h = 0;
    std::vector<uint8_t> rgba;
    std::string error;
    const std::string p = (dir_ / to / frame).string();
    ASSERT_TRUE(render::readPng(p, &w, &h, &rgba, &error)) << error;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        uint8_t* px = &rgba[4 * (size_t(y) * size_t(w) + size_t(x))];
        px[0] = 255, px[1] = 0, px[2] = 255;
      }
    ASSERT_TRUE(render::writePng(p, w, h, rgba.data(), &error)) << error;
  }

  static inline fs::path dir_;
  static inline std::string scene_;
};

TEST_F(DiffCommand, TwoIdenticalRunsDiffClean) {
  const auto r = diff(path("ref"), path("same"), "d_same");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("pass"), std::string::npos) << r.out;
  const auto j = report("d_same");
  EXPECT_EQ(j["verdict"], "pass");
  EXPECT_EQ(j["frames_total"], 6);
  EXPECT_EQ(j["frames_failed"], 0);
  EXPECT_EQ(j["stats"]["pass"], true);
  EXPECT_EQ(j["stats"]["differing_columns"].size(), 0u);
  // The overlay (step timings) is masked by default, from the run's frames/masks.json.
  ASSERT_EQ(j["masks"].size(), 1u);
  EXPECT_EQ(j["masks"][0]["name"], "overlay");
  EXPECT_GT(j["masks"][0]["x0"].get<int>(), 0);
  for (const auto& f : j["frames"]) {
    EXPECT_EQ(f["different_pixels"], 0);
    EXPECT_DOUBLE_EQ(f["ssim"].get<double>(), 1.0);
    EXPECT_TRUE(fs::exists(dir_ / "d_same" / f["diff_image"].get<std::string>()));
  }
  const std::string html = test::readWholeFile(dir_ / "d_same" / "report.html");
  EXPECT_NE(html.find("PASS"), std::string::npos);
  EXPECT_NE(html.find("cp -a"), std::string::npos);
}

TEST_F(DiffCommand, FixedTenAgainstFixedTwoIsFlagged) {
  const auto r = diff(path("ref"), path("fewer"), "d_fewer");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  const auto j = report("d_fewer");
  EXPECT_EQ(j["verdict"], "fail");
  // Flagged by the pixels themselves, not only by stats.csv: the stacks sag with 2 iterations.
  EXPECT_GE(j["frames_failed"].get<int>(), 1);
  EXPECT_EQ(j["frames"][0]["pass"], true);  // the first frame is drawn before the solvers differ much
  bool iterationsFlagged = false;
  for (const auto& c : j["stats"]["differing_columns"]) iterationsFlagged |= c["column"] == "iterations_chosen";
  EXPECT_TRUE(iterationsFlagged);
  EXPECT_NE(j["stats"]["state_hash_reference"], j["stats"]["state_hash_new"]);
  // Failures first in the HTML table.
  const std::string html = test::readWholeFile(dir_ / "d_fewer" / "report.html");
  EXPECT_LT(html.find("FAIL</b>"), html.find("<td>pass</td>"));
}

TEST_F(DiffCommand, OneChangedRegionIsFoundWhereItIsAndMasksHideIt) {
  paintedCopy("painted", "frame_00003.png", 20, 120, 44, 140);
  const auto r = diff(path("ref") + "/frames", path("painted"), "d_painted");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  const auto j = report("d_painted");
  EXPECT_EQ(j["frames_failed"], 1);
  const auto& f = j["frames"][3];
  EXPECT_EQ(f["frame"], "frame_00003.png");
  EXPECT_EQ(f["pass"], false);
  EXPECT_EQ(f["changed_region"]["x0"], 20);
  EXPECT_EQ(f["changed_region"]["y0"], 120);
  EXPECT_EQ(f["changed_region"]["x1"], 44);
  EXPECT_EQ(f["changed_region"]["y1"], 140);
  // Every painted pixel is noticed; a few over the ground's grid lines can pass for anti-aliasing.
  EXPECT_EQ(f["different_pixels"].get<int>() + f["antialiased_pixels"].get<int>(), 24 * 20);
  EXPECT_GT(f["different_pixels"].get<int>(), 24 * 20 * 8 / 10);
  EXPECT_TRUE(j["stats"].is_null());  // plain frame folders: nothing to compare there

  // A mask over the block: clean again.
  const auto masked = diff(path("ref") + "/frames", path("painted"), "d_masked", "--mask 16:116:50:150");
  EXPECT_EQ(masked.exitCode, 0) << masked.out << masked.err;

  // Paint inside the overlay panel: hidden by the default mask, found with --mask none.
  nlohmann::json masks = nlohmann::json::parse(test::readWholeFile(dir_ / "ref" / "frames" / "masks.json"));
  const int ox = masks["regions"][0]["x0"], oy = masks["regions"][0]["y0"];
  paintedCopy("in_overlay", "frame_00002.png", ox + 10, oy + 10, ox + 30, oy + 20);
  fs::copy_file(dir_ / "ref" / "frames" / "masks.json", dir_ / "in_overlay" / "masks.json",
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(diff(path("ref"), path("in_overlay"), "d_overlay").exitCode, 0);
  const auto unmasked = diff(path("ref"), path("in_overlay"), "d_overlay_none", "--mask none");
  EXPECT_EQ(unmasked.exitCode, 1) << unmasked.out << unmasked.err;
  EXPECT_EQ(report("d_overlay_none")["frames"][2]["changed_region"]["x0"], ox + 10);
}

TEST_F(DiffCommand, BadInputExitsTwoWithOneClearLine) {
  auto expectBad = [&](const test::ProcessResult& r, std::initializer_list<std::string> needles) {
    EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "no '" << n << "' in " << r.err;
  };
  expectBad(diff(path("ref"), path("missing"), "d_bad1"), {"new", "missing", "no such folder"});
  expectBad(diff(path("ref"), path("wide"), "d_bad2"), {"size mismatch", "384x192", "320x192"});
  expectBad(diff(path("ref"), path("same"), "d_bad3", "--mask 1:2:3"), {"--mask", "1:2:3"});
  expectBad(diff(path("ref"), path("adaptive"), "d_bad4"), {"adaptive", "fixed, model or replay"});
  expectBad(diff(path("ref"), path("same"), "d_bad5", "--threshold 2"), {"--threshold"});
  expectBad(runHaif("diff '" + path("ref") + "'", dir_ / "log_bad6"), {"two runs"});
  // Nothing was written for any of them.
  for (const char* out : {"d_bad1", "d_bad2", "d_bad3", "d_bad4", "d_bad5"})
    EXPECT_FALSE(fs::exists(dir_ / out / "report.json")) << out;
  // Without masks.json, --mask overlay cannot be honoured.
  paintedCopy("no_masks_a", "frame_00000.png", 0, 0, 1, 1);
  paintedCopy("no_masks_b", "frame_00000.png", 0, 0, 1, 1);
  expectBad(diff(path("no_masks_a"), path("no_masks_b"), "d_bad7", "--mask overlay"), {"masks.json"});
  const auto quiet = diff(path("no_masks_a"), path("no_masks_b"), "d_nomask");
  EXPECT_EQ(quiet.exitCode, 0) << quiet.err;
  EXPECT_NE(report("d_nomask")["notes"][0].get<std::string>().find("nothing masked"), std::string::npos);
}

}  // namespace
}  // namespace haif
