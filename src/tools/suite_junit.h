// junit.xml of `haif suite`: the JUnit XML that CI systems (GitHub Actions reporters, GitLab,
// Jenkins) read. One <testsuite> for the suite (or the shard), one <testcase> per job: a failed job
// has a <failure>, a job that could not run an <error>, a skipped stress job a <skipped/>.
#pragma once

#include "tools/suite_report.h"

#include <string>

namespace haif {

/// junit.xml text.
std::string suiteJunitXml(const SuiteReport& report);

}  // namespace haif
