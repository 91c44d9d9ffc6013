// The haif command on bad input: non-zero exit, one error naming the file and place, no output files.
// And one good run whose summary.json / stats.csv follow docs/metrics.md. Needs the haif target built.
#include <nlohmann/json.hpp>

#include "haif_process.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

struct Result {
  int exitCode = -1;
  std::string err;  ///< stderr
};

// The state_hash a run wrote into DIR/summary.json ("" if none).
std::string summaryHash(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in).value("state_hash", std::string());
}

class RunCommand : public haif::test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    ASSERT_TRUE(fs::exists(HAIF_BINARY)) << "build the haif target first: " << HAIF_BINARY;
  }

  // Runs `haif ARGS`, capturing stderr.
  Result haif(const std::string& args) {
    const fs::path errFile = dir_ / "stderr.txt";
    const std::string cmd = std::string("'") + HAIF_BINARY + "' " + args + " >" + (dir_ / "stdout.txt").string() +
                            " 2>" + errFile.string();
    const int status = std::system(cmd.c_str());
    Result r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    std::ifstream in(errFile);
    std::stringstream ss;
    ss << in.rdbuf();
    r.err = ss.str();
    return r;
  }

  std::string writeScene(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  // The failure contract: non-zero exit, one error line holding `needles`, and no output files.
  void expectCleanFailure(const Result& r, const fs::path& out, std::initializer_list<std::string> needles) {
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_NE(r.exitCode, 128 + SIGSEGV) << "crashed: " << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
    EXPECT_FALSE(r.err.empty());
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one clear error, got: " << r.err;
    EXPECT_FALSE(fs::exists(out / "stats.csv")) << "partial output written";
    EXPECT_FALSE(fs::exists(out / "summary.json")) << "partial output written";
  }

  // "FILE:LINE:" of the first occurrence of `needle` in `text`.
  static std::string placeOf(const std::string& file, const std::string& text, const std::string& needle) {
    const size_t pos = text.find(needle);
    EXPECT_NE(pos, std::string::npos);
    const int line = 1 + int(std::count(text.begin(), text.begin() + std::min(pos, text.size()), '\n'));
    return file + ":" + std::to_string(line) + ":";
  }
};

const std::string kStacks = std::string(HAIF_SOURCE_DIR) + "/scenes/stacks_100.json";

TEST_F(RunCommand, MissingSceneFile) {
  const fs::path out = dir_ / "out";
  const std::string scene = (dir_ / "no_such_scene.json").string();
  const Result r = haif("run '" + scene + "' --no-render --frames 5 --out '" + out.string() + "'");
  expectCleanFailure(r, out, {scene});
}

TEST_F(RunCommand, JsonSyntaxError) {
  const fs::path out = dir_ / "out";
  const std::string text = "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"sphere\"},, \"position\": [0, 1, 0]}\n  ]\n}\n";
  const std::string scene = writeScene("syntax.json", text);
  const Result r = haif("run '" + scene + "' --no-render --frames 5 --out '" + out.string() + "'");
  expectCleanFailure(r, out, {scene + ":3:"});
}

TEST_F(RunCommand, NegativeMass) {
  const fs::path out = dir_ / "out";
  const std::string text =
      "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"box\", \"half_extents\": [0.5, 0.5, 0.5]},\n"
      "     \"position\": [0, 1, 0],\n     \"mass\": -2}\n  ]\n}\n";
  const std::string scene = writeScene("negative_mass.json", text);
  const Result r = haif("run '" + scene + "' --no-render --frames 5 --out '" + out.string() + "'");
  expectCleanFailure(r, out, {placeOf(scene, text, "-2"), "mass"});
}

TEST_F(RunCommand, UnknownShape) {
  const fs::path out = dir_ / "out";
  const std::string text = "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"dodecahedron\"}, \"position\": [0, 1, 0]}\n  ]\n}\n";
  const std::string scene = writeScene("unknown_shape.json", text);
  const Result r = haif("run '" + scene + "' --no-render --frames 5 --out '" + out.string() + "'");
  expectCleanFailure(r, out, {placeOf(scene, text, "dodecahedron"), "dodecahedron"});
}

TEST_F(RunCommand, UnwritableOutputFolder) {
  const Result r = haif("run '" + kStacks + "' --no-render --frames 5 --out /proc/haif_no");
  expectCleanFailure(r, "/proc/haif_no", {"/proc/haif_no"});
}

