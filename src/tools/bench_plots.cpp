#include "tools/bench_plots.h"

#include "tools/pareto.h"

#ifdef HAIF_HAVE_RENDER
#include "render/run_charts.h"
#endif

#include <algorithm>
#include <map>

namespace haif {

#ifdef HAIF_HAVE_RENDER

namespace {

// Colour per curve, fixed by engine and mode so every plot reads the same.
render::Rgba curveColor(const BenchResult& r) {
  if (r.engine == "bullet") return {214, 39, 40, 255};                     // red
  if (r.mode == "adaptive") return {44, 160, 44, 255};                     // green
  return r.threads == 1 ? render::Rgba{148, 103, 189, 255} : render::Rgba{31, 119, 180, 255};  // purple / blue
}

render::ChartSpec panel(const std::string& scene, const std::vector<BenchResult>& rows, const BenchMetric& m) {
  render::ChartSpec spec;
  spec.title = scene + ": " + m.title;
  spec.xLabel = "ms per step (median), log scale";
  spec.yLabel = std::string(m.title) + ", log scale";
  spec.logX = true;
  spec.logY = true;
  spec.legend = render::LegendCorner::Best;
  // One curve per engine, mode and thread count, in increasing iterations / budget.
  std::map<std::string, std::vector<const BenchResult*>> curves;
  std::vector<double> x, y;
  for (const BenchResult& r : rows) {
    if (r.scene != scene || r.nan || !std::isfinite(m.get(r)) || m.get(r) <= 0.0) continue;
    curves[benchCurveName(r)].push_back(&r);
    x.push_back(r.msMedian);
    y.push_back(m.get(r));
  }
  for (auto& [name, pts] : curves) {
    std::sort(pts.begin(), pts.end(), [](const BenchResult* a, const BenchResult* b) { return a->param < b->param; });
    render::ChartSeries s;
    s.name = name;
    s.color = curveColor(*pts.front());
    s.width = 1.8f;
    s.marker = 7.f;
    for (const BenchResult* r : pts) {
      s.x.push_back(float(r->msMedian));
      s.values.push_back(float(m.get(*r)));
    }
    spec.series.push_back(std::move(s));
  }
  const std::vector<size_t> front = paretoFront(x, y);
  if (!front.empty()) {
    render::ChartSeries f;
    f.name = "Pareto front";
    f.color = {30, 30, 35, 255};
    f.width = 1.2f;
    f.dashed = true;
    f.marker = 15.f;
    f.hollow = true;
    for (size_t i : front) {
      f.x.push_back(float(x[i]));
      f.values.push_back(float(y[i]));
    }
    spec.series.push_back(std::move(f));
  }
  return spec;
}

}  // namespace

bool benchPlotsAvailable() { return true; }

bool writeBenchPlots(const std::string& dir, const std::vector<BenchResult>& rows, std::vector<std::string>& written,
                     std::string& error) {
  std::vector<std::string> scenes;
  for (const BenchResult& r : rows)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  render::RunChartOptions options;
  options.width = 1600;
  options.height = 1200;
  for (const std::string& scene : scenes) {
    std::vector<render::ChartSpec> panels;
    for (const BenchMetric& m : benchErrorMetrics()) panels.push_back(panel(scene, rows, m));
    const std::string name = "pareto_" + scene + ".png";
    if (!render::writeChartGrid(dir + "/" + name, panels, 2, options, &error)) return false;
    written.push_back(name);
  }
  return true;
}

#else

bool benchPlotsAvailable() { return false; }

bool writeBenchPlots(const std::string&, const std::vector<BenchResult>&, std::vector<std::string>&, std::string&) {
  return true;  // built without the renderer: no plots (the report says so)
}

#endif

}  // namespace haif
