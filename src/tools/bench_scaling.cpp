#include "tools/bench_scaling.h"

#include "core/growing_array.h"
#include "haif/world.h"
#include "scene/build_world.h"
#include "scene/scene_loader.h"
#include "tools/run_report.h"

#ifdef HAIF_HAVE_RENDER
#include "render/run_charts.h"
#endif

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

namespace haif {

namespace {

// Heap memory in use (MB): what the allocator has handed out and not had back, mapped blocks
// included, and the pages the largest arrays map for themselves (core/growing_array.h). Read before a world is built and after its last step, the difference is what it holds
// (the process's resident size would not do: freed memory of the last world is reused, not returned).
// NaN where the allocator does not keep these counts (a sanitizer's replaces malloc: all zero).
double heapInUseMb() {
  const struct mallinfo2 m = mallinfo2();
  const size_t heap = m.uordblks + m.hblkhd;
  const size_t bytes = heap + growingArrayMappedBytes();
  return heap > 0 ? double(bytes) / (1024.0 * 1024.0) : NAN;
}

// The random pile's cell edge is 2.2 x its largest size (0.4 m): ten layers of cells over a square.
constexpr double kPileCell = 2.2 * 0.4;
constexpr int kPileLayers = 10;

}  // namespace

std::string scalingSceneJson(const std::string& family, int bodies, int steps) {
  std::ostringstream s;
  s << "{\"name\": \"" << family << "_" << bodies << "\", \"settings\": {\"frames\": " << steps
    << ", \"sleeping\": false}, \"generators\": [{\"type\": \"ground\"}, ";
  if (family == "stacks") {
    s << "{\"type\": \"stacks\", \"count\": " << bodies << ", \"per_stack\": 10}]}";
  } else if (family == "pile") {
    const int side = int(std::ceil(std::sqrt(double(bodies) / kPileLayers)));
    const double half = 0.5 * side * kPileCell + 1e-3;
    s << "{\"type\": \"random_pile\", \"count\": " << bodies << ", \"seed\": 7, \"min\": [" << -half << ", 0.5, "
      << -half << "], \"max\": [" << half << ", " << 0.5 + kPileLayers * kPileCell + 1e-3 << ", " << half << "]}]}";
  } else {
    return "";
  }
  return s.str();
}

bool runScalingPoint(const std::string& family, int bodies, int steps, int threads, ScalingResult& out,
                     std::string& error) {
  const std::string text = scalingSceneJson(family, bodies, steps);
  if (text.empty()) {
    error = "haif bench --scaling: unknown family '" + family + "' (stacks, pile)";
    return false;
  }
  SceneDesc scene;
  const std::string where = "haif bench --scaling (" + family + ", " + std::to_string(bodies) + " bodies)";
  if (!parseSceneText(text, where, scene, error)) return false;
  scene.settings.world.threads = threads;
  const double before = heapInUseMb();
  ScalingResult r;
  r.family = family;
  r.bodies = bodies;
  r.threads = threads;
  {
    World world(scene.settings.world);
    if (!buildWorld(scene, world, error)) return false;
    std::vector<double> ms;
    ms.reserve(size_t(steps));
    for (int s = 0; s < steps; ++s) {
      world.step();
      ms.push_back(world.lastStats().totalMs);
      r.steps = s + 1;
      const Vec3& p = world.bodies().xf.back().p;
      if (!std::isfinite(p.x() + p.y() + p.z())) {
        r.nan = true;
        break;
      }
    }
    r.msMedian = quantile(ms, 0.5);
    r.msP95 = quantile(ms, 0.95);
    const double after = heapInUseMb();
    r.worldMb = std::isnan(before) || std::isnan(after) ? NAN : std::max(0.0, after - before);
  }
  out = r;
  return true;
}

double powerLawExponent(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int n = 0;
  for (size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  const double d = n * sxx - sx * sx;
  if (n < 2 || d <= 0.0) return NAN;
  return (n * sxy - sx * sy) / d;
}

std::string scalingCsv(const std::vector<ScalingResult>& rows) {
  std::ostringstream s;
  s << "family,bodies,threads,steps,ms_per_step_median,ms_per_step_p95,world_mb,nan\n";
  char line[256];
  for (const ScalingResult& r : rows) {
    std::snprintf(line, sizeof line, "%s,%d,%d,%d,%.4f,%.4f,%.1f,%d\n", r.family.c_str(), r.bodies, r.threads,
                  r.steps, r.msMedian, r.msP95, r.worldMb, r.nan ? 1 : 0);
    s << line;
  }
  return s.str();
}

namespace {

// Rows grouped by family, in the order the families first appear.
std::vector<std::pair<std::string, std::vector<const ScalingResult*>>> byFamily(const std::vector<ScalingResult>& rows) {
  std::vector<std::pair<std::string, std::vector<const ScalingResult*>>> out;
  for (const ScalingResult& r : rows) {
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& f) { return f.first == r.family; });
    if (it == out.end()) it = out.insert(out.end(), {r.family, {}});
    it->second.push_back(&r);
  }
  return out;
}

double exponentOf(const std::vector<const ScalingResult*>& rows, double ScalingResult::*field) {
  std::vector<double> x, y;
  for (const ScalingResult* r : rows) {
    if (r->nan) continue;
    x.push_back(r->bodies);
    y.push_back(r->*field);
  }
  return powerLawExponent(x, y);
}

}  // namespace

