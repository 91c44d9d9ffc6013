// haif suite end to end: passing and failing jobs give exit 0 / 1 and the JUnit counts to match; bad
// input is exit 2 with one line naming the place and no output; the shards of a split run every job
// once and their merge judges as the unsharded run does; merge refuses missing and mixed shards;
// render jobs diff against references that --update-references writes; the shipped smoke suite passes.
#include "haif_process.h"
#include "render/png_io.h"
#include "support/xml_check.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace haif::test {
namespace {

namespace fs = std::filesystem;

// A 1 m box dropped from 2.5 m; `stressMax` bounds its drop in the scene's own stress block.
std::string dropScene(double stressMax, bool quick = true) {
  return R"({"settings": {"frames": 20},
  "bodies": [{"name": "box", "shape": {"type": "box"}, "position": [0, 2.5, 0]}],
  "generators": [{"type": "ground"}],
  "stress": {"steps": 20, "quick": )" +
         std::string(quick ? "true" : "false") + R"(, "checks": [{"check": "max_drop_m", "max": )" +
         std::to_string(stressMax) + "}]}}";
}

// Seven quick jobs of every kind; jobs 1, 3 and 6 fail, job 4 is skipped (out of the quick set).
const char* kMixedSuite = R"({"name": "mixed", "defaults": {"frames": 10, "threads": 1, "quick": true},
  "jobs": [
    {"kind": "run", "name": "drop_ok", "scene": "drop.json", "checks": [{"check": "max_drop_m", "max": 10}]},
    {"kind": "run", "name": "drop_strict", "scene": "drop.json", "checks": [{"check": "max_drop_m", "max": 0.0001}]},
    {"kind": "stress", "name": "stress_ok", "scene": "drop.json"},
    {"kind": "stress", "name": "stress_strict", "scene": "drop_strict.json"},
    {"kind": "stress", "name": "stress_skipped", "scene": "drop_slow.json"},
    {"kind": "run", "name": "drop_model", "scene": "drop.json", "mode": "model", "budget_ms": 4,
     "checks": [{"check": "iterations_mean", "min": 1}]},
    {"kind": "run", "name": "drop_summary", "scene": "drop.json", "checks": [{"check": "mean_drop_m", "max": 0}]}
  ]})";

class SuiteCommand : public ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    write("drop.json", dropScene(10));
    write("drop_strict.json", dropScene(0.001));
    write("drop_slow.json", dropScene(10, /*quick=*/false));
    write("mixed.json", kMixedSuite);
  }

  void write(const std::string& name, const std::string& text) {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // `haif suite DIR/SUITE --out DIR/OUT EXTRA`.
  ProcessResult suite(const std::string& file, const std::string& out, const std::string& extra = "") {
    return runHaif("suite '" + path(file) + "' --out '" + path(out) + "' " + extra, dir_ / ("log_" + out));
  }
  ProcessResult merge(const std::string& out, const std::vector<std::string>& shards) {
    std::string args = "suite merge '" + path(out) + "'";
    for (const std::string& s : shards) args += " '" + path(s) + "'";
    return runHaif(args, dir_ / ("log_" + out));
  }

  nlohmann::json report(const std::string& out) const {
    return nlohmann::json::parse(readWholeFile(dir_ / out / "report.json"));
  }
  XmlElement junit(const std::string& out) const {
    XmlElement root;
    std::string error;
    EXPECT_TRUE(XmlReader().parse(readWholeFile(dir_ / out / "junit.xml"), root, error)) << error;
    return root;
  }
  // Job name -> pass (null for skipped) of a report.
  std::map<std::string, nlohmann::json> verdicts(const std::string& out) const {
    std::map<std::string, nlohmann::json> v;
    const nlohmann::json r = report(out);  // held: a range-for over a temporary's member would dangle
    for (const auto& j : r.at("jobs")) v[j.at("name").get<std::string>()] = j.at("pass");
    return v;
  }
};

