#include "tools/suite_report.h"

#include "scene/json_reader.h"
#include "scene/text_file.h"

#include <cstdio>
#include <ctime>

namespace haif {

namespace {

// Tells report.json apart from other JSON files a merge might be pointed at, and its layout's version.
constexpr const char* kFormat = "haif-suite-report-1";

nlohmann::ordered_json numberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

double readNumberOrNull(const JsonNode& node) { return node.json().is_null() ? NAN : readNumber(node); }

std::vector<std::string> readStrings(const JsonNode& node) {
  requireArray(node);
  std::vector<std::string> out;
  for (size_t i = 0; i < node.size(); ++i) out.push_back(readString(node.element(i)));
  return out;
}

SuiteJobResult readJob(const JsonNode& node, size_t totalJobs) {
  requireObject(node);
  SuiteJobResult j;
  j.index = size_t(readInt(requireMember(node, "index"), 0, int(totalJobs) - 1));
  j.name = readString(requireMember(node, "name"));
  j.kind = readString(requireMember(node, "kind"));
  j.scene = readString(requireMember(node, "scene"));
  const JsonNode setup = requireMember(node, "setup");
  requireObject(setup);
  j.setup = setup.json();
  const JsonNode pass = requireMember(node, "pass");
  j.skipped = readBool(requireMember(node, "skipped"));
  if (!j.skipped) j.pass = readBool(pass);
  j.error = readBool(requireMember(node, "error"));
  j.failures = readStrings(requireMember(node, "failures"));
  j.notes = readStrings(requireMember(node, "notes"));
  const JsonNode checks = requireMember(node, "checks");
  requireArray(checks);
  for (size_t i = 0; i < checks.size(); ++i) {
    const JsonNode c = checks.element(i);
    requireObject(c);
    SuiteCheckOutcome o;
    o.check = readString(requireMember(c, "check"));
    o.criterion = readString(requireMember(c, "criterion"));
    o.value = readNumberOrNull(requireMember(c, "value"));
    o.limit = readNumberOrNull(requireMember(c, "limit"));
    o.pass = readBool(requireMember(c, "pass"));
    j.checks.push_back(o);
  }
  const JsonNode metrics = requireMember(node, "metrics");
  requireObject(metrics);
  j.metrics = metrics.json();
  j.artifacts = readStrings(requireMember(node, "artifacts"));
  j.wallSeconds = readNumber(requireMember(node, "wall_s"));
  return j;
}

void readReport(const JsonNode& root, SuiteReport& r) {
  requireObject(root);
  const JsonNode format = requireMember(root, "format", std::string("\"") + kFormat + "\"");
  if (!format.json().is_string() || format.json().get<std::string>() != kFormat)
    fail(format, std::string("not a haif suite report (expected \"") + kFormat + "\", got " +
                     describeValue(format.json()) + ")");
  const JsonNode suite = requireMember(root, "suite");
  requireObject(suite);
  r.suiteFile = readString(requireMember(suite, "file"));
  r.suiteName = readString(requireMember(suite, "name"));
  r.suiteHash = readString(requireMember(suite, "hash"));
  r.totalJobs = size_t(readInt(requireMember(suite, "jobs"), 1, 100000000));
  r.jobNames = readStrings(requireMember(suite, "job_names"));
  if (r.jobNames.size() != r.totalJobs)
    fail(suite.member("job_names"), "lists " + std::to_string(r.jobNames.size()) + " names for " +
                                        std::to_string(r.totalJobs) + " jobs");
  const JsonNode shard = requireMember(root, "shard");
  if (!shard.json().is_null()) {
    requireObject(shard);
    r.shard.count = readInt(requireMember(shard, "count"), 1, 100000);
    r.shard.index = readInt(requireMember(shard, "index"), 1, r.shard.count);
  }
  if (root.member("merged_from").present()) r.mergedFrom = readStrings(root.member("merged_from"));
  r.started = readString(requireMember(root, "started"));
  r.command = readString(requireMember(root, "command"));
  r.wallSeconds = readNumber(requireMember(root, "wall_s"));
  r.updateReferences = readBool(requireMember(root, "update_references"));
  const JsonNode jobs = requireMember(root, "jobs");
  requireArray(jobs);
  for (size_t i = 0; i < jobs.size(); ++i) {
    r.jobs.push_back(readJob(jobs.element(i), r.totalJobs));
    if (r.jobs.back().name != r.jobNames[r.jobs.back().index])
      fail(jobs.element(i).member("name"), "job " + std::to_string(r.jobs.back().index) + " is '" +
                                               r.jobNames[r.jobs.back().index] + "' in suite.job_names");
  }
}

}  // namespace

int SuiteReport::passed() const {
  int n = 0;
  for (const SuiteJobResult& j : jobs) n += !j.skipped && j.pass ? 1 : 0;
  return n;
}

int SuiteReport::failed() const {
  int n = 0;
  for (const SuiteJobResult& j : jobs) n += !j.skipped && !j.pass ? 1 : 0;
  return n;
}

int SuiteReport::errors() const {
  int n = 0;
  for (const SuiteJobResult& j : jobs) n += j.error ? 1 : 0;
  return n;
}

int SuiteReport::skipped() const {
  int n = 0;
  for (const SuiteJobResult& j : jobs) n += j.skipped ? 1 : 0;
  return n;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string suiteNumber(double v) {
  if (!std::isfinite(v)) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string suiteReportJson(const SuiteReport& r) {
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["suite"] = {{"file", r.suiteFile},
                {"name", r.suiteName},
                {"hash", r.suiteHash},
                {"jobs", r.totalJobs},
                {"job_names", r.jobNames}};
  if (r.merged()) {
    j["shard"] = nullptr;
    j["merged_from"] = r.mergedFrom;
  } else {
    j["shard"] = {{"index", r.shard.index}, {"count", r.shard.count}};
  }
  j["jobs_in_report"] = r.jobs.size();
  j["passed"] = r.passed();
  j["failed"] = r.failed();
  j["errors"] = r.errors();
  j["skipped"] = r.skipped();
  j["pass"] = r.pass();
  j["started"] = r.started;
  j["command"] = r.command;
  j["wall_s"] = r.wallSeconds;
  j["update_references"] = r.updateReferences;
  nlohmann::ordered_json jobs = nlohmann::ordered_json::array();
  for (const SuiteJobResult& job : r.jobs) {
    nlohmann::ordered_json o;
    o["index"] = job.index;
    o["name"] = job.name;
    o["kind"] = job.kind;
    o["scene"] = job.scene;
    o["setup"] = job.setup;
    if (job.skipped) o["pass"] = nullptr;
    else o["pass"] = job.pass;
    o["skipped"] = job.skipped;
    o["error"] = job.error;
    o["failures"] = job.failures;
    o["notes"] = job.notes;
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    for (const SuiteCheckOutcome& c : job.checks)
      checks.push_back({{"check", c.check},
                        {"criterion", c.criterion},
                        {"value", numberOrNull(c.value)},
                        {"limit", numberOrNull(c.limit)},
                        {"pass", c.pass}});
    o["checks"] = checks;
    o["metrics"] = job.metrics;
    o["artifacts"] = job.artifacts;
    o["wall_s"] = job.wallSeconds;
    jobs.push_back(o);
  }
  j["jobs"] = jobs;
  return j.dump(2) + "\n";
}

bool readSuiteReport(const std::string& path, SuiteReport& out, std::string& error) {
  std::string text;
  if (!readTextFile(path, "suite report", text, error)) return false;
  const Json doc = Json::parse(text, nullptr, false);
  if (doc.is_discarded()) {
    error = path + ": not a haif suite report (not valid JSON)";
    return false;
  }
  JsonNode root;
  root.value = &doc;
  SuiteReport r;
  try {
    readReport(root, r);
  } catch (const SceneError& e) {
    error = path + ": " + (e.place == "scene" ? "report" : e.place) + ": " + e.message;
    return false;
  }
  out = std::move(r);
  return true;
}

std::string suiteJobLine(const SuiteJobResult& job, size_t total) {
  const char* verdict = job.skipped ? "SKIP" : job.error ? "ERROR" : job.pass ? "PASS" : "FAIL";
  std::string detail;
  if (!job.failures.empty()) {
    detail = job.failures.front();
    if (job.failures.size() > 1) detail += " (+" + std::to_string(job.failures.size() - 1) + " more)";
  } else if (!job.notes.empty()) {
    detail = job.notes.front();
  } else {
    for (const SuiteCheckOutcome& c : job.checks)
      if (c.check != "no_nan") {
        detail = c.criterion + " (got " + suiteNumber(c.value) + ")";
        break;
      }
  }
  char head[160];
  std::snprintf(head, sizeof head, "[%zu/%zu] %-24s %-5s ", job.index + 1, total, job.name.c_str(), verdict);
  char tail[48];
  std::snprintf(tail, sizeof tail, "  [%.1f s]", job.wallSeconds);
  return head + detail + tail;
}

}  // namespace haif
