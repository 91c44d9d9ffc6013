#include "render/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/chart.h"
#include "render/chart_colors.h"

namespace haif::render {
namespace {

// Layout in "720p pixels", scaled with the image height so the panel reads the same at any size.
struct Layout {
  float scale;
  int font, lineH, pad, chartH, width;
};

Layout layoutFor(int imageHeight) {
  Layout l;
  l.scale = std::clamp(imageHeight / 720.f, 0.5f, 3.f);
  l.font = std::max(9, static_cast<int>(std::lround(13.f * l.scale)));
  l.lineH = static_cast<int>(std::lround(l.font * 1.45f));
  l.pad = static_cast<int>(std::lround(10.f * l.scale));
  l.chartH = static_cast<int>(std::lround(105.f * l.scale));
  l.width = static_cast<int>(std::lround(430.f * l.scale));
  return l;
}

std::vector<std::string> textLines(const Overlay& o, ViewMode mode) {
  char buf[256];
  std::vector<std::string> lines;
  std::snprintf(buf, sizeof buf, "scene: %s    mode: %s", o.scene.empty() ? "-" : o.scene.c_str(),
                o.mode.empty() ? "-" : o.mode.c_str());
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof buf, "bodies: %d    islands: %d    view: %s", o.bodies, o.islands,
                viewModeName(mode));
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof buf, "step %lld    %.2f ms/step", static_cast<long long>(o.step), o.msPerStep);
  lines.emplace_back(buf);
  for (const auto& e : o.extraLines) lines.push_back(e);
  return lines;
}

// The most recent `window` entries of v.
std::vector<float> tail(const std::vector<float>& v, int window) {
  const size_t n = std::min(v.size(), static_cast<size_t>(std::max(window, 1)));
  return std::vector<float>(v.end() - static_cast<std::ptrdiff_t>(n), v.end());
}

}  // namespace

const char* viewModeName(ViewMode mode) {
  switch (mode) {
    case ViewMode::Island: return "island";
    case ViewMode::Sleep: return "sleep";
    case ViewMode::Heat: return "heat";
    case ViewMode::Normal:
    default: return "normal";
  }
}

PanelRect overlayPanelRect(const Overlay& o, int w, int h) {
  const Layout l = layoutFor(h);
  const int lines = 3 + static_cast<int>(o.extraLines.size());
  const int pw = std::min(l.width, w);
  const int ph = std::min(l.pad * 2 + lines * l.lineH + 2 * (l.chartH + l.pad / 2), h);
  const int margin = static_cast<int>(std::lround(12.f * l.scale));
  const bool right = o.corner == Corner::TopRight || o.corner == Corner::BottomRight;
  const bool bottom = o.corner == Corner::BottomLeft || o.corner == Corner::BottomRight;
  PanelRect r;
  r.x0 = std::max(0, right ? w - margin - pw : margin);
  r.y0 = std::max(0, bottom ? h - margin - ph : margin);
  r.x1 = std::min(w, r.x0 + pw);
  r.y1 = std::min(h, r.y0 + ph);
  return r;
}

void drawOverlay(Canvas& canvas, TextRenderer& text, const Overlay& o, ViewMode mode) {
  const Layout l = layoutFor(canvas.height());
  const PanelRect r = overlayPanelRect(o, canvas.width(), canvas.height());
  canvas.setClip(r.x0, r.y0, r.x1, r.y1);
  canvas.fillRect(static_cast<float>(r.x0), static_cast<float>(r.y0), static_cast<float>(r.x1),
                  static_cast<float>(r.y1), Rgba{16, 20, 28, 170});

  const Rgba textColor{238, 240, 245, 255};
  float y = static_cast<float>(r.y0 + l.pad);
  for (const auto& line : textLines(o, mode)) {
    text.draw(canvas, static_cast<float>(r.x0 + l.pad), y + text.ascent(l.font), line, l.font, textColor);
    y += l.lineH;
  }

  ChartStyle style;
  style.compact = true;
  style.fontSize = std::max(8, l.font - 2);
  style.background = Rgba{0, 0, 0, 0};
  style.plotBackground = Rgba{255, 255, 255, 18};
  style.axis = Rgba{190, 195, 205, 220};
  style.grid = Rgba{255, 255, 255, 40};
  style.text = textColor;

  const int cx0 = r.x0 + l.pad / 2, cx1 = r.x1 - l.pad / 2;
  ChartSpec iter;
  iter.title = "iterations";
  iter.series.push_back({"I", tail(o.iterations, o.window), Rgba{110, 180, 255, 255}, ChartSeries::Style::Line, 1.6f});
  if (o.iMin > 0.f) iter.hlines.push_back({"I_min", o.iMin, Rgba{120, 220, 120, 255}, true});
  if (o.iMax > 0.f) iter.hlines.push_back({"I_max", o.iMax, Rgba{255, 110, 100, 255}, true});
  int cy = static_cast<int>(y) + l.pad / 2;
  // Charts are clamped to the panel so nothing outside overlayPanelRect is ever touched.
  if (cy + 8 < r.y1) drawChart(canvas, text, cx0, cy, cx1, std::min(cy + l.chartH, r.y1), iter, style);

  ChartSpec time;
  time.title = "step ms";
  time.series.push_back({"collision", tail(o.collisionMs, o.window), chart_colors::kCollision,
                         ChartSeries::Style::StackedArea, 0.f});
  time.series.push_back({"solve", tail(o.solveMs, o.window), chart_colors::kSolve,
                         ChartSeries::Style::StackedArea, 0.f});
  if (o.budgetMs > 0.f) time.hlines.push_back({"budget", o.budgetMs, Rgba{255, 90, 90, 255}, false});
  {
    std::vector<float> total = time.series[0].values;
    for (size_t i = 0; i < total.size() && i < time.series[1].values.size(); ++i) total[i] += time.series[1].values[i];
    time.yMax = robustTimeTop(std::move(total), o.budgetMs);
  }
  cy += l.chartH + l.pad / 2;
  if (cy + 8 < r.y1) drawChart(canvas, text, cx0, cy, cx1, std::min(cy + l.chartH, r.y1), time, style);
  canvas.resetClip();
}

}  // namespace haif::render
