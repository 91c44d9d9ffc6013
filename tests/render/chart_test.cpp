// Software charts: data lands on the right pixel rows, legends and text are drawn, the run
// charts are written as PNGs of the requested size.
#include <gtest/gtest.h>

#include <filesystem>

#include "render/chart.h"
#include "render/png_io.h"
#include "render/run_charts.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

std::unique_ptr<TextRenderer> font() {
  std::string error;
  auto t = TextRenderer::create(HAIF_FONT_PATH, &error);
  EXPECT_NE(t, nullptr) << error;
  return t;
}

TEST(Chart, ConstantSeriesSitsOnItsValueRow) {
  auto text = font();
  ASSERT_TRUE(text);
  const int w = 400, h = 300;
  std::vector<uint8_t> px(static_cast<size_t>(w) * h * 4);
  Canvas canvas(px.data(), w, h);
  ChartSpec spec;
  spec.yMin = 0.f, spec.yMax = 10.f;
  spec.series.push_back({"", std::vector<float>(50, 5.f), Rgba{0, 0, 255, 255}, ChartSeries::Style::Line, 2.f});
  const ChartGeometry g = drawChart(canvas, *text, 0, 0, w, h, spec, ChartStyle{});
  ASSERT_GT(g.bottom - g.top, 100.f);
  const float expected = g.yToPixel(5.0);
  EXPECT_NEAR(expected, (g.top + g.bottom) * 0.5f, 1.0f);
  const int x = static_cast<int>((g.left + g.right) * 0.5f);
  int bestRow = -1, bestBlue = 0;
  for (int y = 0; y < h; ++y) {
    const auto p = test::at(px, w, x, y);
    const int blueness = p.b - (p.r + p.g) / 2;
    if (blueness > bestBlue) bestBlue = blueness, bestRow = y;
  }
  EXPECT_GT(bestBlue, 150);
  EXPECT_NEAR(bestRow + 0.5f, expected, 1.0f);
}

TEST(Chart, LegendTextIsDrawnInsideThePlot) {
  auto text = font();
  ASSERT_TRUE(text);
  const int w = 400, h = 300;
  ChartSpec spec;
  spec.series.push_back({"", {1.f, 2.f, 3.f}, Rgba{0, 0, 255, 255}, ChartSeries::Style::Line, 2.f});
  std::vector<uint8_t> plain(static_cast<size_t>(w) * h * 4), legend(plain.size());
  Canvas c1(plain.data(), w, h), c2(legend.data(), w, h);
  drawChart(c1, *text, 0, 0, w, h, spec, ChartStyle{});
  spec.series[0].name = "iterations";
  const ChartGeometry g = drawChart(c2, *text, 0, 0, w, h, spec, ChartStyle{});
  // Dark text pixels that only the named version has, in the top-right part of the plot.
  int textPixels = 0, elsewhere = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto a = test::at(plain, w, x, y), b = test::at(legend, w, x, y);
      if (a.r == b.r && a.g == b.g && a.b == b.b) continue;
      const bool topRight = x > (g.left + g.right) / 2 && y < (g.top + g.bottom) / 2;
      if (!topRight) ++elsewhere;
      if (topRight && b.r < 100 && b.g < 100 && b.b < 100) ++textPixels;
    }
  EXPECT_GT(textPixels, 20) << "legend text missing";
  EXPECT_EQ(elsewhere, 0);
}

