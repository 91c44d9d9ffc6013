// Standalone PNG charts for a whole run, drawn in software (no GL): iterations.png,
// step_time.png and error.png. The app calls these once at the end of a run.
#pragma once

#include <string>
#include <vector>

#include "render/chart.h"
#include "render/renderer.h"

namespace haif::render {

/// Per-step series of a run; all vectors are indexed by step (oldest first) and may differ in length.
struct RunSeries {
  std::string scene;                 ///< scene name for the titles
  std::string mode;                  ///< controller mode for the titles, e.g. "adaptive"
  std::vector<float> iterations;     ///< solver iterations chosen per step
  float iMin = 0.f;                  ///< controller lower bound (<= 0: not drawn)
  float iMax = 0.f;                  ///< controller upper bound (<= 0: not drawn)
  std::vector<float> collisionMs;    ///< collision detection time per step (ms)
  std::vector<float> solveMs;        ///< solver time per step (ms)
  std::vector<float> totalMs;        ///< whole step time (ms); empty: collision + solve
  float budgetMs = 0.f;              ///< step budget (ms) (<= 0: not drawn)
  std::vector<float> error;          ///< per-step error, e.g. solve error e (dimensionless)
  std::string errorName = "solve error e";  ///< legend/axis name of `error`
  std::string errorUnit = "";        ///< unit shown on the error axis ("" = dimensionless)
  float errorThreshold = 0.f;        ///< reference line on the error chart, e.g. 0.02 (<= 0: none)
};

/// Image size and font of the charts.
struct RunChartOptions {
  int width = 1200;                       ///< pixels
  int height = 560;                       ///< pixels
  std::string fontPath = HAIF_FONT_PATH;  ///< TrueType font
};

/// iterations per step with dashed I_min / I_max.
bool writeIterationsChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                          std::string* error);
/// collision + solve stacked, total line and budget line, in ms.
bool writeStepTimeChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                        std::string* error);
/// the error series; log y axis when it spans more than a decade and a half.
bool writeErrorChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                     std::string* error);
/// Charts side by side in one PNG: `columns` per row, each panel width/columns wide and
/// height/rows tall (the benchmark's Pareto plots use it).
bool writeChartGrid(const std::string& path, const std::vector<ChartSpec>& panels, int columns,
                    const RunChartOptions& options, std::string* error);
/// All three into dir/iterations.png, dir/step_time.png, dir/error.png (error.png only if
/// run.error is non-empty). Stops at the first failure.
bool writeRunCharts(const std::string& dir, const RunSeries& run, const RunChartOptions& options,
                    std::string* error);

}  // namespace haif::render
