// The suite's reports (tools/suite_report.h, suite_junit.h, suite_html.h, suite_merge.h): report.json
// reads back as written, junit.xml is well formed whatever the messages hold and counts what the
// report counts, and merging joins the shards of one suite only when they hold every job once.
#include "support/scratch_folder.h"
#include "support/xml_check.h"
#include "tools/markup_text.h"
#include "tools/suite_html.h"
#include "tools/suite_junit.h"
#include "tools/suite_merge.h"
#include "tools/suite_report.h"

#include <gtest/gtest.h>

#include <fstream>

namespace haif {
namespace {

// A report of `shard` of a suite of `total` jobs named job0, job1, ...; job k fails when k % 3 == 1.
SuiteReport shardReport(int index, int count, size_t total = 7, const std::string& hash = "00112233aabbccdd") {
  SuiteReport r;
  r.suiteFile = "suites/x.json";
  r.suiteName = "x";
  r.suiteHash = hash;
  r.totalJobs = total;
  for (size_t k = 0; k < total; ++k) r.jobNames.push_back("job" + std::to_string(k));
  r.shard = SuiteShard{index, count};
  r.started = "2024-05-01T12:00:0" + std::to_string(index) + "Z";
  r.command = "haif suite suites/x.json --shard " + r.shard.text();
  r.wallSeconds = 1.5 * index;
  for (size_t k = 0; k < total; ++k) {
    if (!r.shard.holds(k)) continue;
    SuiteJobResult j;
    j.index = k;
    j.name = r.jobNames[k];
    j.kind = "run";
    j.scene = "../scenes/a.json";
    j.setup = {{"mode", "fixed"}, {"iterations", 10}, {"frames", 30}, {"threads", 2}};
    j.checks.push_back({"no_nan", "no NaN or inf in the state", 0.0, NAN, true});
    const bool fails = k % 3 == 1;
    j.checks.push_back({"max_drop_m", "max_drop_m <= 0.05", fails ? 0.5 : 0.01, 0.05, !fails});
    if (fails) j.failures.push_back("max_drop_m <= 0.05: got 0.5");
    j.pass = !fails;
    j.metrics = {{"max_drop_m", fails ? 0.5 : 0.01}, {"state_hash", "0123456789abcdef"}};
    j.artifacts = {"jobs/" + j.name + "/summary.json"};
    j.wallSeconds = 0.25;
    r.jobs.push_back(j);
  }
  return r;
}

class SuiteReportTest : public test::ScratchFolderTest {
 protected:
  SuiteReport roundTrip(const SuiteReport& r) {
    const std::string path = (dir_ / "report.json").string();
    std::ofstream(path) << suiteReportJson(r);
    SuiteReport back;
    std::string error;
    EXPECT_TRUE(readSuiteReport(path, back, error)) << error;
    return back;
  }
};

TEST_F(SuiteReportTest, ReportJsonReadsBackAsWritten) {
  SuiteReport r = shardReport(2, 3);
  r.jobs[0].error = true;
  r.jobs[0].pass = false;
  r.jobs[0].failures = {"renderer: no GL"};
  const SuiteReport back = roundTrip(r);
  EXPECT_EQ(suiteReportJson(back), suiteReportJson(r));
  EXPECT_EQ(back.shard.text(), "2/3");
  EXPECT_EQ(back.totalJobs, 7u);
  ASSERT_EQ(back.jobs.size(), r.jobs.size());
  EXPECT_TRUE(std::isnan(back.jobs[0].checks[0].limit)) << "no limit reads back as none";
  EXPECT_EQ(back.errors(), 1);
}

TEST_F(SuiteReportTest, ReadingRefusesWhatIsNotASuiteReport) {
  const std::string path = (dir_ / "report.json").string();
  std::string error;
  SuiteReport r;
  std::ofstream(path) << R"({"format": "something else"})";
  EXPECT_FALSE(readSuiteReport(path, r, error));
  EXPECT_NE(error.find("not a haif suite report"), std::string::npos) << error;
  std::ofstream(path) << "{";
  EXPECT_FALSE(readSuiteReport(path, r, error));
  EXPECT_NE(error.find(path), std::string::npos) << error;
  std::string text = suiteReportJson(shardReport(1, 1));
  // The first failed job's verdict (the report's own "pass" comes before the jobs).
  text.replace(text.find("\"pass\": false", text.find("\"jobs\": [")), 13, "\"pass\": 3");
  std::ofstream(path) << text;
  EXPECT_FALSE(readSuiteReport(path, r, error));
  EXPECT_NE(error.find("jobs[1].pass: must be true or false"), std::string::npos) << error;
}

TEST(SuiteJunit, IsWellFormedAndCountsTestsAndFailures) {
  SuiteReport r = shardReport(1, 1);
  // Messages and names with every character XML reserves, a control character and a broken UTF-8 byte.
  r.suiteName = "a&b <c> \"d\" 'e'";
  r.jobs[1].failures = {"max_drop_m <= 0.05 & \"more\" <tag>\x01 \xff end", "second line"};
  r.jobs[2].skipped = true;
  r.jobs[2].notes = {"not in the quick set"};
  r.jobs[3].error = true;
  r.jobs[3].pass = false;
  r.jobs[3].failures = {"renderer: cannot create a GL context"};
  const std::string xml = suiteJunitXml(r);
  test::XmlElement root;
  std::string error;
  ASSERT_TRUE(test::XmlReader().parse(xml, root, error)) << error << "\n" << xml;
  EXPECT_EQ(root.name, "testsuite");
  EXPECT_EQ(root.attr("name"), r.suiteName) << "reads back as written";
  const auto cases = root.all("testcase");
  ASSERT_EQ(cases.size(), r.jobs.size());
  EXPECT_EQ(root.attr("tests"), std::to_string(r.jobs.size()));
  int failures = 0, errors = 0, skipped = 0;
  for (const test::XmlElement* c : cases) {
    failures += int(c->all("failure").size());
    errors += int(c->all("error").size());
    skipped += int(c->all("skipped").size());
    EXPECT_FALSE(c->attr("time").empty());
  }
  EXPECT_EQ(failures, r.failed() - r.errors());
  EXPECT_EQ(root.attr("failures"), std::to_string(failures));
  EXPECT_EQ(errors, 1);
  EXPECT_EQ(root.attr("errors"), "1");
  EXPECT_EQ(skipped, 1);
  EXPECT_EQ(root.attr("skipped"), "1");
  const test::XmlElement* failed = cases[1]->all("failure").at(0);
  EXPECT_EQ(failed->attr("message"), "max_drop_m <= 0.05 & \"more\" <tag>? ? end");
  EXPECT_NE(failed->text.find("second line"), std::string::npos);
  EXPECT_EQ(cases[1]->attr("name"), "job1");
}

TEST(SuiteHtml, IsOnePageWithEveryJobAndEscapedText) {
  SuiteReport r = shardReport(1, 1);
  r.jobs[1].failures = {"<script>alert(1)</script>"};
  const std::string html = suiteReportHtml(r);
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);
  for (const SuiteJobResult& j : r.jobs) EXPECT_NE(html.find("id=\"job-" + std::to_string(j.index) + "\""), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos) << "self-contained";
  EXPECT_EQ(html.find("https://"), std::string::npos) << "self-contained";
  EXPECT_EQ(suiteSetupText(r.jobs[0]), "fixed, 10 iterations, 30 frames, 2 threads");
}

TEST(SuiteMerge, JoinsTheShardsIntoTheUnshardedReport) {
  const SuiteReport whole = shardReport(1, 1);
  SuiteReport merged;
  std::string error;
  ASSERT_TRUE(mergeSuiteReports({shardReport(3, 3), shardReport(1, 3), shardReport(2, 3)}, {"c", "a", "b"}, merged,
                                error))
      << error;
  ASSERT_EQ(merged.jobs.size(), whole.jobs.size());
  for (size_t k = 0; k < whole.jobs.size(); ++k) {
    EXPECT_EQ(merged.jobs[k].index, k);
    EXPECT_EQ(merged.jobs[k].pass, whole.jobs[k].pass) << k;
  }
  EXPECT_EQ(merged.failed(), whole.failed());
  EXPECT_TRUE(merged.merged());
  EXPECT_EQ(merged.started, "2024-05-01T12:00:01Z") << "the earliest shard's start";
  EXPECT_EQ(merged.wallSeconds, 4.5) << "shards run side by side: the longest";
  ASSERT_EQ(merged.mergedFrom.size(), 3u);
  EXPECT_EQ(merged.mergedFrom[0], "c (shard 3/3)");
}

TEST(SuiteMerge, RefusesMissingOverlappingAndMixedShards) {
  SuiteReport merged;
  std::string error;
  EXPECT_FALSE(mergeSuiteReports({shardReport(1, 3), shardReport(3, 3)}, {"a", "c"}, merged, error));
  EXPECT_NE(error.find("2 of 7 jobs are in none of the reports: 1 (job1), 4 (job4)"), std::string::npos) << error;
  EXPECT_NE(error.find("missing shard 2/3"), std::string::npos) << error;

  EXPECT_FALSE(mergeSuiteReports({shardReport(1, 3), shardReport(2, 3), shardReport(1, 3)}, {"a", "b", "a2"}, merged,
                                 error));
  EXPECT_NE(error.find("job 0 (job0) is in both a (shard 1/3) and a2 (shard 1/3)"), std::string::npos) << error;

  EXPECT_FALSE(mergeSuiteReports({shardReport(1, 2), shardReport(2, 2, 7, "ffffffffffffffff")}, {"a", "b"}, merged,
                                 error));
  EXPECT_NE(error.find("merge the shards of one suite file"), std::string::npos) << error;

  // Splits that differ but cover every job once are one suite's jobs all the same.
  SuiteReport part = shardReport(1, 1);
  part.jobs.resize(2);  // jobs 0 and 1 ...
  SuiteReport rest = shardReport(1, 1);
  rest.jobs.erase(rest.jobs.begin(), rest.jobs.begin() + 2);  // ... and 2 to 6
  EXPECT_TRUE(mergeSuiteReports({part, rest}, {"a", "b"}, merged, error)) << error;
}

TEST(MarkupText, EscapesWhatXmlReservesAndDropsWhatItForbids) {
  EXPECT_EQ(escapeMarkup("a&b<c>\"d\"'e'"), "a&amp;b&lt;c&gt;&quot;d&quot;&#39;e&#39;");
  EXPECT_EQ(escapeMarkup("line\nnext\ttab"), "line&#10;next&#9;tab");
  EXPECT_EQ(escapeMarkup("line\nnext\ttab\r<", true), "line\nnext\ttab&#13;&lt;");
  EXPECT_EQ(escapeMarkup(std::string("nul\0bell\a", 9)), "nul?bell?");
  EXPECT_EQ(escapeMarkup("\xc3\xa9t\xc3\xa9 \xe2\x9c\x93"), "\xc3\xa9t\xc3\xa9 \xe2\x9c\x93") << "UTF-8 kept";
  EXPECT_EQ(escapeMarkup("bad \xc3 \xff \xed\xa0\x80"), "bad ? ? ???") << "not UTF-8: replaced";
  EXPECT_EQ(urlPath("jobs/a b/frames#1"), "jobs/a%20b/frames%231");
}

}  // namespace
}  // namespace haif
