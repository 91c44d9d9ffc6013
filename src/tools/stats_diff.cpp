#include "tools/stats_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

namespace haif {

namespace {

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

bool parseTable(const std::string& text, const std::string& name, Table& t, std::string& error) {
  std::stringstream ss(text);
  std::string line;
  if (!std::getline(ss, line) || line.empty()) {
    error = name + ": empty stats file (expected a CSV header)";
    return false;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  t.header = splitCsvLine(line);
  for (int lineNo = 2; std::getline(ss, line); ++lineNo) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    t.rows.push_back(splitCsvLine(line));
    if (t.rows.back().size() != t.header.size()) {
      error = name + ":" + std::to_string(lineNo) + ": " + std::to_string(t.rows.back().size()) +
              " cells, the header has " + std::to_string(t.header.size());
      return false;
    }
  }
  return true;
}

bool asNumber(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return *end == '\0';
}

}  // namespace

bool isTimingColumn(const std::string& name) {
  const auto endsWith = [&](const char* suffix) {
    const std::string s(suffix);
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  // *_ms are wall-clock times; a deadline miss is decided by them.
  return endsWith("_ms") || name == "deadline_miss";
}

bool compareStatsCsv(const std::string& referenceCsv, const std::string& testCsv, const std::string& referenceName,
                     const std::string& testName, StatsDiff& out, std::string& error) {
  Table a, b;
  if (!parseTable(referenceCsv, referenceName, a, error) || !parseTable(testCsv, testName, b, error)) return false;
  StatsDiff d;
  d.referenceRows = int(a.rows.size());
  d.testRows = int(b.rows.size());
  std::map<std::string, size_t> columnOfB;
  for (size_t c = 0; c < b.header.size(); ++c) columnOfB[b.header[c]] = c;
  for (const std::string& name : b.header)
    if (std::find(a.header.begin(), a.header.end(), name) == a.header.end()) d.missingColumns.push_back(name);
  const size_t rows = std::min(a.rows.size(), b.rows.size());
  for (size_t ca = 0; ca < a.header.size(); ++ca) {
    const std::string& name = a.header[ca];
    if (isTimingColumn(name)) {
      d.ignoredColumns.push_back(name);
      continue;
    }
    const auto it = columnOfB.find(name);
    if (it == columnOfB.end()) {
      d.missingColumns.push_back(name);
      continue;
    }
    ColumnDiff cd;
    cd.column = name;
    for (size_t r = 0; r < rows; ++r) {
      const std::string& va = a.rows[r][ca];
      const std::string& vb = b.rows[r][it->second];
      if (va == vb) continue;
      if (cd.rows++ == 0) cd.firstRow = int(r), cd.reference = va, cd.test = vb;
      double x = 0, y = 0;
      if (asNumber(va, x) && asNumber(vb, y)) cd.maxAbsDiff = std::max(cd.maxAbsDiff, std::fabs(x - y));
    }
    if (cd.rows > 0) d.differing.push_back(cd);
  }
  out = std::move(d);
  return true;
}

}  // namespace haif
