#include "haif/cost_model.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace haif {

double CostModel::criticalRows(unsigned totalRows, unsigned largestRows, int threads, double efficiency) {
  const double share = threads > 1 ? double(totalRows) / (1.0 + (threads - 1) * efficiency) : double(totalRows);
  return std::max(double(largestRows), share);
}

namespace {
struct Field {
  const char* key;
  double CostModel::*member;
};
const Field kFields[] = {
    {"ms_per_row_iteration", &CostModel::msPerRowIteration},
    {"ms_per_row_prepare", &CostModel::msPerRowPrepare},
    {"ms_per_contact_point", &CostModel::msPerContactPoint},
    {"ms_per_body", &CostModel::msPerBody},
    {"parallel_efficiency", &CostModel::parallelEfficiency},
};
}  // namespace

bool CostModel::save(const std::string& path, std::string& error) const {
  std::ostringstream out;
  out << "# HAIF cost model (haif calibrate); times in milliseconds\n";
  char buf[64];
  for (const Field& f : kFields) {
    std::snprintf(buf, sizeof buf, "%.6g", this->*f.member);
    out << f.key << ' ' << buf << '\n';
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << out.str();
    if (!f.good()) {
      error = path + ": cannot write cost model (" + std::strerror(errno) + ")";
      std::remove(tmp.c_str());
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = path + ": cannot write cost model (" + std::strerror(errno) + ")";
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

bool CostModel::load(const std::string& path, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open cost model (" + std::strerror(errno) + ")";
    return false;
  }
  CostModel m = *this;
  std::string line;
  for (int row = 1; std::getline(in, line); ++row) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::string key, value;
    ls >> key >> value;
    const Field* field = nullptr;
    for (const Field& f : kFields)
      if (key == f.key) field = &f;
    if (!field) {
      error = path + ":" + std::to_string(row) + ": unknown key '" + key + "'";
      return false;
    }
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v) || v <= 0.0) {
      error = path + ":" + std::to_string(row) + ": " + key + ": expected a positive number, got '" + value + "'";
      return false;
    }
    m.*(field->member) = v;
  }
  *this = m;
  return true;
}

}  // namespace haif
