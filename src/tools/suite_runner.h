// Running one job of a suite (docs/suites.md) with the library the single-job commands use:
// simulation.h and run_report.h as `haif run`, the stress probe and judge as `haif stress`, the
// frame diff as `haif diff`. A job that fails, or cannot run, is a result, not an error: the suite
// goes on and the report says why.
#pragma once

#include "tools/simulation.h"
#include "tools/suite_report.h"
#include "tools/suite_spec.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// Draws frames of a simulated scene for render jobs. The command supplies it: the renderer and the
/// frame builder belong to the app, and a build without a renderer has none.
class SuiteFramePainter {
 public:
  virtual ~SuiteFramePainter() = default;
  /// Prepares to draw `sim` (its meshes, its camera) at width x height. One error line on failure.
  virtual bool begin(const Simulation& sim, int width, int height, std::string& error) = 0;
  /// Draws the current state: width * height RGBA pixels, top row first.
  virtual bool paint(const Simulation& sim, std::vector<uint8_t>& rgba, std::string& error) = 0;
};

struct SuiteRunContext {
  int threads = 1;                      ///< for jobs that set none
  std::string reportDir;                ///< where the report is being written (its staging folder)
  SuiteFramePainter* painter = nullptr; ///< null: render jobs cannot run (the command refuses them first)
  bool updateReferences = false;        ///< render jobs write their frames as the new reference
};

/// Runs `job`, writing its files under ctx.reportDir/jobs/NAME/. Always returns its result.
SuiteJobResult runSuiteJob(const SuiteJob& job, const SuiteRunContext& ctx);

}  // namespace haif