TEST_F(SuiteCommand, PassingAndFailingChecksGiveExitStatusAndJunitCounts) {
  write("two.json", R"({"jobs": [
    {"kind": "run", "name": "ok", "scene": "drop.json", "frames": 30, "checks": [{"check": "max_drop_m", "max": 10}]},
    {"kind": "run", "name": "strict", "scene": "drop.json", "frames": 30,
     "checks": [{"check": "max_drop_m", "max": 0.0001}]}]})");
  const ProcessResult r = suite("two.json", "out", "--threads 1");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("strict"), std::string::npos) << "one line per job: " << r.out;
  const nlohmann::json j = report("out");
  EXPECT_EQ(j.at("passed"), 1);
  EXPECT_EQ(j.at("failed"), 1);
  EXPECT_EQ(j.at("suite").at("jobs"), 2);
  EXPECT_EQ(j.at("shard").at("index"), 1);
  EXPECT_EQ(j.at("shard").at("count"), 1);
  const nlohmann::json& strict = j.at("jobs").at(1);
  EXPECT_EQ(strict.at("pass"), false);
  EXPECT_EQ(strict.at("setup").at("mode"), "fixed");
  EXPECT_EQ(strict.at("setup").at("frames"), 30);
  EXPECT_GT(strict.at("metrics").at("max_drop_m").get<double>(), 0.0001) << "summary.json's numbers";
  ASSERT_FALSE(strict.at("failures").empty());
  EXPECT_NE(strict.at("failures").at(0).get<std::string>().find("max_drop_m <= 0.0001"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "jobs" / "strict" / "summary.json"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "report.html"));

  const XmlElement x = junit("out");
  EXPECT_EQ(x.attr("tests"), "2");
  EXPECT_EQ(x.attr("failures"), "1");
  const auto cases = x.all("testcase");
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_TRUE(cases[0]->all("failure").empty());
  ASSERT_EQ(cases[1]->all("failure").size(), 1u);
  EXPECT_NE(cases[1]->all("failure")[0]->attr("message").find("max_drop_m <= 0.0001"), std::string::npos);

  write("one.json", R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": 30,
    "checks": [{"check": "max_drop_m", "max": 10}, {"check": "nan_free_steps_do_not_exist", "max": 1}]}]})");
  EXPECT_EQ(suite("one.json", "bad").exitCode, 2) << "an unknown check is bad input";
  write("one.json", R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": 30,
    "checks": [{"check": "max_drop_m", "max": 10}]}]})");
  const ProcessResult ok = suite("one.json", "out");  // replaces the earlier report
  EXPECT_EQ(ok.exitCode, 0) << ok.out << ok.err;
  EXPECT_EQ(junit("out").attr("failures"), "0");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "jobs" / "strict")) << "a report folder is replaced as a whole";
}

TEST_F(SuiteCommand, BadInputIsExit2WithOneLineNamingThePlace) {
  write("broken_scene.json", R"({"bodies": [{"shape": {"type": "box"}, "mass": -2}]})");
  struct Case {
    std::string suite, extra, expected;
  };
  const std::vector<Case> cases = {
      {R"({"jobs": [{"kind": "run"}]})", "", "jobs[0]: missing required key 'scene'"},
      {R"({"jobs": [{"kind": "bench", "scene": "drop.json"}]})", "", "jobs[0].kind: unknown job kind 'bench'"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}, {"kind": "run", "scene": "no_such.json"}]})", "",
       "jobs[1].scene: "},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}, {"kind": "run", "scene": "broken_scene.json"}]})", "",
       "broken_scene.json:1:"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": -1}]})", "", "jobs[0].frames: must be in [1, 10000000] (got -1)"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}]})", "--shard 3/2", "--shard"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}]})", "--shard 0/0", "--shard"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}]})", "--shard 1", "--shard"},
  };
  for (const Case& c : cases) {
    write("bad.json", c.suite);
    const ProcessResult r = suite("bad.json", "out", c.extra);
    EXPECT_EQ(r.exitCode, 2) << c.suite << " " << c.extra << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.suite << "\n  gave: " << r.err;
    if (c.extra.empty()) {
      EXPECT_NE(r.err.find("bad.json:1:"), std::string::npos) << "names the file: " << r.err;
    }
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "nothing is written for bad input: " << c.suite;
  }
  EXPECT_EQ(runHaif("suite", dir_ / "log_none").exitCode, 2);
  EXPECT_EQ(runHaif("suite merge '" + path("m") + "'", dir_ / "log_none").exitCode, 2);
}

