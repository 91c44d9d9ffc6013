// Suite files (tools/suite_spec.h) and shards (tools/suite_shard.h): defaults reach the jobs that
// take them, every mistake is one line naming the file, line, place and problem, and the shards of
// a split hold every job exactly once.
#include "support/scratch_folder.h"
#include "tools/suite_shard.h"
#include "tools/suite_spec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace haif {
namespace {

namespace fs = std::filesystem;

class SuiteSpecTest : public test::ScratchFolderTest {
 protected:
  void SetUp() override {
    ScratchFolderTest::SetUp();
    std::ofstream(dir_ / "drop.json") << R"({"name": "drop", "settings": {"frames": 40},
      "bodies": [{"name": "box", "shape": {"type": "box"}, "position": [0, 2.5, 0]}],
      "generators": [{"type": "ground"}],
      "stress": {"steps": 30, "checks": [{"check": "max_drop_m", "max": 10}]}})";
    std::ofstream(dir_ / "plain.json") << R"({"generators": [{"type": "ground"}, {"type": "stack", "count": 2}]})";
  }

  // Parses `text` as DIR/suite.json; the error when it fails ("" when it parses).
  std::string parse(const std::string& text, SuiteSpec* out = nullptr, bool referencesMayBeMissing = false) {
    SuiteSpec spec;
    SuiteLoadOptions options;
    options.referencesMayBeMissing = referencesMayBeMissing;
    std::string error;
    if (!parseSuiteText(text, (dir_ / "suite.json").string(), options, spec, error)) return error;
    if (out) *out = spec;
    return "";
  }
};

TEST_F(SuiteSpecTest, DefaultsReachTheJobsThatTakeThemAndNamesComeFromScenes) {
  SuiteSpec s;
  ASSERT_EQ(parse(R"({"defaults": {"frames": 12, "mode": "model", "budget_ms": 2, "quick": true, "threads": 3},
    "jobs": [{"kind": "run", "scene": "drop.json"},
             {"kind": "run", "name": "drop_fixed", "scene": "drop.json", "mode": "fixed", "frames": 5},
             {"kind": "stress", "name": "drop_stress", "scene": "drop.json"}]})",
                  &s),
            "");
  ASSERT_EQ(s.jobs.size(), 3u);
  EXPECT_EQ(s.name, "suite");
  EXPECT_EQ(s.hash.size(), 16u);
  EXPECT_EQ(s.jobs[0].name, "drop");
  EXPECT_EQ(s.jobs[0].frames, 12);
  EXPECT_EQ(s.jobs[0].mode, "model");
  EXPECT_EQ(s.jobs[0].budgetMs, 2.0);
  EXPECT_EQ(s.jobs[0].threads, 3);
  EXPECT_EQ(s.jobs[0].scenePath, (dir_ / "drop.json").string());
  EXPECT_EQ(s.jobs[1].frames, 5);
  EXPECT_EQ(s.jobs[1].mode, "fixed");
  EXPECT_EQ(s.jobs[2].kind, SuiteJobKind::Stress);
  EXPECT_TRUE(s.jobs[2].quick);
  EXPECT_EQ(s.jobs[2].threads, 3);
}

TEST_F(SuiteSpecTest, ChecksAreStressChecksOrSummaryNumbers) {
  SuiteSpec s;
  ASSERT_EQ(parse(R"({"jobs": [{"kind": "run", "scene": "drop.json", "error_every": 5, "checks": [
      {"check": "max_drop_m", "body": "box", "max": 3},
      {"check": "mean_drop_m", "min": 0.1, "max": 4},
      {"check": "solve_error_mean", "max": 1}]}]})",
                  &s),
            "");
  const auto& checks = s.jobs[0].checks;
  ASSERT_EQ(checks.size(), 3u);
  EXPECT_TRUE(checks[0].stress);
  EXPECT_EQ(checks[0].stressCheck.body, 0);
  EXPECT_FALSE(checks[1].stress);
  EXPECT_EQ(checks[1].key, "mean_drop_m");
  EXPECT_TRUE(checks[1].hasMin && checks[1].hasMax);
  EXPECT_EQ(checks[2].where, "jobs[0].checks[2]");
}

