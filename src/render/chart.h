// A small line/area chart drawn in software into a rectangle of a Canvas: axes with "nice" ticks
// (linear or log10 on either axis), tick labels, axis titles, a legend, line series (evenly spaced
// or at given x, with optional point markers), stacked areas and horizontal reference lines.
// The overlay panel, the standalone run charts and the benchmark's Pareto plots use it.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "render/canvas.h"
#include "render/text_renderer.h"

namespace haif::render {

/// One data series; values[i] sits at x = ChartSpec::xStart + i * ChartSpec::xStep, or at x[i]
/// when `x` is given.
struct ChartSeries {
  enum class Style { Line, StackedArea };
  std::string name;            ///< legend text (empty: not in the legend)
  std::vector<float> values;   ///< data (non-finite values leave gaps)
  Rgba color;                  ///< line or fill colour
  Style style = Style::Line;   ///< StackedArea series stack on each other in the order given
  float width = 2.f;           ///< line width in pixels (Line only; <= 0: markers only)
  std::vector<float> x = {};   ///< x of each value, joined in the order given (Line only; empty: evenly spaced)
  float marker = 0.f;          ///< diameter in pixels of a dot at each point (0: none)
  bool hollow = false;         ///< markers drawn as rings
  bool dashed = false;         ///< dashed line
};

/// A horizontal reference line across the plot (budget, I_min, ...).
struct ChartHLine {
  std::string name;      ///< legend text
  float value = 0.f;     ///< y value
  Rgba color;            ///< colour
  bool dashed = true;    ///< dashed or solid
};

/// Where the legend box sits inside the plot. Best: the corner that hides the fewest points of
/// series placed at given x (others count as top right).
enum class LegendCorner { TopRight, TopLeft, BottomLeft, BottomRight, Best };

/// What to plot.
struct ChartSpec {
  std::string title;                 ///< drawn above the plot
  std::string xLabel, yLabel;        ///< axis titles with units (ignored in compact style)
  std::vector<ChartSeries> series;   ///< drawn areas first, then lines
  std::vector<ChartHLine> hlines;    ///< reference lines
  bool logY = false;                 ///< log10 y axis (non-positive values are skipped)
  bool logX = false;                 ///< log10 x axis (series with x only; non-positive x skipped)
  LegendCorner legend = LegendCorner::TopRight;  ///< where the legend box goes
  float yMin = NAN, yMax = NAN;      ///< fixed y range; NaN = from the data
  float xStart = 0.f, xStep = 1.f;   ///< x of the first value and spacing
};

/// Look of a chart.
struct ChartStyle {
  Rgba background{255, 255, 255, 255};  ///< fill of the whole rectangle (alpha < 255: translucent)
  Rgba plotBackground{250, 250, 252, 255};
  Rgba axis{90, 90, 100, 255};
  Rgba grid{225, 227, 232, 255};
  Rgba text{30, 30, 35, 255};
  int fontSize = 14;      ///< tick labels and legend; titles are a bit larger
  bool compact = false;   ///< overlay style: no axis titles, fewer ticks, legend in the title row
};

/// Where the plot landed, to map data to pixels (tests use it).
struct ChartGeometry {
  float left = 0.f, top = 0.f, right = 0.f, bottom = 0.f;  ///< plot area in canvas pixels
  double xLo = 0.0, xHi = 1.0, yLo = 0.0, yHi = 1.0;       ///< data range shown (log10 of it on log axes)
  bool logX = false, logY = false;
  float yToPixel(double y) const;
  float xToPixel(double x) const;
};

/// The top of a time axis that a one-off stall does not set (the first step's allocations and cold
/// caches, a page fault, the OS): 1.4 times the 99th percentile of `values` (the highest value left
/// out once there are 8), never below 1.15 times `budget` so its line shows. NaN (the axis from the
/// data) when every value fits under it anyway; values above it run off the top of the plot.
float robustTimeTop(std::vector<float> values, float budget);

/// Draws spec into rect [x0,x1) x [y0,y1) of canvas.
ChartGeometry drawChart(Canvas& canvas, TextRenderer& text, int x0, int y0, int x1, int y1,
                        const ChartSpec& spec, const ChartStyle& style);

}  // namespace haif::render
