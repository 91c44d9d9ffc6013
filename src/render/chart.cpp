#include "render/chart.h"

#include <algorithm>
#include <cstdio>

namespace haif::render {
namespace {

// 1-2-5 step that gives about `target` intervals over span.
double niceStep(double span, int target) {
  const double raw = span / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return mag * (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0);
}

std::string formatTick(double v, double step) {
  char buf[32];
  if (std::fabs(v) < step * 1e-6) v = 0.0;
  const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string formatDecade(int e) {
  char buf[32];
  if (e >= -3 && e <= 4)
    std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, e));
  else
    std::snprintf(buf, sizeof buf, "1e%d", e);
  return buf;
}

struct Tick {
  double value;
  std::string label;
};

// Linearly interpolated sample at fractional index f (NaN outside or across gaps).
float sampleAt(const std::vector<float>& v, double f) {
  if (v.empty() || f < 0.0 || f > static_cast<double>(v.size() - 1)) return NAN;
  const size_t i = static_cast<size_t>(f);
  if (i + 1 >= v.size()) return v.back();
  const float t = static_cast<float>(f - static_cast<double>(i));
  return v[i] + (v[i + 1] - v[i]) * t;
}

}  // namespace

float ChartGeometry::yToPixel(double y) const {
  double t;
  if (logY)
    t = (std::log10(std::max(y, 1e-300)) - yLo) / (yHi - yLo);
  else
    t = (y - yLo) / (yHi - yLo);
  return static_cast<float>(bottom - t * (bottom - top));
}

float ChartGeometry::xToPixel(double x) const {
  const double v = logX ? std::log10(std::max(x, 1e-300)) : x;
  return static_cast<float>(left + (v - xLo) / (xHi - xLo) * (right - left));
}

float robustTimeTop(std::vector<float> values, float budget) {
  values.erase(std::remove_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }),
               values.end());
  const size_t n = values.size();
  if (n < 8) return NAN;
  const auto p99 = values.begin() + std::ptrdiff_t(std::min(n * 99 / 100, n - 2));
  std::nth_element(values.begin(), p99, values.end());
  const float top = std::max(*p99 * 1.4f, budget * 1.15f);
  return *std::max_element(values.begin(), values.end()) > top ? top : NAN;
}

