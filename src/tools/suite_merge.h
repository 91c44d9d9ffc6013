// Joining the reports of a suite's shards (`haif suite merge`) into the report one unsharded run
// would have written: every job exactly once, in suite order. Reports of different suite files,
// overlapping reports and incomplete sets are refused, naming the jobs concerned.
#pragma once

#include "tools/suite_report.h"

#include <string>
#include <vector>

namespace haif {

/// Joins `parts` (read from the report files `labels` name, for messages). False with one error
/// line when they are of different suites (file hash), when a job is in two of them, or when jobs
/// are in none (listed by index and name, with the shards that would have held them).
bool mergeSuiteReports(const std::vector<SuiteReport>& parts, const std::vector<std::string>& labels, SuiteReport& out,
                       std::string& error);

}  // namespace haif
