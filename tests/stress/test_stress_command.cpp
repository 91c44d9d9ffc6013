// `haif stress`: the quick set of the shipped suite passes and stress.json has the documented
// structure; bad input (an unknown check, no stress block) is one clear error with exit 2 and no
// stress.json; a scene that fails its checks gives exit 1.
#include "../app/haif_process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace haif::test {
namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// A box dropped from 2 m with the given checks.
// `haif stress --out DIR/out FILE`.
ProcessResult runStress(const fs::path& dir, const fs::path& file) {
  return runHaif("stress --out '" + (dir / "out").string() + "' '" + file.string() + "'", dir);
}

std::string droppedBoxScene(const std::string& checks) {
  return R"({"name": "drop", "bodies": [{"name": "box", "shape": {"type": "box"}, "position": [0, 2.5, 0]}],
  "generators": [{"type": "ground"}],
  "stress": {"steps": 60, "quick_steps": 30, "checks": [)" + checks + "]}}";
}

TEST(StressCommand, QuickSuitePassesAndWritesStressJson) {
  const fs::path dir = scratchDir("haif_stress_quick");
  const ProcessResult r = runHaif("stress --quick --out '" + (dir / "out").string() + "' '" +
                                      std::string(HAIF_SOURCE_DIR) + "/scenes/stress'",
                                  dir);
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  const fs::path json = dir / "out" / "stress.json";
  ASSERT_TRUE(fs::exists(json)) << r.err;
  const nlohmann::json j = nlohmann::json::parse(readWholeFile(json));
  EXPECT_EQ(j.at("quick"), true);
  ASSERT_TRUE(j.at("scenes").is_array());
  EXPECT_GE(j.at("scenes").size(), 13u);
  int skipped = 0;
  for (const auto& s : j.at("scenes")) {
    const std::string name = s.at("name");
    ASSERT_TRUE(s.contains("pass") && s.contains("metrics") && s.contains("criterion")) << name;
    if (s.at("skipped") == true) {
      ++skipped;
      EXPECT_TRUE(s.at("pass").is_null()) << name;
      EXPECT_FALSE(s.value("note", "").empty()) << name << ": a scene left out of --quick must say why";
      continue;
    }
    EXPECT_EQ(s.at("pass"), true) << name;
    EXPECT_EQ(s.at("metrics").at("nan_detected"), false) << name;
    ASSERT_GE(s.at("criterion").size(), 2u) << name << ": no_nan plus at least one check";
    for (const auto& c : s.at("criterion")) {
      EXPECT_TRUE(c.at("pass").is_boolean()) << name;
      EXPECT_FALSE(c.at("criterion").get<std::string>().empty()) << name;
    }
    // One printed line per scene, with its verdict.
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  }
  EXPECT_GE(skipped, 1) << "the 10,000-body pile is left out of --quick";
  EXPECT_GE(int(j.at("scenes").size()) - skipped, 9) << "most scenes run in the quick set";
  EXPECT_EQ(j.at("failed"), 0);
}

TEST(StressCommand, UnknownCheckIsBadInput) {
  const fs::path dir = scratchDir("haif_stress_badcheck");
  writeText(dir / "bad.json", droppedBoxScene(R"({"check": "max_drop", "max": 1})"));
  const ProcessResult r = runStress(dir, dir / "bad.json");
  EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
  // One line naming the file, the place and the problem, with the likely intended name.
  EXPECT_NE(r.err.find("bad.json:3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("stress.checks[0].check: unknown check 'max_drop'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("max_drop_m"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "stress.json"));
}

TEST(StressCommand, BadCheckArgumentsAreBadInput) {
  const fs::path dir = scratchDir("haif_stress_badargs");
  const std::pair<std::string, std::string> cases[] = {
      {R"({"check": "max_drop_m"})", "missing required key 'max'"},
      {R"({"check": "max_drop_m", "max": -1})", "must be >= 0"},
      {R"({"check": "no_tunnel", "body": "bx", "normal": [1, 0, 0]})", "no body is named 'bx'"},
      {R"({"check": "peak_speed", "max": 1, "limit": 2})", "unknown key"},
  };
  for (const auto& [check, message] : cases) {
    writeText(dir / "bad.json", droppedBoxScene(check));
    const ProcessResult r = runStress(dir, dir / "bad.json");
    EXPECT_EQ(r.exitCode, 2) << check << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << check << "\n" << r.err;
  }
  // A scene without a stress block cannot be judged.
  writeText(dir / "plain.json", R"({"generators": [{"type": "ground"}]})");
  const ProcessResult r = runStress(dir, dir / "plain.json");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("no \"stress\" block"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "stress.json"));
}

TEST(StressCommand, FailingCheckGivesExitOneAndSaysWhich) {
  // The box falls 2 m: a 1 cm drop limit must fail, and the report must carry the measured drop.
  const fs::path dir = scratchDir("haif_stress_fail");
  writeText(dir / "drop.json",
            droppedBoxScene(R"({"check": "max_drop_m", "max": 0.01}, {"check": "peak_speed", "max": 100})"));
  const ProcessResult r = runStress(dir, dir / "drop.json");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(readWholeFile(dir / "out" / "stress.json"));
  const auto& s = j.at("scenes").at(0);
  EXPECT_EQ(s.at("pass"), false);
  const auto& drop = s.at("criterion").at(1);
  EXPECT_EQ(drop.at("check"), "max_drop_m");
  EXPECT_EQ(drop.at("pass"), false);
  EXPECT_NEAR(drop.at("value").get<double>(), 2.0, 0.05);
  EXPECT_EQ(s.at("criterion").at(2).at("pass"), true);  // peak speed about 6.3 m/s
  EXPECT_EQ(j.at("failed"), 1);
}

TEST(StressCommand, JointErrorAndSpeedBoundChecksMeasureTheRun) {
  // A 1 t block on a 1 kg link swinging from the horizontal: the joints hold to a few micrometres
  // (a 1 um limit fails, 1 cm passes); nothing is fast enough for the speed bound to act.
  const fs::path dir = scratchDir("haif_stress_joint_checks");
  writeText(dir / "swing.json", R"({"name": "swing", "bodies": [
    {"name": "link", "shape": {"type": "sphere", "radius": 0.2}, "position": [0.5, 5, 0], "mass": 1},
    {"name": "block", "shape": {"type": "box"}, "position": [1.5, 5, 0], "mass": 1000}],
  "joints": [{"type": "ball", "body_b": "link", "anchor": [0, 5, 0]},
             {"type": "ball", "body_a": "link", "body_b": "block", "anchor": [1, 5, 0]}],
  "stress": {"steps": 60, "checks": [{"check": "max_joint_error_m", "max": 1e-6},
                                     {"check": "max_joint_error_m", "max": 0.01},
                                     {"check": "speed_limited", "max": 0}]}})");
  const ProcessResult r = runStress(dir, dir / "swing.json");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(readWholeFile(dir / "out" / "stress.json"));
  const auto& c = j.at("scenes").at(0).at("criterion");
  EXPECT_EQ(c.at(1).at("pass"), false);
  EXPECT_GT(c.at(1).at("value").get<double>(), 1e-6);
  EXPECT_EQ(c.at(2).at("pass"), true);
  EXPECT_EQ(c.at(3).at("check"), "speed_limited");
  EXPECT_EQ(c.at(3).at("value").get<double>(), 0.0);
  EXPECT_EQ(c.at(3).at("pass"), true);
}

}  // namespace
}  // namespace haif::test
