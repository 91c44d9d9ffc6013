#include "render/run_charts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/chart.h"
#include "render/chart_colors.h"
#include "render/png_io.h"

namespace haif::render {
namespace {

std::string titleOf(const RunSeries& run, const std::string& what) {
  std::string t = what;
  if (!run.scene.empty()) t += "  -  " + run.scene;
  if (!run.mode.empty()) t += " (" + run.mode + ")";
  return t;
}

bool renderAndWrite(const std::string& path, const ChartSpec& spec, const RunChartOptions& options,
                    std::string* error) {
  return writeChartGrid(path, {spec}, 1, options, error);
}

}  // namespace

bool writeIterationsChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                          std::string* error) {
  ChartSpec spec;
  spec.title = titleOf(run, "Solver iterations per step");
  spec.xLabel = "step";
  spec.yLabel = "iterations";
  spec.series.push_back({"iterations", run.iterations, chart_colors::kIterations, ChartSeries::Style::Line, 1.6f});
  if (run.iMin > 0.f) spec.hlines.push_back({"I_min", run.iMin, chart_colors::kIMin, true});
  if (run.iMax > 0.f) spec.hlines.push_back({"I_max", run.iMax, chart_colors::kIMax, true});
  return renderAndWrite(path, spec, options, error);
}

bool writeStepTimeChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                        std::string* error) {
  ChartSpec spec;
  spec.title = titleOf(run, "Step time");
  spec.xLabel = "step";
  spec.yLabel = "time per step (ms)";
  spec.series.push_back({"collision", run.collisionMs, chart_colors::kCollision, ChartSeries::Style::StackedArea, 0.f});
  spec.series.push_back({"solve", run.solveMs, chart_colors::kSolve, ChartSeries::Style::StackedArea, 0.f});
  std::vector<float> total = run.totalMs;
  if (total.empty()) {
    total.resize(std::max(run.collisionMs.size(), run.solveMs.size()), 0.f);
    for (size_t i = 0; i < total.size(); ++i)
      total[i] = (i < run.collisionMs.size() ? run.collisionMs[i] : 0.f) +
                 (i < run.solveMs.size() ? run.solveMs[i] : 0.f);
  }
  // A first step of 130 ms (allocations, cold caches) would set a scale that flattens every later
  // step against a 4 ms budget: such steps run off the top, and the title says how many and how high.
  spec.yMax = robustTimeTop(total, run.budgetMs);
  if (std::isfinite(spec.yMax)) {
    int above = 0;
    float highest = 0.f;
    for (float v : total)
      if (v > spec.yMax) ++above, highest = std::max(highest, v);
    char note[96];
    std::snprintf(note, sizeof note, "   [%d step%s above the scale, up to %.1f ms]", above, above == 1 ? "" : "s",
                  highest);
    spec.title += note;
  }
  spec.series.push_back({"total step", std::move(total), chart_colors::kTotal, ChartSeries::Style::Line, 1.3f});
  if (run.budgetMs > 0.f) spec.hlines.push_back({"budget", run.budgetMs, chart_colors::kBudget, false});
  return renderAndWrite(path, spec, options, error);
}

bool writeErrorChart(const std::string& path, const RunSeries& run, const RunChartOptions& options,
                     std::string* error) {
  ChartSpec spec;
  spec.title = titleOf(run, "Per-step " + run.errorName);
  spec.xLabel = "step";
  spec.yLabel = run.errorName + (run.errorUnit.empty() ? "" : " (" + run.errorUnit + ")");
  float lo = INFINITY, hi = 0.f;
  for (float v : run.error)
    if (std::isfinite(v) && v > 0.f) lo = std::min(lo, v), hi = std::max(hi, v);
  if (run.errorThreshold > 0.f) lo = std::min(lo, run.errorThreshold), hi = std::max(hi, run.errorThreshold);
  // Log scale once the data spans more than ~1.5 decades; otherwise a linear axis reads easier.
  spec.logY = hi > 0.f && std::isfinite(lo) && hi / lo > 30.f;
  if (spec.logY) spec.yLabel += ", log scale";
  spec.series.push_back({run.errorName, run.error, chart_colors::kError, ChartSeries::Style::Line, 1.6f});
  if (run.errorThreshold > 0.f)
    spec.hlines.push_back({"threshold", run.errorThreshold, chart_colors::kBudget, true});
  return renderAndWrite(path, spec, options, error);
}

bool writeChartGrid(const std::string& path, const std::vector<ChartSpec>& panels, int columns,
                    const RunChartOptions& options, std::string* error) {
  if (options.width < 64 || options.height < 64 || panels.empty() || columns < 1) {
    if (error) *error = "chart '" + path + "': image too small or nothing to draw";
    return false;
  }
  auto text = TextRenderer::create(options.fontPath, error);
  if (!text) return false;
  std::vector<uint8_t> rgba(static_cast<size_t>(options.width) * options.height * 4);
  Canvas canvas(rgba.data(), options.width, options.height);
  const int cols = std::min<int>(columns, static_cast<int>(panels.size()));
  const int rows = static_cast<int>((panels.size() + cols - 1) / cols);
  ChartStyle style;
  style.fontSize = std::max(11, options.height / rows / 40);
  for (size_t k = 0; k < panels.size(); ++k) {
    const int c = static_cast<int>(k) % cols, r = static_cast<int>(k) / cols;
    drawChart(canvas, *text, options.width * c / cols, options.height * r / rows, options.width * (c + 1) / cols,
              options.height * (r + 1) / rows, panels[k], style);
  }
  return writePng(path, options.width, options.height, rgba.data(), error);
}

bool writeRunCharts(const std::string& dir, const RunSeries& run, const RunChartOptions& options,
                    std::string* error) {
  const std::string base = dir.empty() || dir.back() == '/' ? dir : dir + "/";
  if (!writeIterationsChart(base + "iterations.png", run, options, error)) return false;
  if (!writeStepTimeChart(base + "step_time.png", run, options, error)) return false;
  if (!run.error.empty() && !writeErrorChart(base + "error.png", run, options, error)) return false;
  return true;
}

}  // namespace haif::render