TEST_F(SuiteCommand, ABadSceneLeavesTheEarlierReportWholeAndNoTemporaries) {
  write("good.json", R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": 5}]})");
  ASSERT_EQ(suite("good.json", "out").exitCode, 0);
  const std::string before = readWholeFile(dir_ / "out" / "report.json");
  write("broken_scene.json", R"({"bodies": [{"shape": {"type": "box"}, "position": [0, "up", 0]}]})");
  write("bad.json", R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": 5},
    {"kind": "run", "scene": "broken_scene.json", "frames": 5}]})");
  const ProcessResult r = suite("bad.json", "out");
  EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("jobs[1].scene"), std::string::npos) << r.err;
  EXPECT_EQ(readWholeFile(dir_ / "out" / "report.json"), before);
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "out"))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(SuiteCommand, ShardsPartitionTheJobsAndTheirMergeJudgesAsTheWholeRun) {
  const ProcessResult whole = suite("mixed.json", "whole");
  EXPECT_EQ(whole.exitCode, 1) << whole.out << whole.err;
  const auto expected = verdicts("whole");
  ASSERT_EQ(expected.size(), 7u);
  EXPECT_EQ(expected.at("drop_ok"), true);
  EXPECT_EQ(expected.at("drop_strict"), false);
  EXPECT_EQ(expected.at("stress_ok"), true);
  EXPECT_EQ(expected.at("stress_strict"), false);
  EXPECT_TRUE(expected.at("stress_skipped").is_null());
  EXPECT_EQ(expected.at("drop_model"), true);
  EXPECT_EQ(expected.at("drop_summary"), false);

  std::multiset<int> seen;
  for (int i = 1; i <= 3; ++i) {
    const std::string out = "shard" + std::to_string(i);
    const ProcessResult r = suite("mixed.json", out, "--shard " + std::to_string(i) + "/3");
    EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 1) << r.err;
    const nlohmann::json j = report(out);
    EXPECT_EQ(j.at("shard").at("index"), i);
    EXPECT_EQ(j.at("shard").at("count"), 3);
    EXPECT_EQ(j.at("suite").at("jobs"), 7) << "the report records the suite's total";
    for (const auto& job : j.at("jobs")) {
      const int k = job.at("index");
      EXPECT_EQ(k % 3, i - 1) << "job k runs in shard k mod N + 1";
      seen.insert(k);
    }
    EXPECT_EQ(junit(out).all("testcase").size(), j.at("jobs").size());
  }
  EXPECT_EQ(seen, (std::multiset<int>{0, 1, 2, 3, 4, 5, 6})) << "every job in exactly one shard";

  const ProcessResult m = merge("merged", {"shard2", "shard1", "shard3"});
  EXPECT_EQ(m.exitCode, 1) << "some jobs failed\n" << m.out << m.err;
  EXPECT_EQ(verdicts("merged"), expected);
  const nlohmann::json j = report("merged");
  EXPECT_TRUE(j.at("shard").is_null());
  EXPECT_EQ(j.at("merged_from").size(), 3u);
  for (size_t k = 0; k < j.at("jobs").size(); ++k) EXPECT_EQ(j.at("jobs").at(k).at("index"), k) << "in suite order";
  const XmlElement a = junit("whole"), b = junit("merged");
  for (const char* count : {"tests", "failures", "errors", "skipped"}) EXPECT_EQ(a.attr(count), b.attr(count)) << count;
  EXPECT_EQ(a.attr("failures"), "3");
  EXPECT_TRUE(fs::exists(dir_ / "merged" / "jobs" / "drop_ok" / "summary.json")) << "the jobs' files come along";

  // Missing, overlapping and mixed shards are refused, and nothing is written.
  const ProcessResult missing = merge("m1", {"shard1", "shard3"});
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("1 (drop_strict), 4 (stress_skipped)"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("missing shard 2/3"), std::string::npos) << missing.err;
  const ProcessResult twice = merge("m2", {"shard1", "shard2", "shard3", "shard1"});
  EXPECT_EQ(twice.exitCode, 2);
  EXPECT_NE(twice.err.find("overlap"), std::string::npos) << twice.err;
  write("other.json", R"({"name": "mixed", "jobs": [{"kind": "run", "scene": "drop.json", "frames": 3},
    {"kind": "run", "name": "b", "scene": "drop.json", "frames": 3}]})");
  ASSERT_LE(suite("other.json", "other", "--shard 2/3").exitCode, 1);
  const ProcessResult mixed = merge("m3", {"shard1", "other", "shard3"});
  EXPECT_EQ(mixed.exitCode, 2);
  EXPECT_NE(mixed.err.find("merge the shards of one suite file"), std::string::npos) << mixed.err;
  const ProcessResult notReport = merge("m4", {"shard1", "whole/jobs"});
  EXPECT_EQ(notReport.exitCode, 2);
  for (const char* out : {"m1", "m2", "m3", "m4"}) EXPECT_FALSE(fs::exists(dir_ / out)) << out;
}

