#include "tools/suite_shard.h"

#include <cstdlib>

namespace haif {

namespace {

// A whole decimal number in [lo, hi]; no sign, no spaces, no trailing characters.
bool readCount(const std::string& text, long lo, long hi, long& out) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return false;
  out = std::strtol(text.c_str(), nullptr, 10);
  return out >= lo && out <= hi;
}

}  // namespace

bool parseSuiteShard(const std::string& text, SuiteShard& out, std::string& error) {
  const std::string what = "--shard: expected I/N, shard I (from 1) of N (e.g. 2/4), got '" + text + "'";
  const size_t slash = text.find('/');
  if (slash == std::string::npos) {
    error = what;
    return false;
  }
  long i = 0, n = 0;
  if (!readCount(text.substr(slash + 1), 1, 100000, n)) {
    error = what + ": N must be a whole number from 1 to 100000";
    return false;
  }
  if (!readCount(text.substr(0, slash), 1, 100000, i)) {
    error = what + ": I must be a whole number from 1 to N (shards count from 1)";
    return false;
  }
  if (i > n) {
    error = what + ": there is no shard " + std::to_string(i) + " of " + std::to_string(n) + " (I runs from 1 to N)";
    return false;
  }
  out.index = int(i);
  out.count = int(n);
  return true;
}

}  // namespace haif
