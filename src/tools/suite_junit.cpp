#include "tools/suite_junit.h"

#include "tools/markup_text.h"

#include <cstdio>

namespace haif {

namespace {

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", s);
  return text;
}

std::string attribute(const char* name, const std::string& value) {
  return std::string(" ") + name + "=\"" + escapeMarkup(value) + "\"";
}

// JUnit's timestamp has no zone designator (xs:dateTime as the schema uses it); ours is UTC.
std::string junitTimestamp(const std::string& iso) {
  return !iso.empty() && iso.back() == 'Z' ? iso.substr(0, iso.size() - 1) : iso;
}

}  // namespace

std::string suiteJunitXml(const SuiteReport& r) {
  double total = 0.0;
  for (const SuiteJobResult& j : r.jobs) total += j.wallSeconds;
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuite" + attribute("name", r.suiteName) + attribute("tests", std::to_string(r.jobs.size())) +
       attribute("failures", std::to_string(r.failed() - r.errors())) +
       attribute("errors", std::to_string(r.errors())) + attribute("skipped", std::to_string(r.skipped())) +
       attribute("time", seconds(total)) + attribute("timestamp", junitTimestamp(r.started)) + ">\n";
  x += "  <properties>\n";
  x += "    <property" + attribute("name", "suite_file") + attribute("value", r.suiteFile) + "/>\n";
  x += "    <property" + attribute("name", "suite_hash") + attribute("value", r.suiteHash) + "/>\n";
  x += "    <property" + attribute("name", "shard") + attribute("value", r.merged() ? "merged" : r.shard.text()) +
       "/>\n";
  x += "    <property" + attribute("name", "suite_jobs") + attribute("value", std::to_string(r.totalJobs)) + "/>\n";
  x += "  </properties>\n";
  for (const SuiteJobResult& j : r.jobs) {
    x += "  <testcase" + attribute("classname", r.suiteName + "." + j.kind) + attribute("name", j.name) +
         attribute("time", seconds(j.wallSeconds)) + ">\n";
    if (j.skipped) {
      x += "    <skipped" + attribute("message", j.notes.empty() ? "skipped" : j.notes.front()) + "/>\n";
    } else if (!j.pass) {
      // The first reason is the message CI systems show in their summaries; the body has them all.
      std::string all;
      for (const std::string& f : j.failures) all += f + "\n";
      const std::string first = j.failures.empty() ? "failed" : j.failures.front();
      const char* tag = j.error ? "error" : "failure";
      x += std::string("    <") + tag + attribute("message", first) + attribute("type", j.error ? "error" : "check") +
           ">" + escapeMarkup(all, true) + "</" + tag + ">\n";
    }
    std::string out = j.scene + "\n";
    for (const SuiteCheckOutcome& c : j.checks)
      out += std::string(c.pass ? "pass " : "FAIL ") + c.criterion + " (got " + suiteNumber(c.value) + ")\n";
    for (const std::string& n : j.notes) out += n + "\n";
    x += "    <system-out>" + escapeMarkup(out, true) + "</system-out>\n";
    x += "  </testcase>\n";
  }
  x += "</testsuite>\n";
  return x;
}

}  // namespace haif
