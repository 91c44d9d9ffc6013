// haif suite SUITE.json: run a list of jobs (simulate and check, render and diff, stress scenes),
// or one shard of it, and write one report (report.json, report.html, junit.xml); haif suite merge
// joins the reports of the shards. Exit 0 every job passed, 1 some failed, 2 bad input.
#include "app/cli.h"
#include "app/commands.h"
#include "app/suite_painter.h"
#include "tools/atomic_file.h"
#include "tools/diff_report.h"
#include "tools/interrupts.h"
#include "tools/staged_output.h"
#include "tools/suite_html.h"
#include "tools/suite_junit.h"
#include "tools/suite_merge.h"
#include "tools/suite_report.h"
#include "tools/suite_runner.h"
#include "tools/suite_shard.h"
#include "tools/suite_spec.h"

#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace haif {

namespace {

namespace fs = std::filesystem;

constexpr int kBadInput = 2;
// A folder holding one of these is a suite report the commands may replace.
const std::vector<std::string> kReportMarkers = {"report.json", "junit.xml"};

int fail(const std::string& message, int status) {
  waitIfInterrupted();
  const bool prefixed = message.rfind("haif suite", 0) == 0;  // CommandLine's messages name the command
  std::fprintf(stderr, "%s%s\n", prefixed ? "" : "haif suite: ", message.c_str());
  return status;
}

// The three report files, written into the staged folder and moved into place together.
bool writeReport(StagedFolder& output, const SuiteReport& report, std::string& error) {
  return writeFileAtomic(output.path() + "/report.json", suiteReportJson(report), error) &&
         writeFileAtomic(output.path() + "/report.html", suiteReportHtml(report), error) &&
         writeFileAtomic(output.path() + "/junit.xml", suiteJunitXml(report), error) && output.commit(error);
}

void printVerdict(const SuiteReport& report, const std::string& outDir) {
  std::printf("suite %s: %s: %d passed, %d failed, %d skipped of %zu jobs; wrote %s/report.html, report.json, "
              "junit.xml\n",
              report.suiteName.c_str(), report.pass() ? "pass" : "FAIL", report.passed(), report.failed(),
              report.skipped(), report.jobs.size(), outDir.c_str());
}

// haif suite merge OUT_DIR SHARD_DIR...
int commandMerge(int argc, char** argv) {
  CommandLine cl("suite merge", {}, {});
  std::string error;
  if (!cl.parse(argc, argv, 3, error)) return fail(error, kBadInput);
  const std::vector<std::string>& args = cl.positional();
  if (args.size() < 2)
    return fail("merge: expected OUT_DIR and at least one shard's report folder: haif suite merge OUT_DIR "
                "SHARD_DIR... (see 'haif help suite')",
                kBadInput);
  const std::string outDir = args[0];
  std::vector<SuiteReport> parts;
  std::vector<std::string> labels;
  for (size_t i = 1; i < args.size(); ++i) {
    SuiteReport r;
    const std::string path = (fs::path(args[i]) / "report.json").string();
    if (!readSuiteReport(path, r, error)) return fail("merge: " + error, kBadInput);
    parts.push_back(std::move(r));
    labels.push_back(args[i]);
  }
  SuiteReport merged;
  if (!mergeSuiteReports(parts, labels, merged, error)) return fail("merge: " + error, kBadInput);
  merged.command = commandLineOf(argc, argv);

  StagedFolder output;
  if (!output.open(outDir, kReportMarkers, error)) return fail("merge: " + error, kBadInput);
  // The jobs' files come along, so the merged report's links work.
  for (size_t p = 0; p < parts.size(); ++p)
    for (const SuiteJobResult& job : parts[p].jobs) {
      const fs::path from = fs::path(labels[p]) / "jobs" / job.name;
      std::error_code ec;
      if (!fs::exists(from, ec)) continue;
      const fs::path to = fs::path(output.path()) / "jobs" / job.name;
      fs::create_directories(to.parent_path(), ec);
      if (!ec) fs::copy(from, to, fs::copy_options::recursive, ec);
      if (ec) return fail("merge: cannot copy " + from.string() + " to " + to.string() + ": " + ec.message(), kBadInput);
    }
  if (!writeReport(output, merged, error)) return fail("merge: " + error, kBadInput);
  printVerdict(merged, outDir);
  return merged.pass() ? 0 : 1;
}

}  // namespace

int commandSuite(int argc, char** argv) {
  if (argc >= 3 && std::strcmp(argv[2], "merge") == 0) return commandMerge(argc, argv);
  CommandLine cl("suite", {"--out", "--shard", "--threads"}, {"--update-references"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, kBadInput);
  if (cl.positional().size() != 1)
    return fail("expected one suite file: haif suite SUITE.json [options], or haif suite merge OUT_DIR SHARD_DIR... "
                "(see 'haif help suite')",
                kBadInput);
  int threads = int(tbb::info::default_concurrency());
  if (!cl.getInt("--threads", 1, 1024, threads, error)) return fail(error, kBadInput);
  SuiteShard shard;
  if (cl.has("--shard") && !parseSuiteShard(cl.get("--shard"), shard, error)) return fail(error, kBadInput);
  const bool update = cl.has("--update-references");

  // Every job is read and checked (scenes, checks, references) before the first one runs.
  SuiteLoadOptions options;
  options.referencesMayBeMissing = update;
  SuiteSpec suite;
  if (!loadSuiteFile(cl.positional()[0], options, suite, error)) return fail(error, kBadInput);
  std::unique_ptr<SuiteFramePainter> painter = makeSuiteFramePainter();
  for (const SuiteJob& job : suite.jobs)
    if (job.kind == SuiteJobKind::Render && !painter)
      return fail(suite.path + ": " + job.where + ": a render job, and this build has no renderer", kBadInput);
  const std::string outDir = cl.get("--out", "output/suite");
  StagedFolder output;
  if (!output.open(outDir, kReportMarkers, error)) return fail(error, kBadInput);

  SuiteReport report;
  report.suiteFile = suite.path;
  report.suiteName = suite.name;
  report.suiteHash = suite.hash;
  report.totalJobs = suite.jobs.size();
  for (const SuiteJob& job : suite.jobs) report.jobNames.push_back(job.name);
  report.shard = shard;
  report.started = utcNow();
  report.command = commandLineOf(argc, argv);
  report.updateReferences = update;

  SuiteRunContext ctx;
  ctx.threads = threads;
  ctx.reportDir = output.path();
  ctx.painter = painter.get();
  ctx.updateReferences = update;
  size_t selected = 0;
  for (const SuiteJob& job : suite.jobs) selected += shard.holds(job.index) ? 1 : 0;
  std::printf("suite %s: %zu of %zu jobs (shard %s), %d threads\n", suite.name.c_str(), selected, suite.jobs.size(),
              shard.text().c_str(), threads);
  std::fflush(stdout);
  const auto t0 = std::chrono::steady_clock::now();
  for (const SuiteJob& job : suite.jobs) {
    if (!shard.holds(job.index)) continue;
    report.jobs.push_back(runSuiteJob(job, ctx));
    std::printf("%s\n", suiteJobLine(report.jobs.back(), suite.jobs.size()).c_str());
    std::fflush(stdout);
  }
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!writeReport(output, report, error)) return fail(error, kBadInput);
  printVerdict(report, outDir);
  return report.pass() ? 0 : 1;
}

}  // namespace haif