TEST_F(SuiteSpecTest, MistakesNameTheFileThePlaceAndTheProblem) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {R"({"jobs": [{"kind": "run"}]})", "jobs[0]: missing required key 'scene'"},
      {R"({"jobs": [{"kind": "simulate", "scene": "drop.json"}]})", "jobs[0].kind: unknown job kind 'simulate'"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "frames": 0}]})",
       "jobs[0].frames: must be in [1, 10000000] (got 0)"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}, {"kind": "run", "scene": "nope.json"}]})",
       "jobs[1].scene: "},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "checks": [{"check": "max_drop", "max": 1}]}]})",
       "jobs[0].checks[0].check: unknown check 'max_drop' (did you mean 'max_drop_m'?)"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "checks": [{"check": "mean_drop_m"}]}]})",
       "jobs[0].checks[0]: a summary.json check needs \"min\", \"max\" or both"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "checks": [{"check": "max_drop_m", "body": "lid", "max": 1}]}]})",
       "jobs[0].checks[0].body: no body is named 'lid'"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json", "checks": [{"check": "solve_error_mean", "max": 1}]}]})",
       "needs the solve error measured"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json"}, {"kind": "run", "scene": "drop.json"}]})",
       "two jobs are named 'drop' (jobs[0] and jobs[1])"},
      {R"({"jobs": [{"kind": "stress", "scene": "plain.json"}]})", "has no \"stress\" block"},
      {R"({"jobs": [{"kind": "stress", "scene": "drop.json", "frames": 3}]})", "jobs[0].frames: unknown key"},
      {R"({"defaults": {"mode": "adaptive"}, "jobs": [{"kind": "render", "scene": "drop.json", "reference": "r"}]})",
       "defaults.mode: a render job needs a reproducible mode"},
      {R"({"jobs": [{"kind": "render", "scene": "drop.json", "reference": "missing_refs"}]})",
       "jobs[0].reference: reference '"},
      {R"({"jobs": []})", "jobs: is empty"},
      {R"({"jobs": [{"kind": "run", "scene": "drop.json",}]})", "syntax error"},
  };
  for (const Case& c : cases) {
    const std::string error = parse(c.text);
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.text << "\n  gave: " << error;
    EXPECT_EQ(error.rfind((dir_ / "suite.json").string() + ":1:", 0), 0u) << "names the file and line: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  }
  // The default that is wrong for a job says for which job.
  EXPECT_NE(parse(R"({"defaults": {"mode": "adaptive"}, "jobs": [{"kind": "render", "scene": "drop.json",
    "reference": "r"}]})")
                .find("(the default for jobs[0])"),
            std::string::npos);
}

TEST_F(SuiteSpecTest, ReferencesMayBeMissingWhenTheyAreToBeWritten) {
  const std::string text = R"({"jobs": [{"kind": "render", "scene": "drop.json", "reference": "refs/drop",
    "width": 64, "height": 48, "diff": {"max_diff_ratio": 0.01, "masks": [[0, 0, 8, 8]]}}]})";
  EXPECT_NE(parse(text), "");
  SuiteSpec s;
  ASSERT_EQ(parse(text, &s, /*referencesMayBeMissing=*/true), "");
  EXPECT_EQ(s.jobs[0].referencePath, (dir_ / "refs/drop").string());
  EXPECT_EQ(s.jobs[0].width, 64);
  EXPECT_EQ(s.jobs[0].diff.maxDiffRatio, 0.01);
  ASSERT_EQ(s.jobs[0].diff.masks.size(), 1u);
  EXPECT_EQ(s.jobs[0].diff.masks[0].x1, 8);
  const std::string error = parse(R"({"jobs": [{"kind": "render", "name": "a", "scene": "drop.json", "reference": "r"},
    {"kind": "render", "name": "b", "scene": "drop.json", "reference": "./r"}]})",
                                  nullptr, /*referencesMayBeMissing=*/true);
  EXPECT_NE(error.find("jobs[1].reference: is also the reference of jobs[0]"), std::string::npos) << error;
}

TEST(SuiteShard, ParsesIOfNFromOne) {
  SuiteShard s;
  std::string error;
  ASSERT_TRUE(parseSuiteShard("2/3", s, error)) << error;
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_EQ(s.text(), "2/3");
  for (const char* bad : {"3/2", "0/0", "0/3", "1/0", "2", "a/b", "-1/3", "1/3/4", " 1/3", "1/", "/3", ""}) {
    EXPECT_FALSE(parseSuiteShard(bad, s, error)) << bad;
    EXPECT_NE(error.find("--shard"), std::string::npos) << error;
  }
  EXPECT_FALSE(parseSuiteShard("3/2", s, error));
  EXPECT_NE(error.find("there is no shard 3 of 2"), std::string::npos) << error;
}

TEST(SuiteShard, TheShardsOfASplitHoldEveryJobOnce) {
  for (int n = 1; n <= 7; ++n)
    for (size_t job = 0; job < 40; ++job) {
      int holders = 0;
      for (int i = 1; i <= n; ++i) holders += SuiteShard{i, n}.holds(job) ? 1 : 0;
      EXPECT_EQ(holders, 1) << "job " << job << " of a split in " << n;
    }
  EXPECT_TRUE((SuiteShard{1, 3}.holds(0)));
  EXPECT_TRUE((SuiteShard{1, 3}.holds(3)));
  EXPECT_TRUE((SuiteShard{3, 3}.holds(2)));
}

}  // namespace
}  // namespace haif
