#include "tools/suite_merge.h"

#include <algorithm>
#include <set>

namespace haif {

namespace {

std::string describeShard(const SuiteReport& r) { return r.merged() ? "a merged report" : "shard " + r.shard.text(); }

// "3 (pyramid_15), 7 (cradle)", at most `limit` of them.
std::string jobList(const std::vector<size_t>& jobs, const std::vector<std::string>& names, size_t limit = 10) {
  std::string out;
  for (size_t k = 0; k < jobs.size() && k < limit; ++k)
    out += (k ? ", " : "") + std::to_string(jobs[k]) + " (" + names[jobs[k]] + ")";
  if (jobs.size() > limit) out += " and " + std::to_string(jobs.size() - limit) + " more";
  return out;
}

}  // namespace

bool mergeSuiteReports(const std::vector<SuiteReport>& parts, const std::vector<std::string>& labels, SuiteReport& out,
                       std::string& error) {
  if (parts.empty()) {
    error = "no reports to merge";
    return false;
  }
  const SuiteReport& first = parts.front();
  for (size_t p = 1; p < parts.size(); ++p) {
    const SuiteReport& r = parts[p];
    if (r.suiteHash != first.suiteHash || r.totalJobs != first.totalJobs || r.jobNames != first.jobNames) {
      error = labels[p] + " is a report of suite '" + r.suiteName + "' (" + r.suiteFile + ", hash " + r.suiteHash +
              "), " + labels[0] + " of suite '" + first.suiteName + "' (" + first.suiteFile + ", hash " +
              first.suiteHash + "): merge the shards of one suite file";
      return false;
    }
  }
  // Which report holds each job: once exactly.
  std::vector<int> owner(first.totalJobs, -1);
  for (size_t p = 0; p < parts.size(); ++p)
    for (const SuiteJobResult& j : parts[p].jobs) {
      if (owner[j.index] >= 0) {
        error = "job " + std::to_string(j.index) + " (" + j.name + ") is in both " + labels[size_t(owner[j.index])] +
                " (" + describeShard(parts[size_t(owner[j.index])]) + ") and " + labels[p] + " (" +
                describeShard(parts[p]) + "): the reports overlap";
        return false;
      }
      owner[j.index] = int(p);
    }
  std::vector<size_t> missing;
  for (size_t k = 0; k < owner.size(); ++k)
    if (owner[k] < 0) missing.push_back(k);
  if (!missing.empty()) {
    error = std::to_string(missing.size()) + " of " + std::to_string(first.totalJobs) +
            " jobs are in none of the reports: " + jobList(missing, first.jobNames);
    // When the parts are shards of one split, say which shards are missing.
    std::set<int> counts;
    for (const SuiteReport& r : parts) counts.insert(r.merged() ? 0 : r.shard.count);
    if (counts.size() == 1 && *counts.begin() > 0) {
      const int n = *counts.begin();
      std::set<int> shards;
      for (const size_t k : missing) shards.insert(int(k % size_t(n)) + 1);
      std::string list;
      for (const int s : shards) list += (list.empty() ? "" : ", ") + std::to_string(s) + "/" + std::to_string(n);
      error += " (missing shard" + std::string(shards.size() > 1 ? "s " : " ") + list + ")";
    }
    return false;
  }

  SuiteReport m;
  m.suiteFile = first.suiteFile;
  m.suiteName = first.suiteName;
  m.suiteHash = first.suiteHash;
  m.totalJobs = first.totalJobs;
  m.jobNames = first.jobNames;
  m.started = first.started;
  for (size_t p = 0; p < parts.size(); ++p) {
    const SuiteReport& r = parts[p];
    m.mergedFrom.push_back(labels[p] + " (" + describeShard(r) + ")");
    if (!r.started.empty() && (m.started.empty() || r.started < m.started)) m.started = r.started;
    // Shards run side by side: the merged run took as long as the longest.
    m.wallSeconds = std::max(m.wallSeconds, r.wallSeconds);
    m.updateReferences = m.updateReferences || r.updateReferences;
    m.jobs.insert(m.jobs.end(), r.jobs.begin(), r.jobs.end());
  }
  std::sort(m.jobs.begin(), m.jobs.end(),
            [](const SuiteJobResult& a, const SuiteJobResult& b) { return a.index < b.index; });
  out = std::move(m);
  return true;
}

}  // namespace haif