ChartGeometry drawChart(Canvas& canvas, TextRenderer& text, int x0, int y0, int x1, int y1,
                        const ChartSpec& spec, const ChartStyle& style) {
  canvas.setClip(x0, y0, x1, y1);
  canvas.fillRect(static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1),
                  static_cast<float>(y1), style.background);
  const int fs = style.fontSize;
  const int titleFs = style.compact ? fs : fs + 4;

  // ---- data ranges ----
  size_t n = 0;
  for (const auto& s : spec.series) n = std::max(n, s.values.size());
  ChartGeometry g;
  g.logY = spec.logY;
  g.xLo = spec.xStart;
  g.xHi = spec.xStart + spec.xStep * static_cast<double>(n > 1 ? n - 1 : 1);
  // Series placed at given x set the x range themselves.
  double xMin = INFINITY, xMax = -INFINITY;
  for (const auto& s : spec.series)
    for (size_t i = 0; i < s.x.size() && i < s.values.size(); ++i)
      if (std::isfinite(s.x[i]) && (!spec.logX || s.x[i] > 0.f) && std::isfinite(s.values[i]))
        xMin = std::min(xMin, double(s.x[i])), xMax = std::max(xMax, double(s.x[i]));
  const bool placed = xMin <= xMax;
  g.logX = spec.logX && placed;
  if (g.logX) {
    g.xLo = std::floor(std::log10(xMin));
    g.xHi = std::ceil(std::log10(xMax));
    if (g.xHi <= g.xLo) g.xHi = g.xLo + 1.0;
  } else if (placed) {
    const double pad = xMax > xMin ? 0.05 * (xMax - xMin) : 1.0;
    g.xLo = xMin - pad, g.xHi = xMax + pad;
  }

  double lo = INFINITY, hi = -INFINITY;
  auto take = [&](double v) {
    if (!std::isfinite(v) || (spec.logY && v <= 0.0)) return;
    lo = std::min(lo, v), hi = std::max(hi, v);
  };
  std::vector<double> stackTop(n, 0.0);
  for (const auto& s : spec.series) {
    for (size_t i = 0; i < s.values.size(); ++i) {
      if (s.style == ChartSeries::Style::StackedArea) {
        if (std::isfinite(s.values[i])) stackTop[i] += s.values[i];
        take(stackTop[i]);
      } else {
        take(s.values[i]);
      }
    }
  }
  for (const auto& h : spec.hlines) take(h.value);
  if (!(lo <= hi)) lo = spec.logY ? 1.0 : 0.0, hi = spec.logY ? 10.0 : 1.0;

  std::vector<Tick> yTicks;
  if (spec.logY) {
    int eLo = static_cast<int>(std::floor(std::log10(lo))), eHi = static_cast<int>(std::ceil(std::log10(hi)));
    if (eHi <= eLo) eHi = eLo + 1;
    g.yLo = eLo, g.yHi = eHi;
    const int every = std::max(1, (eHi - eLo + (style.compact ? 2 : 6)) / (style.compact ? 3 : 7));
    for (int e = eLo; e <= eHi; e += every) yTicks.push_back({std::pow(10.0, e), formatDecade(e)});
  } else {
    if (!spec.logY) lo = std::min(lo, 0.0);  // times and counts read best from zero
    if (std::isfinite(spec.yMin)) lo = spec.yMin;
    if (std::isfinite(spec.yMax)) hi = spec.yMax;
    if (hi <= lo) hi = lo + 1.0;
    const double step = niceStep(hi - lo, style.compact ? 3 : 6);
    if (!std::isfinite(spec.yMin)) lo = std::floor(lo / step + 1e-9) * step;
    if (!std::isfinite(spec.yMax)) {
      const double top = hi;
      hi = std::ceil(hi / step - 1e-9) * step;
      // A series at the top of the data (a fixed run's iterations at I_max) would lie on the plot's
      // frame and vanish into it: leave it some headroom.
      if (hi - top < 0.04 * (hi - lo)) hi += 0.08 * (hi - lo);
    }
    if (hi <= lo) hi = lo + step;
    g.yLo = lo, g.yHi = hi;
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-6; v += step)
      yTicks.push_back({v, formatTick(v, step)});
  }

  // ---- layout ----
  float tickW = 0.f;
  for (const auto& t : yTicks) tickW = std::max(tickW, text.measure(t.label, fs));
  const float pad = style.compact ? 4.f : 12.f;
  g.left = x0 + pad + tickW + 6.f + (style.compact ? 0.f : fs * 1.6f);
  g.right = x1 - pad - (style.compact ? 2.f : 8.f);
  g.top = y0 + pad + titleFs * 1.35f;
  g.bottom = y1 - pad - (style.compact ? 2.f : fs * 3.0f);
  if (g.right <= g.left + 4.f || g.bottom <= g.top + 4.f) {
    canvas.resetClip();
    return g;
  }

  canvas.fillRect(g.left, g.top, g.right, g.bottom, style.plotBackground);
  for (const auto& t : yTicks) {
    const float y = g.yToPixel(t.value);
    canvas.line(g.left, y, g.right, y, 1.f, style.grid);
    text.draw(canvas, g.left - 6.f - text.measure(t.label, fs), y + text.ascent(fs) * 0.5f, t.label,
              fs, style.text);
  }
  if (!style.compact && g.logX) {
    // Decades labelled; 2 and 5 labelled too when there are few decades; 2..9 as light grid.
    const int decades = static_cast<int>(g.xHi - g.xLo);
    for (int e = static_cast<int>(g.xLo); e <= static_cast<int>(g.xHi); ++e)
      for (int m = 1; m <= 9; ++m) {
        const double v = m * std::pow(10.0, e);
        if (std::log10(v) > g.xHi + 1e-9) break;
        const float x = g.xToPixel(v);
        canvas.line(x, g.top, x, g.bottom, m == 1 ? 1.f : 0.6f, style.grid);
        if (m == 1 || (decades <= 2 && (m == 2 || m == 5))) {
          const std::string label = m == 1 ? formatDecade(e) : formatTick(v, std::pow(10.0, e));
          text.draw(canvas, x - text.measure(label, fs) * 0.5f, g.bottom + 6.f + text.ascent(fs), label, fs,
                    style.text);
        }
      }
  } else if (!style.compact) {
    const double xs = niceStep(g.xHi - g.xLo, 8);
    for (double v = std::ceil(g.xLo / xs - 1e-9) * xs; v <= g.xHi + xs * 1e-6; v += xs) {
      const float x = g.xToPixel(v);
      canvas.line(x, g.top, x, g.bottom, 1.f, style.grid);
      const std::string label = formatTick(v, xs);
      text.draw(canvas, x - text.measure(label, fs) * 0.5f, g.bottom + 6.f + text.ascent(fs), label,
                fs, style.text);
    }
  }

  // ---- data, clipped to the plot ----
  canvas.setClip(static_cast<int>(std::floor(g.left)), static_cast<int>(std::floor(g.top)),
                 static_cast<int>(std::ceil(g.right)), static_cast<int>(std::ceil(g.bottom)));
  const double idxPerPx = (g.xHi - g.xLo) / spec.xStep / std::max(1.f, g.right - g.left);
  for (int px = static_cast<int>(g.left); px < static_cast<int>(std::ceil(g.right)); ++px) {
    const double f = (px + 0.5 - g.left) * idxPerPx;
    double base = 0.0;
    for (const auto& s : spec.series) {
      if (s.style != ChartSeries::Style::StackedArea) continue;
      const float v = sampleAt(s.values, f);
      if (!std::isfinite(v)) continue;
      canvas.verticalSpan(px, g.yToPixel(base + v), g.yToPixel(base), s.color);
      base += v;
    }
  }
  for (const auto& h : spec.hlines) {
    const float y = g.yToPixel(h.value);
    if (h.dashed)
      canvas.dashedLine(g.left, y, g.right, y, 1.5f, 7.f, 5.f, h.color);
    else
      canvas.line(g.left, y, g.right, y, 1.5f, h.color);
  }
  auto marker = [&](float x, float y, const ChartSeries& s) {
    if (s.marker <= 0.f) return;
    if (!s.hollow) {
      canvas.line(x, y, x, y, s.marker, s.color);
      return;
    }
    const float r = 0.5f * s.marker;
    const int segments = 16;
    for (int k = 0; k < segments; ++k) {
      const float a0 = 2.f * 3.14159265f * k / segments, a1 = 2.f * 3.14159265f * (k + 1) / segments;
      canvas.line(x + r * std::cos(a0), y + r * std::sin(a0), x + r * std::cos(a1), y + r * std::sin(a1), 1.6f,
                  s.color);
    }
  };
  auto valid = [&](float x, float y) {
    return std::isfinite(x) && std::isfinite(y) && (!g.logX || x > 0.f) && (!spec.logY || y > 0.f);
  };
  for (const auto& s : spec.series) {
    if (s.style != ChartSeries::Style::Line || s.x.empty()) continue;
    const size_t m = std::min(s.x.size(), s.values.size());
    for (size_t i = 0; s.width > 0.f && i + 1 < m; ++i) {
      if (!valid(s.x[i], s.values[i]) || !valid(s.x[i + 1], s.values[i + 1])) continue;
      const float xa = g.xToPixel(s.x[i]), ya = g.yToPixel(s.values[i]);
      const float xb = g.xToPixel(s.x[i + 1]), yb = g.yToPixel(s.values[i + 1]);
      if (s.dashed)
        canvas.dashedLine(xa, ya, xb, yb, s.width, 6.f, 4.f, s.color);
      else
        canvas.line(xa, ya, xb, yb, s.width, s.color);
    }
    for (size_t i = 0; i < m; ++i)
      if (valid(s.x[i], s.values[i])) marker(g.xToPixel(s.x[i]), g.yToPixel(s.values[i]), s);
  }
  for (const auto& s : spec.series) {
    if (s.style != ChartSeries::Style::Line || !s.x.empty()) continue;
    const size_t m = s.values.size();
    auto X = [&](size_t i) { return g.xToPixel(spec.xStart + spec.xStep * static_cast<double>(i)); };
    if (static_cast<double>(m) > 2.0 * (g.right - g.left)) {
      // Denser than the pixels: draw each column's min..max so spikes stay visible.
      float prevY = NAN;
      for (int px = static_cast<int>(g.left); px < static_cast<int>(g.right); ++px) {
        const size_t a = static_cast<size_t>(std::max(0.0, (px - g.left) * idxPerPx));
        const size_t b = std::min(m, static_cast<size_t>((px + 1 - g.left) * idxPerPx) + 1);
        float mn = INFINITY, mx = -INFINITY, sum = 0.f;
        int cnt = 0;
        for (size_t i = a; i < b; ++i)
          if (std::isfinite(s.values[i]) && (!spec.logY || s.values[i] > 0.f))
            mn = std::min(mn, s.values[i]), mx = std::max(mx, s.values[i]), sum += s.values[i], ++cnt;
        if (!cnt) {
          prevY = NAN;
          continue;
        }
        const float yMean = g.yToPixel(sum / cnt);
        canvas.line(px + 0.5f, g.yToPixel(mn), px + 0.5f, g.yToPixel(mx), 1.f, s.color);
        if (std::isfinite(prevY)) canvas.line(px - 0.5f, prevY, px + 0.5f, yMean, s.width, s.color);
        prevY = yMean;
      }
    } else {
      for (size_t i = 0; i + 1 < m; ++i) {
        const float a = s.values[i], b = s.values[i + 1];
        if (!std::isfinite(a) || !std::isfinite(b) || (spec.logY && (a <= 0.f || b <= 0.f))) continue;
        canvas.line(X(i), g.yToPixel(a), X(i + 1), g.yToPixel(b), s.width, s.color);
      }
      if (m == 1 && std::isfinite(s.values[0]))
        canvas.line(g.left, g.yToPixel(s.values[0]), g.right, g.yToPixel(s.values[0]), s.width, s.color);
    }
  }
  canvas.setClip(x0, y0, x1, y1);

  // ---- axes, titles ----
  canvas.line(g.left, g.bottom, g.right, g.bottom, 1.2f, style.axis);
  canvas.line(g.left, g.top, g.left, g.bottom, 1.2f, style.axis);
  const float titleBase = y0 + pad + text.ascent(titleFs);
  const float titleEnd = x0 + pad + text.draw(canvas, x0 + pad, titleBase, spec.title, titleFs, style.text);
  if (!style.compact) {
    text.draw(canvas, (g.left + g.right) * 0.5f - text.measure(spec.xLabel, fs) * 0.5f,
              y1 - pad - 2.f, spec.xLabel, fs, style.text);
    text.drawVertical(canvas, x0 + pad + text.ascent(fs) + 1.f,
                      (g.top + g.bottom) * 0.5f + text.measure(spec.yLabel, fs) * 0.5f, spec.yLabel, fs,
                      style.text);
  }

  // ---- legend: inside the plot (top right), or on the title row when compact ----
  struct Entry {
    std::string name;
    Rgba color;
    int kind;                         // 0 line, 1 area, 2 dashed, 3 no line (markers only)
    const ChartSeries* series = nullptr;  // for its marker
  };
  std::vector<Entry> entries;
  for (const auto& s : spec.series) {
    if (s.name.empty()) continue;
    const int kind = s.style != ChartSeries::Style::Line ? 1 : s.width <= 0.f ? 3 : s.dashed ? 2 : 0;
    entries.push_back({s.name, s.color, kind, &s});
  }
  for (const auto& h : spec.hlines)
    if (!h.name.empty()) entries.push_back({h.name, h.color, h.dashed ? 2 : 0, nullptr});
  if (!entries.empty()) {
    const float sw = fs * 1.6f, gap = fs * 0.5f;
    auto swatch = [&](float x, float yMid, const Entry& e) {
      if (e.kind == 1)
        canvas.fillRect(x, yMid - fs * 0.35f, x + sw, yMid + fs * 0.35f, e.color);
      else if (e.kind == 2)
        canvas.dashedLine(x, yMid, x + sw, yMid, 2.f, 5.f, 3.f, e.color);
      else if (e.kind == 0)
        canvas.line(x, yMid, x + sw, yMid, 2.f, e.color);
      if (e.series) marker(x + sw * 0.5f, yMid, *e.series);
    };
    if (style.compact) {
      float x = titleEnd + fs;
      for (const auto& e : entries) {
        swatch(x, titleBase - text.ascent(fs) * 0.4f, e);
        x += sw + 4.f;
        x += text.draw(canvas, x, titleBase, e.name, fs, style.text) + gap * 1.5f;
      }
    } else {
      float w = 0.f;
      for (const auto& e : entries) w = std::max(w, text.measure(e.name, fs));
      const float lineH = fs * 1.45f;
      const float bw = sw + 8.f + w + 2.f * gap, bh = lineH * entries.size() + gap;
      // Corner boxes: top right, top left, bottom left, bottom right.
      const float cx[4] = {g.right - bw - 8.f, g.left + 8.f, g.left + 8.f, g.right - bw - 8.f};
      const float cy[4] = {g.top + 8.f, g.top + 8.f, g.bottom - bh - 8.f, g.bottom - bh - 8.f};
      int corner = static_cast<int>(spec.legend);
      if (spec.legend == LegendCorner::Best) {
        // Count the placed points and line samples each corner box would cover; the first least wins.
        int hidden[4] = {0, 0, 0, 0};
        auto cover = [&](float px, float py) {
          for (int k = 0; k < 4; ++k) hidden[k] += px >= cx[k] && px <= cx[k] + bw && py >= cy[k] && py <= cy[k] + bh;
        };
        for (const auto& s : spec.series) {
          const size_t m = std::min(s.x.size(), s.values.size());
          for (size_t i = 0; i < m; ++i) {
            if (!valid(s.x[i], s.values[i])) continue;
            const float xa = g.xToPixel(s.x[i]), ya = g.yToPixel(s.values[i]);
            cover(xa, ya);
            cover(xa, ya);  // a point weighs more than a piece of line
            if (i + 1 < m && s.width > 0.f && valid(s.x[i + 1], s.values[i + 1]))
              for (int t = 1; t < 8; ++t)
                cover(xa + (g.xToPixel(s.x[i + 1]) - xa) * t / 8.f, ya + (g.yToPixel(s.values[i + 1]) - ya) * t / 8.f);
          }
        }
        corner = static_cast<int>(std::min_element(hidden, hidden + 4) - hidden);
      }
      const float bx = cx[corner], by = cy[corner];
      canvas.fillRect(bx, by, bx + bw, by + bh, Rgba{255, 255, 255, 225});
      canvas.line(bx, by, bx + bw, by, 1.f, style.grid);
      canvas.line(bx, by + bh, bx + bw, by + bh, 1.f, style.grid);
      canvas.line(bx, by, bx, by + bh, 1.f, style.grid);
      canvas.line(bx + bw, by, bx + bw, by + bh, 1.f, style.grid);
      for (size_t i = 0; i < entries.size(); ++i) {
        const float base = by + gap * 0.5f + lineH * (i + 0.5f) + text.ascent(fs) * 0.5f;
        swatch(bx + gap, base - text.ascent(fs) * 0.5f, entries[i]);
        text.draw(canvas, bx + gap + sw + 8.f, base, entries[i].name, fs, style.text);
      }
    }
  }
  canvas.resetClip();
  return g;
}

}  // namespace haif::render