TEST_F(RunCommand, BadOptionValues) {
  const fs::path out = dir_ / "out";
  const std::string tail = " --no-render --out '" + out.string() + "'";
  expectCleanFailure(haif("run '" + kStacks + "' --frames abc" + tail), out, {"--frames", "abc"});
  expectCleanFailure(haif("run '" + kStacks + "' --frames -3" + tail), out, {"--frames"});
  expectCleanFailure(haif("run '" + kStacks + "' --threads 0 --frames 5" + tail), out, {"--threads"});
  expectCleanFailure(haif("run '" + kStacks + "' --budget-ms nan --mode adaptive --frames 5" + tail), out,
                     {"--budget-ms"});
  expectCleanFailure(haif("run '" + kStacks + "' --mode turbo --frames 5" + tail), out, {"--mode", "turbo"});
  expectCleanFailure(haif("run '" + kStacks + "' --frames" + tail), out, {"--frames"});
}

// Two boxes 0.1 m through each other, a third resting 5 mm into the ground: the run goes on (exit 0)
// and says once which bodies overlap and by how much; the resting box is not mentioned.
TEST_F(RunCommand, DeepOverlapAtTheStartIsAWarning) {
  const fs::path out = dir_ / "out";
  const std::string text =
      "{\n  \"bodies\": [\n"
      "    {\"name\": \"floor\", \"type\": \"static\", \"shape\": {\"type\": \"box\", \"half_extents\": [20, 1, 20]},"
      " \"position\": [0, -1, 0]},\n"
      "    {\"name\": \"left\", \"shape\": {\"type\": \"box\", \"half_extents\": [0.5, 0.5, 0.5]}, \"position\": [0, 3, 0]},\n"
      "    {\"name\": \"right\", \"shape\": {\"type\": \"box\", \"half_extents\": [0.5, 0.5, 0.5]}, \"position\": [0.9, 3, 0]},\n"
      "    {\"name\": \"resting\", \"shape\": {\"type\": \"box\", \"half_extents\": [0.5, 0.5, 0.5]}, \"position\": [5, 0.495, 0]}\n"
      "  ]\n}\n";
  const std::string scene = writeScene("overlap.json", text);
  const Result r = haif("run '" + scene + "' --no-render --frames 5 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_NE(r.err.find("warning: " + scene + ": bodies[1] \"left\" and bodies[2] \"right\" overlap by 0.100 m"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("resting"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(RunCommand, GoodRunWritesSummaryAndStats) {
  const fs::path out = dir_ / "out";
  const Result r = haif("run '" + kStacks + "' --no-render --frames 30 --threads 2 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  ASSERT_TRUE(fs::exists(out / "stats.csv"));
  EXPECT_FALSE(fs::exists(out / "frames" / "frame_00000.png")) << "--no-render wrote frames";

  std::ifstream sj(out / "summary.json");
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(sj));
  for (const char* key : {"scene", "bodies", "steps", "threads", "mode", "budget_ms", "ms_per_step_median",
                          "ms_per_step_p95", "ms_per_step_p99", "deadline_miss_rate", "iterations_mean",
                          "iterations_min", "iterations_max", "max_penetration_m", "rms_penetration_m",
                          "mean_drop_m", "max_drop_m", "rms_velocity_last_s", "solve_error_mean",
                          "nan_detected", "state_hash"})
    EXPECT_TRUE(j.contains(key)) << "summary.json lacks '" << key << "'";
  EXPECT_EQ(j.value("scene", ""), "stacks_100");
  EXPECT_EQ(j.value("bodies", 0), 101);  // 100 boxes + ground
  EXPECT_EQ(j.value("steps", 0), 30);
  EXPECT_EQ(j.value("threads", 0), 2);
  EXPECT_EQ(j.value("mode", ""), "fixed");
  EXPECT_EQ(j.value("nan_detected", true), false);
  EXPECT_LE(j.value("ms_per_step_median", 1e9), j.value("ms_per_step_p95", -1.0));
  EXPECT_LE(j.value("ms_per_step_p95", 1e9), j.value("ms_per_step_p99", -1.0));
  EXPECT_LE(j.value("iterations_min", 1e9), j.value("iterations_mean", -1.0));
  EXPECT_LE(j.value("iterations_mean", 1e9), j.value("iterations_max", -1.0));
  EXPECT_LE(j.value("rms_penetration_m", 1e9), j.value("max_penetration_m", -1.0));
  EXPECT_LE(j.value("mean_drop_m", 1e9), j.value("max_drop_m", -1.0));
  // Half a second of a standing stack: boxes drop by at most their gaps (<= 9 cm) plus slop.
  EXPECT_LT(j.value("max_drop_m", 1e9), 0.12);
  const std::string hash = j.value("state_hash", "");
  EXPECT_EQ(hash.size(), 16u) << hash;

  std::ifstream sc(out / "stats.csv");
  std::string header, line;
  ASSERT_TRUE(std::getline(sc, header));
  EXPECT_NE(header.find("iterations_chosen"), std::string::npos);
  const auto columns = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(sc, line)) {
    if (line.empty()) continue;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << "row " << rows;
    EXPECT_EQ(line.rfind(std::to_string(rows) + ",", 0), 0u) << "row " << rows << " starts with its step";
    ++rows;
  }
  EXPECT_EQ(rows, 30);
  // No temporary files left in the output folder.
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(RunCommand, SameRunTwiceGivesSameHash) {
  const fs::path a = dir_ / "a", b = dir_ / "b";
  ASSERT_EQ(haif("run '" + kStacks + "' --no-render --frames 20 --threads 1 --out '" + a.string() + "'").exitCode, 0);
  ASSERT_EQ(haif("run '" + kStacks + "' --no-render --frames 20 --threads 4 --out '" + b.string() + "'").exitCode, 0);
  EXPECT_EQ(summaryHash(a), summaryHash(b)) << "fixed mode must not depend on the thread count";
}

// Rendering only reads the world: the run's state_hash is the same with and without frames.
TEST_F(RunCommand, RenderingDoesNotChangeTheSimulation) {
  const fs::path a = dir_ / "headless", b = dir_ / "rendered";
  ASSERT_EQ(haif("run '" + kStacks + "' --no-render --frames 12 --threads 1 --out '" + a.string() + "'").exitCode, 0);
  const Result r = haif("run '" + kStacks + "' --frames 12 --frame-every 4 --width 160 --height 120 --threads 1 --out '" +
                        b.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(fs::exists(b / "frames" / "frame_00000.png")) << "the rendered run wrote no frames";
  EXPECT_FALSE(summaryHash(a).empty());
  EXPECT_EQ(summaryHash(a), summaryHash(b));
}

// --render-phases: summary.json gets the median of each render phase, in render order; without the
// flag there is no such key, and asking for phases of a headless run is an error.
TEST_F(RunCommand, RenderPhasesAreReportedOnlyWhenAsked) {
  const fs::path timed = dir_ / "timed", plain = dir_ / "plain";
  const std::string common = " --frames 6 --width 160 --height 120 --threads 1 --error-every 0 --out '";
  Result r = haif("run '" + kStacks + "'" + common + timed.string() + "' --render-phases");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(haif("run '" + kStacks + "'" + common + plain.string() + "'").exitCode, 0);

  std::ifstream a(timed / "summary.json"), b(plain / "summary.json");
  const nlohmann::ordered_json ja = nlohmann::ordered_json::parse(a), jb = nlohmann::ordered_json::parse(b);
  EXPECT_FALSE(jb.contains("render_phase_ms_median"));
  ASSERT_TRUE(ja.contains("render_phase_ms_median"));
  const nlohmann::ordered_json& phases = ja["render_phase_ms_median"];
  const std::vector<std::string> expected = {"prepare", "shadow", "scene", "sky", "resolve", "readback", "flip",
                                             "overlay"};
  std::vector<std::string> keys;
  double sum = 0;
  for (auto it = phases.begin(); it != phases.end(); ++it) {
    keys.push_back(it.key());
    ASSERT_TRUE(it.value().is_number()) << it.key();
    EXPECT_GE(it.value().get<double>(), 0.0) << it.key();
    sum += it.value().get<double>();
  }
  EXPECT_EQ(keys, expected) << "phases missing or out of render order";
  EXPECT_GT(phases.value("scene", 0.0), 0.0) << "the main pass took no time";
  EXPECT_GT(sum, 0.0) << "no phase took any time";
  EXPECT_EQ(summaryHash(timed), summaryHash(plain)) << "timing the phases changed the simulation";

  r = haif("run '" + kStacks + "' --no-render --render-phases --frames 2 --out '" + (dir_ / "headless").string() + "'");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--render-phases needs rendering"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "headless" / "summary.json"));
}

TEST_F(RunCommand, BudgetedRunSaysWhetherTheFloorFitsTheBudget) {
  // At a 1 us budget even I_min cannot fit: every step runs at the floor, and summary.json says the
  // budget is infeasible, with the floor's measured cost. At 1 s it fits.
  auto summary = [&](const std::string& budget) {
    const fs::path out = dir_ / ("b" + budget);
    const Result r = haif("run '" + kStacks + "' --no-render --frames 10 --mode adaptive --budget-ms " + budget +
                          " --out '" + out.string() + "'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::ifstream sj(out / "summary.json");
    return nlohmann::json::parse(sj);
  };
  const nlohmann::json tight = summary("0.001");
  EXPECT_EQ(tight.value("budget_feasible", true), false);
  EXPECT_EQ(tight.value("i_min", 0), 4);
  EXPECT_EQ(tight.value("floor_steps", 0), 10);
  EXPECT_EQ(tight.value("floor_misses", 0), 10);
  EXPECT_GT(tight.value("floor_ms_median", 0.0), 0.001);
  const nlohmann::json loose = summary("1000");
  EXPECT_EQ(loose.value("budget_feasible", false), true);
}

}  // namespace
