#include "tools/suite_html.h"

#include "tools/markup_text.h"

#include <cstdio>

namespace haif {

namespace {

std::string h(const std::string& s) { return escapeMarkup(s); }

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", s);
  return text;
}

// A set-up member as text ("" when absent or null).
std::string member(const nlohmann::json& setup, const char* key) {
  const auto it = setup.find(key);
  if (it == setup.end() || it->is_null()) return "";
  if (it->is_string()) return it->get<std::string>();
  if (it->is_boolean()) return it->get<bool>() ? "true" : "false";
  if (it->is_number_integer()) return std::to_string(it->get<long long>());
  if (it->is_number()) return suiteNumber(it->get<double>());
  return it->dump();
}

const char* kStyle = R"(body{font:14px/1.4 sans-serif;margin:1.5em;color:#222}
h1{font-size:1.4em;margin:0 0 .3em}table{border-collapse:collapse;width:100%}
th,td{border:1px solid #ccc;padding:4px 6px;vertical-align:top;text-align:left}
th{background:#f0f0f0}td.n{text-align:right;white-space:nowrap}
.pass{color:#176617;font-weight:bold}.fail{color:#b00020;font-weight:bold}.skip{color:#777;font-weight:bold}
tr.failed{background:#fff0f0}.verdict{font-size:1.2em;margin:.5em 0}
ul.checks{margin:0;padding-left:1.1em}li.bad{color:#b00020}code{font-size:.95em}
details{margin-top:.2em}pre{margin:.2em 0;white-space:pre-wrap}.meta{color:#555})";

}  // namespace

std::string suiteSetupText(const SuiteJobResult& job) {
  std::string out = member(job.setup, "mode");
  auto add = [&](const std::string& part) {
    if (!part.empty()) out += (out.empty() ? "" : ", ") + part;
  };
  const std::string it = member(job.setup, "iterations"), budget = member(job.setup, "budget_ms");
  add(it.empty() ? "" : it + " iterations");
  add(budget.empty() ? "" : budget + " ms budget");
  const std::string frames = member(job.setup, "frames");
  add(frames.empty() ? "" : frames + " frames");
  const std::string w = member(job.setup, "width"), hh = member(job.setup, "height");
  if (!w.empty()) add(w + "x" + hh + " every " + member(job.setup, "frame_every") + " steps");
  if (member(job.setup, "quick") == "true") add("quick");
  const std::string threads = member(job.setup, "threads");
  add(threads.empty() ? "" : threads + " threads");
  return out;
}

std::string suiteReportHtml(const SuiteReport& r) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>haif suite " +
                  h(r.suiteName) + "</title>\n<style>" + kStyle + "</style></head><body>\n";
  o += "<h1>haif suite: " + h(r.suiteName) + "</h1>\n";
  const std::string scope = r.merged() ? "merged from " + std::to_string(r.mergedFrom.size()) + " reports"
                                       : r.shard.whole() ? "the whole suite" : "shard " + r.shard.text();
  o += "<p class=\"meta\"><code>" + h(r.suiteFile) + "</code> (hash " + h(r.suiteHash) + "), " + h(scope) + ": " +
       std::to_string(r.jobs.size()) + " of " + std::to_string(r.totalJobs) + " jobs. Started " + h(r.started) +
       ", " + seconds(r.wallSeconds) + ".<br><code>" + h(r.command) + "</code></p>\n";
  if (r.merged()) {
    o += "<p class=\"meta\">Reports joined:</p><ul class=\"meta\">";
    for (const std::string& m : r.mergedFrom) o += "<li><code>" + h(m) + "</code></li>";
    o += "</ul>\n";
  }
  o += std::string("<p class=\"verdict\"><span class=\"") + (r.pass() ? "pass\">PASS" : "fail\">FAIL") +
       "</span>: " + std::to_string(r.passed()) + " passed, " + std::to_string(r.failed()) + " failed" +
       (r.errors() ? " (" + std::to_string(r.errors()) + " could not run)" : "") + ", " +
       std::to_string(r.skipped()) + " skipped.</p>\n";
  if (r.updateReferences) o += "<p>Render jobs rewrote their reference frames in this run.</p>\n";
  if (r.failed() > 0) {
    o += "<p>Failed:</p><ul>";
    for (const SuiteJobResult& j : r.jobs)
      if (!j.skipped && !j.pass)
        o += "<li><a href=\"#job-" + std::to_string(j.index) + "\">" + h(j.name) + "</a>: " +
             h(j.failures.empty() ? "failed" : j.failures.front()) + "</li>";
    o += "</ul>\n";
  }
  o += "<table>\n<tr><th>#</th><th>job</th><th>kind</th><th>scene</th><th>set-up</th><th>result</th>"
       "<th>checks</th><th>time</th></tr>\n";
  for (const SuiteJobResult& j : r.jobs) {
    const bool failed = !j.skipped && !j.pass;
    const char* cls = j.skipped ? "skip\">SKIP" : j.error ? "fail\">ERROR" : j.pass ? "pass\">PASS" : "fail\">FAIL";
    o += std::string("<tr id=\"job-") + std::to_string(j.index) + "\"" + (failed ? " class=\"failed\"" : "") + ">";
    o += "<td class=\"n\">" + std::to_string(j.index) + "</td><td>" + h(j.name) + "</td><td>" + h(j.kind) +
         "</td><td><code>" + h(j.scene) + "</code></td><td>" + h(suiteSetupText(j)) + "</td>";
    o += std::string("<td><span class=\"") + cls + "</span>";
    for (const std::string& f : j.failures) o += "<br>" + h(f);
    for (const std::string& n : j.notes) o += "<br><i>" + h(n) + "</i>";
    o += "</td><td><ul class=\"checks\">";
    for (const SuiteCheckOutcome& c : j.checks)
      o += std::string("<li") + (c.pass ? "" : " class=\"bad\"") + ">" + h(c.criterion) + ": " + suiteNumber(c.value) +
           "</li>";
    o += "</ul>";
    if (!j.metrics.empty()) o += "<details><summary>numbers</summary><pre>" + escapeMarkup(j.metrics.dump(1), true) + "</pre></details>";
    if (!j.artifacts.empty()) {
      o += "<details><summary>files</summary>";
      for (const std::string& a : j.artifacts) o += "<a href=\"" + h(urlPath(a)) + "\">" + h(a) + "</a><br>";
      o += "</details>";
    }
    o += "</td><td class=\"n\">" + seconds(j.wallSeconds) + "</td></tr>\n";
  }
  o += "</table>\n</body></html>\n";
  return o;
}

}  // namespace haif
