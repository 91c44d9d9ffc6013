// Shards of a suite: `--shard I/N` runs the jobs whose index k (from 0, in the suite file's order)
// has k mod N == I - 1. I counts from 1, as Slurm array ids and CI matrix values usually do; the
// split depends only on the job list, so N machines given 1/N .. N/N run every job exactly once.
#pragma once

#include <cstddef>
#include <string>

namespace haif {

struct SuiteShard {
  int index = 1;  ///< I, from 1
  int count = 1;  ///< N
  bool whole() const { return count == 1; }
  /// "I/N".
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
  /// Whether job `job` (its index in the suite, from 0) belongs to this shard.
  bool holds(size_t job) const { return int(job % size_t(count)) == index - 1; }
};

/// Parses "I/N" with 1 <= I <= N <= 100000. False with one error line saying what is wrong.
bool parseSuiteShard(const std::string& text, SuiteShard& out, std::string& error);

}  // namespace haif