TEST(Chart, PointsAtGivenXOnLogAxesLandOnTheirDecades) {
  auto text = font();
  ASSERT_TRUE(text);
  const int w = 500, h = 400;
  std::vector<uint8_t> px(static_cast<size_t>(w) * h * 4);
  Canvas canvas(px.data(), w, h);
  ChartSpec spec;
  spec.logX = spec.logY = true;
  spec.legend = LegendCorner::BottomLeft;
  ChartSeries s{"curve", {100.f, 10.f, 1.f}, Rgba{0, 0, 255, 255}, ChartSeries::Style::Line, 0.f};
  s.x = {0.1f, 1.f, 10.f};
  s.marker = 9.f;
  spec.series.push_back(s);
  const ChartGeometry g = drawChart(canvas, *text, 0, 0, w, h, spec, ChartStyle{});
  ASSERT_TRUE(g.logX && g.logY);
  // Decades are evenly spaced on both axes: x 0.1..10, y 1..100.
  EXPECT_NEAR(g.xToPixel(1.0) - g.xToPixel(0.1), g.xToPixel(10.0) - g.xToPixel(1.0), 0.01f);
  EXPECT_NEAR(g.xToPixel(0.1), g.left, 0.5f);
  EXPECT_NEAR(g.xToPixel(10.0), g.right, 0.5f);
  EXPECT_NEAR(g.yToPixel(100.0), g.top, 0.5f);
  // A blue dot at each point (markers only: width 0), and no blue half-way between two points.
  auto blue = [&](float x, float y) {
    const auto p = test::at(px, w, static_cast<int>(x), static_cast<int>(y));
    return p.b > 200 && p.r < 80 && p.g < 80;
  };
  EXPECT_TRUE(blue(g.xToPixel(0.1) + 2.f, g.yToPixel(100.0) + 2.f));  // corners: inside the plot, off the axes
  EXPECT_TRUE(blue(g.xToPixel(1.0), g.yToPixel(10.0)));
  EXPECT_TRUE(blue(g.xToPixel(10.0) - 3.f, g.yToPixel(1.0) - 3.f));
  EXPECT_FALSE(blue(g.xToPixel(std::sqrt(10.0)), g.yToPixel(std::sqrt(10.0))));
}

TEST(Chart, BestLegendCornerLeavesThePointsVisible) {
  auto text = font();
  ASSERT_TRUE(text);
  const int w = 500, h = 400;
  // Points along the top and right edges: only the bottom-left corner is free.
  ChartSpec spec;
  ChartSeries s{"", {}, Rgba{0, 0, 255, 255}, ChartSeries::Style::Line, 1.f};
  for (int i = 0; i <= 5; ++i) s.x.push_back(2.f * i), s.values.push_back(10.f);
  for (int i = 4; i >= 0; --i) s.x.push_back(10.f), s.values.push_back(2.f * i);
  s.marker = 6.f;
  spec.series.push_back(s);
  spec.legend = LegendCorner::Best;
  spec.yMax = 10.5f;  // the top row just inside the plot, where a top-corner legend would cover it
  std::vector<uint8_t> plain(static_cast<size_t>(w) * h * 4), legend(plain.size());
  Canvas c1(plain.data(), w, h), c2(legend.data(), w, h);
  drawChart(c1, *text, 0, 0, w, h, spec, ChartStyle{});
  spec.series[0].name = "a long legend entry";
  const ChartGeometry g = drawChart(c2, *text, 0, 0, w, h, spec, ChartStyle{});
  int inBottomLeft = 0, elsewhere = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto a = test::at(plain, w, x, y), b = test::at(legend, w, x, y);
      if (a.r == b.r && a.g == b.g && a.b == b.b) continue;
      const bool bottomLeft = x < (g.left + g.right) / 2 && y > (g.top + g.bottom) / 2;
      (bottomLeft ? inBottomLeft : elsewhere)++;
    }
  EXPECT_GT(inBottomLeft, 100);
  EXPECT_EQ(elsewhere, 0);
}

TEST(Chart, TextRendererDrawsGlyphsAndMeasures) {
  auto text = font();
  ASSERT_TRUE(text);
  std::vector<uint8_t> px(100 * 30 * 4, 255);
  Canvas c(px.data(), 100, 30);
  const float adv = text->draw(c, 2.f, 20.f, "HAIF", 16, Rgba{0, 0, 0, 255});
  EXPECT_NEAR(adv, text->measure("HAIF", 16), 0.01f);
  EXPECT_GT(adv, 20.f);
  int dark = 0;
  for (size_t i = 0; i < px.size(); i += 4) dark += px[i] < 80;
  EXPECT_GT(dark, 40);
  std::string error;
  EXPECT_EQ(TextRenderer::create("/nonexistent/font.ttf", &error), nullptr);
  EXPECT_NE(error.find("/nonexistent/font.ttf"), std::string::npos);
}

