// The benchmark's outputs: results.csv (one row per scene, engine and set-up) and report.md
// (the seed's table of sequential, HAIF and Bullet, equal-error comparisons, Pareto fronts, every run).
#pragma once

#include "tools/bench_sweep.h"

#include <string>
#include <vector>

namespace haif {

/// How the bench was run, for the report's preamble.
struct BenchReportInfo {
  int steps = 0;
  int threads = 1;              ///< HAIF's threads in the seed's table (the most swept)
  std::vector<int> threadCounts;  ///< every thread count swept, fewest first (more than one: a scaling table)
  int errorEvery = 0;           ///< solve error sampled every this many steps (0: off)
  double seedBudgetMs = 4.0;    ///< HAIF's budget in the seed's table
  bool quick = false;
  int rounds = 1;               ///< runs per set-up (--repeat)
  std::vector<std::string> engines;
  std::vector<std::string> plots;  ///< PNG file names next to report.md
  std::string plotsNote;           ///< why there are no plots (empty: there are)
};

/// The CSV header and one line per result.
std::string benchResultsCsv(const std::vector<BenchResult>& rows);

/// report.md.
std::string benchReportMarkdown(const std::vector<BenchResult>& rows, const BenchReportInfo& info);

/// The seed's three set-ups on one scene: sequential (HAIF fixed:10 on one thread), HAIF (adaptive
/// at the seed budget on the sweep's threads) and Bullet fixed:10. Null where not run.
struct SeedTriple {
  const BenchResult* sequential = nullptr;
  const BenchResult* haif = nullptr;
  const BenchResult* bullet = nullptr;
};
SeedTriple findSeedTriple(const std::vector<BenchResult>& rows, const std::string& scene, int threads,
                          double budgetMs);

}  // namespace haif
