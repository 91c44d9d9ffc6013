#include "app/cli.h"

#include "tools/diff_report.h"

#include <cmath>
#include <cstdlib>

namespace haif {

bool CommandLine::parse(int argc, char** argv, int first, std::string& error) {
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string value;
    const size_t eq = a.find('=');
    const bool inlineValue = eq != std::string::npos;
    if (inlineValue) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
    }
    if (flags_.count(a)) {
      if (inlineValue) {
        error = "haif " + command_ + ": " + a + " takes no value";
        return false;
      }
      set_.insert(a);
    } else if (valued_.count(a)) {
      if (!inlineValue) {
        if (i + 1 >= argc) {
          error = "haif " + command_ + ": " + a + " needs a value";
          return false;
        }
        value = argv[++i];
      }
      values_[a] = value;
    } else {
      error = "haif " + command_ + ": unknown option " + a + " (see 'haif help')";
      return false;
    }
  }
  return true;
}

std::string CommandLine::get(const std::string& key, const std::string& fallback) const {
  const auto it = values_.find(key);
  return it == values_.end() ? fallback : it->second;
}

bool CommandLine::getInt(const std::string& key, int lo, int hi, int& out, std::string& error) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return true;
  char* end = nullptr;
  const long v = std::strtol(it->second.c_str(), &end, 10);
  if (it->second.empty() || *end != '\0' || v < lo || v > hi) {
    error = "haif " + command_ + ": " + key + ": expected an integer in [" + std::to_string(lo) + ", " +
            std::to_string(hi) + "], got '" + it->second + "'";
    return false;
  }
  out = int(v);
  return true;
}

bool CommandLine::getDouble(const std::string& key, double lo, double hi, double& out, std::string& error) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return true;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
    error = "haif " + command_ + ": " + key + ": expected a number in [" + std::to_string(lo) + ", " +
            std::to_string(hi) + "], got '" + it->second + "'";
    return false;
  }
  out = v;
  return true;
}

std::string commandLineOf(int argc, char** argv) {
  std::string s = "haif";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789-_./:=,+") == std::string::npos;
    s += " " + (plain ? a : shellQuote(a));
  }
  return s;
}

}  // namespace haif