TEST_F(SuiteCommand, RenderJobsDiffAgainstTheReferencesTheyWrote) {
#ifndef HAIF_HAVE_RENDER
  GTEST_SKIP() << "this build has no renderer";
#endif
  write("render.json", R"({"jobs": [{"kind": "render", "name": "drop_frames", "scene": "drop.json", "frames": 20,
    "frame_every": 10, "width": 64, "height": 48, "threads": 1, "reference": "refs/drop"}]})");
  const ProcessResult none = suite("render.json", "out");
  EXPECT_EQ(none.exitCode, 2) << "no reference yet: " << none.err;
  EXPECT_NE(none.err.find("jobs[0].reference"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("--update-references"), std::string::npos) << none.err;

  const ProcessResult made = suite("render.json", "out", "--update-references");
  ASSERT_EQ(made.exitCode, 0) << made.out << made.err;
  EXPECT_TRUE(fs::exists(dir_ / "refs" / "drop" / "frame_00000.png"));
  EXPECT_TRUE(fs::exists(dir_ / "refs" / "drop" / "frame_00001.png"));
  EXPECT_FALSE(fs::exists(dir_ / "refs" / "drop" / "frame_00002.png"));

  const ProcessResult same = suite("render.json", "out");
  EXPECT_EQ(same.exitCode, 0) << same.out << same.err;
  const nlohmann::json job = report("out").at("jobs").at(0);
  EXPECT_EQ(job.at("metrics").at("diff_frames"), 2);
  EXPECT_EQ(job.at("metrics").at("diff_frames_failed"), 0);

  // A block painted into one reference frame: that frame fails, by name.
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
  std::string error;
  const std::string frame = path("refs/drop/frame_00001.png");
  ASSERT_TRUE(render::readPng(frame, &w, &h, &rgba, &error)) << error;
  ASSERT_EQ(w, 64);
  for (int y = 10; y < 30; ++y)
    for (int x = 10; x < 30; ++x) {
      uint8_t* p = &rgba[4 * (size_t(y) * size_t(w) + size_t(x))];
      p[0] = 255, p[1] = 0, p[2] = 255;
    }
  ASSERT_TRUE(render::writePng(frame, w, h, rgba.data(), &error)) << error;
  const ProcessResult changed = suite("render.json", "out");
  EXPECT_EQ(changed.exitCode, 1) << changed.out << changed.err;
  const nlohmann::json failed = report("out").at("jobs").at(0);
  ASSERT_EQ(failed.at("failures").size(), 2u) << failed.dump(1);
  EXPECT_NE(failed.at("failures").at(0).get<std::string>().find("diff_frames_failed <= 0"), std::string::npos);
  EXPECT_NE(failed.at("failures").at(1).get<std::string>().find("frame_00001.png"), std::string::npos)
      << "the failing frame, by name";
  EXPECT_EQ(failed.at("metrics").at("diff_frames_failed"), 1);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "jobs" / "drop_frames" / "diff" / "frame_00001.png"));
}

TEST_F(SuiteCommand, TheShippedSmokeSuitePasses) {
#ifndef HAIF_HAVE_RENDER
  GTEST_SKIP() << "the smoke suite has a render job";
#endif
  const ProcessResult r = runHaif("suite '" + std::string(HAIF_SOURCE_DIR) + "/scenes/suites/smoke.json' --out '" +
                                      path("smoke") + "'",
                                  dir_ / "log_smoke");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  const nlohmann::json j = report("smoke");
  EXPECT_GE(j.at("jobs").size(), 4u);
  std::set<std::string> kinds;
  for (const auto& job : j.at("jobs")) kinds.insert(job.at("kind").get<std::string>());
  EXPECT_EQ(kinds, (std::set<std::string>{"run", "render", "stress"})) << "one job of every kind at least";
}

}  // namespace
}  // namespace haif::test
