// report.html of `haif suite`: one self-contained page (inline style, no scripts, no external
// assets): the verdict, failed jobs first in a list of links, then a table of every job with its
// set-up, checks, numbers, failure messages, time and the files it wrote (relative links).
#pragma once

#include "tools/suite_report.h"

#include <string>

namespace haif {

/// report.html text.
std::string suiteReportHtml(const SuiteReport& report);

/// A job's set-up in a few words: "fixed, 10 iterations, 60 frames, 2 threads".
std::string suiteSetupText(const SuiteJobResult& job);

}  // namespace haif
