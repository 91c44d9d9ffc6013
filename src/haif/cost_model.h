// Cost model of a step on this machine: what `haif calibrate` measures and writes, what the
// adaptive controller starts from, and what model mode decides with (so its decisions are a pure
// function of the simulation state: deterministic for any thread count and machine load).
#pragma once

#include <string>

namespace haif {

struct CostModel {
  double msPerRowIteration = 2.0e-5;  ///< one PGS row update (3 rows per contact point), one thread
  double msPerRowPrepare = 4.0e-5;    ///< building + warm starting + storing one row
  double msPerContactPoint = 2.5e-4;  ///< collision detection per contact point (broad + narrow)
  double msPerBody = 3.0e-4;          ///< per awake body: forces, bounds, integration
  double parallelEfficiency = 0.85;   ///< speed-up per extra thread relative to ideal
  int modelThreads = 1;               ///< threads model mode plans for (fixed, so decisions never depend on --threads)

  /// Modelled time of collision detection for a state.
  double collisionMs(unsigned bodies, unsigned contactPoints) const {
    return msPerBody * 0.5 * bodies + msPerContactPoint * contactPoints;
  }
  /// Rows on the critical path with `threads` threads: the larger of the biggest island and
  /// the total work shared among the threads (docs/architecture.md, "The iteration controller").
  static double criticalRows(unsigned totalRows, unsigned largestRows, int threads, double efficiency);

  /// Writes "key value" lines; returns false with a message on failure.
  bool save(const std::string& path, std::string& error) const;
  /// Reads a file written by save(); unknown keys or bad numbers are errors naming file and line.
  bool load(const std::string& path, std::string& error);
};

}  // namespace haif