TEST(RunCharts, WritesThreeChartsWithBudgetLine) {
  RunSeries run;
  run.scene = "unit";
  run.iMin = 4, run.iMax = 20, run.budgetMs = 10.f;
  for (int i = 0; i < 500; ++i) {
    run.iterations.push_back(static_cast<float>(8 + i % 5));
    run.collisionMs.push_back(2.f);
    run.solveMs.push_back(4.f);
    run.error.push_back(0.5f * std::pow(0.98f, static_cast<float>(i)));  // spans decades: log axis
  }
  RunChartOptions options;
  options.width = 600, options.height = 300;
  const std::string dir = test::tempDir() + "/charts";
  std::filesystem::create_directories(dir);
  std::string error;
  ASSERT_TRUE(writeRunCharts(dir, run, options, &error)) << error;
  for (const char* name : {"iterations.png", "step_time.png", "error.png"}) {
    int w = 0, h = 0;
    std::vector<uint8_t> px;
    ASSERT_TRUE(readPng(dir + "/" + name, &w, &h, &px, &error)) << error;
    EXPECT_EQ(w, 600);
    EXPECT_EQ(h, 300);
  }
  // The budget line (red) runs across the step-time plot.
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  ASSERT_TRUE(readPng(dir + "/step_time.png", &w, &h, &px, &error));
  int bestRowCount = 0;
  for (int y = 0; y < h; ++y) {
    int count = 0;
    for (int x = 0; x < w; ++x) count += test::isRed(test::at(px, w, x, y));
    bestRowCount = std::max(bestRowCount, count);
  }
  EXPECT_GT(bestRowCount, w / 2);
  EXPECT_FALSE(writeRunCharts("/nonexistent_dir_haif", run, options, &error));
}

TEST(RunCharts, AFirstStepStallDoesNotSetTheTimeScale) {
  // 300 steps of ~3 ms under a 4 ms budget, the first one 130 ms (allocations, cold caches).
  std::vector<float> total(300);
  for (size_t i = 0; i < total.size(); ++i) total[i] = 3.f + 0.3f * static_cast<float>(i % 4);
  EXPECT_TRUE(std::isnan(robustTimeTop(total, 4.f))) << "no stall: the scale comes from the data";
  total[0] = 130.f;
  const float top = robustTimeTop(total, 4.f);
  EXPECT_GE(top, 4.f * 1.15f) << "the budget line stays on the plot";
  EXPECT_LE(top, 3.9f * 1.4f + 1e-3f);
  EXPECT_TRUE(std::isnan(robustTimeTop({1.f, 90.f, 2.f}, 4.f))) << "too few steps to call one a stall";

  RunSeries run;
  run.budgetMs = 4.f;
  run.collisionMs.assign(total.size(), 1.f);
  for (float t : total) run.solveMs.push_back(t - 1.f);
  run.totalMs = total;
  RunChartOptions options;
  options.width = 600, options.height = 300;
  const std::string path = test::tempDir() + "/stall_step_time.png";
  std::string error;
  ASSERT_TRUE(writeStepTimeChart(path, run, options, &error)) << error;
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  ASSERT_TRUE(readPng(path, &w, &h, &px, &error)) << error;
  // The budget line's row: on a 150 ms scale 4 ms would sit at the foot of the plot; on the robust
  // scale it is in its upper part.
  int budgetRow = -1, bestCount = 0;
  for (int y = 0; y < h; ++y) {
    int count = 0;
    for (int x = 0; x < w; ++x) {
      const auto p = test::at(px, w, x, y);  // the budget's red, not the solve area's orange
      count += p.r > 150 && p.g < 100 && p.b < 100;
    }
    if (count > bestCount) bestCount = count, budgetRow = y;
  }
  ASSERT_GT(bestCount, w / 2);
  EXPECT_LT(budgetRow, h / 2);
}

}  // namespace
}  // namespace haif::render
