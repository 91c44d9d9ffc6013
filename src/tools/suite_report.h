// The report of `haif suite` (docs/suites.md): what each job was, what it measured and whether it
// passed, for the whole suite or one shard of it. report.json is written here and read back by
// `haif suite merge`; report.html and junit.xml are written from the same data (suite_html.h,
// suite_junit.h), so a merged report reads exactly like one run in one piece.
#pragma once

#include "tools/suite_shard.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace haif {

/// One judged check of a job. `value` and `limit` are NaN when there is none (not measured, no limit).
struct SuiteCheckOutcome {
  std::string check;      ///< "max_drop_m", "no_nan", ...
  std::string criterion;  ///< readable rule, e.g. "max_drop_m <= 0.05"
  double value = NAN;
  double limit = NAN;
  bool pass = false;
};

struct SuiteJobResult {
  size_t index = 0;             ///< in the suite, from 0
  std::string name, kind;       ///< kind: run | render | stress
  std::string scene;            ///< the scene file as the suite names it
  nlohmann::json setup = nlohmann::json::object();    ///< mode, iterations, budget_ms, threads, frames, ...
  bool pass = false;
  bool skipped = false;         ///< a stress job out of its scene's quick set: not run, neither pass nor fail
  bool error = false;           ///< the job could not be run or judged (a renderer or file failure)
  std::vector<std::string> failures;  ///< why it failed, one line each (empty when it passed)
  std::vector<std::string> notes;     ///< things the reader should know (a reference was rewritten, ...)
  std::vector<SuiteCheckOutcome> checks;
  nlohmann::json metrics = nlohmann::json::object();  ///< the numbers measured (summary.json for run jobs)
  std::vector<std::string> artifacts; ///< files and folders it wrote, relative to the report folder
  double wallSeconds = 0.0;
};

struct SuiteReport {
  std::string suiteFile, suiteName, suiteHash;
  size_t totalJobs = 0;                ///< jobs in the whole suite
  std::vector<std::string> jobNames;   ///< every job of the suite, by index (to name missing ones)
  SuiteShard shard;                    ///< the shard this report covers (1/1: the whole suite)
  std::vector<std::string> mergedFrom; ///< a merged report: the reports it joins ("DIR (shard I/N)")
  std::string started;                 ///< UTC, ISO 8601
  std::string command;                 ///< the command line that made it
  double wallSeconds = 0.0;
  bool updateReferences = false;       ///< render jobs rewrote their reference frames
  std::vector<SuiteJobResult> jobs;    ///< the jobs it covers, by index

  bool merged() const { return !mergedFrom.empty(); }
  int passed() const;
  int failed() const;   ///< failed jobs, errors included
  int errors() const;
  int skipped() const;
  /// Every job run passed (or was skipped): the command's exit status 0.
  bool pass() const { return failed() == 0; }
};

/// The current time as UTC ISO 8601 ("2024-05-01T12:00:00Z").
std::string utcNow();

/// report.json text.
std::string suiteReportJson(const SuiteReport& report);

/// Reads a report.json written by suiteReportJson. One error line naming the file and the place on failure.
bool readSuiteReport(const std::string& path, SuiteReport& out, std::string& error);

/// One line for the terminal: index, name, PASS/FAIL/SKIP/ERROR, the first failure or check, the time.
std::string suiteJobLine(const SuiteJobResult& job, size_t total);

/// A number as the reports print it: 4 significant digits, "n/a" for NaN.
std::string suiteNumber(double v);

}  // namespace haif