std::string scalingMarkdown(const std::vector<ScalingResult>& rows, const std::string& plot) {
  std::ostringstream s;
  s << "# haif bench --scaling\n\n"
       "Each world is generated (`stacks`: stacks of 10 unit boxes; `pile`: spheres, boxes, capsules and hulls\n"
       "in ten layers falling onto the ground), stepped at fixed 10 iterations with sleeping off, and timed\n"
       "by the engine's own step clock. `world MB` is the heap memory the world holds after its last step\n"
       "(allocator bytes in use, after minus before). The exponent k is the least-squares slope of log(cost) against log(bodies): cost ~ bodies^k\n"
       "(1 is linear).\n\n";
  s << "| family | bodies | threads | steps | ms/step (median) | ms/step (p95) | world MB |\n|---|---|---|---|---|---|---|\n";
  char line[256];
  for (const ScalingResult& r : rows) {
    char mb[32] = "n/a";
    if (!std::isnan(r.worldMb)) std::snprintf(mb, sizeof mb, "%.1f", r.worldMb);
    std::snprintf(line, sizeof line, "| %s | %d | %d | %d | %.3f | %.3f | %s |%s\n", r.family.c_str(), r.bodies,
                  r.threads, r.steps, r.msMedian, r.msP95, mb, r.nan ? " NaN" : "");
    s << line;
  }
  s << "\n| family | exponent of ms/step | exponent of world MB |\n|---|---|---|\n";
  for (const auto& [family, fr] : byFamily(rows)) {
    std::snprintf(line, sizeof line, "| %s | %.3f | %.3f |\n", family.c_str(), exponentOf(fr, &ScalingResult::msMedian),
                  exponentOf(fr, &ScalingResult::worldMb));
    s << line;
  }
  if (!plot.empty()) s << "\n![ms/step and memory against bodies](" << plot << ")\n";
  return s.str();
}

#ifdef HAIF_HAVE_RENDER

bool writeScalingPlot(const std::string& dir, const std::vector<ScalingResult>& rows, std::string& written,
                      std::string& error) {
  const render::Rgba colors[] = {{31, 119, 180, 255}, {214, 39, 40, 255}, {44, 160, 44, 255}, {148, 103, 189, 255}};
  auto panel = [&](const char* title, const char* yLabel, double ScalingResult::*field) {
    render::ChartSpec spec;
    spec.title = title;
    spec.xLabel = "bodies, log scale";
    spec.yLabel = yLabel;
    spec.logX = true;
    spec.logY = true;
    spec.legend = render::LegendCorner::Best;
    int k = 0;
    for (const auto& [family, fr] : byFamily(rows)) {
      render::ChartSeries series;
      char name[96];
      std::snprintf(name, sizeof name, "%s (k = %.2f)", family.c_str(), exponentOf(fr, field));
      series.name = name;
      series.color = colors[k++ % 4];
      series.width = 1.8f;
      series.marker = 7.f;
      for (const ScalingResult* r : fr) {
        if (r->nan || !(r->*field > 0.0)) continue;
        series.x.push_back(float(r->bodies));
        series.values.push_back(float(r->*field));
      }
      spec.series.push_back(std::move(series));
    }
    return spec;
  };
  render::RunChartOptions options;
  options.width = 1600;
  options.height = 620;
  const std::vector<render::ChartSpec> panels = {
      panel("ms per step (median) against bodies", "ms per step, log scale", &ScalingResult::msMedian),
      panel("memory the world holds against bodies", "MB, log scale", &ScalingResult::worldMb)};
  if (!render::writeChartGrid(dir + "/scaling.png", panels, 2, options, &error)) return false;
  written = "scaling.png";
  return true;
}

#else

bool writeScalingPlot(const std::string&, const std::vector<ScalingResult>&, std::string&, std::string&) {
  return true;
}

#endif

}  // namespace haif
