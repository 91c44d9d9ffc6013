#include "app/comparison_clip.h"

#ifdef HAIF_HAVE_RENDER
#include "render/chart.h"
#include "render/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace haif {

namespace {

// The two sides' colours, used for their label bars and their lines in the strip.
const render::Rgba kSideColour[2] = {{77, 163, 255, 255}, {255, 159, 64, 255}};
const render::Rgba kPanel{24, 28, 36, 255};
const render::Rgba kText{236, 238, 243, 255};
const render::Rgba kDimText{160, 167, 180, 255};
const char* kSideName[2] = {"left", "right"};

float uiScale(int height) { return std::clamp(height / 720.f, 0.5f, 3.f); }

// `values` followed by NaN up to `total` entries, so the x axis spans the whole clip from the start.
std::vector<float> paddedTo(const std::vector<float>& values, int total) {
  std::vector<float> v = values;
  if (int(v.size()) < total) v.resize(size_t(total), NAN);
  return v;
}

}  // namespace

bool ComparisonClip::open(const std::string& scenePath, const std::string& leftSpec, const std::string& rightSpec,
                          const ComparisonOptions& options, std::string& error) {
  opt_ = options;
  const float s = uiScale(opt_.height);
  labelH_ = std::max(18, int(std::lround(34.f * s)));
  stripH_ = std::max(60, int(std::lround(opt_.height * 0.25f)));
  sideH_ = opt_.height - labelH_ - stripH_;
  sideW_[0] = opt_.width / 2 - 1;  // a 2-pixel divider between the halves
  sideW_[1] = opt_.width - opt_.width / 2 - 1;
  if (sideH_ < 32 || sideW_[1] < 32) {
    error = "frame " + std::to_string(opt_.width) + "x" + std::to_string(opt_.height) +
            " is too small for two sides and the chart strip (at least 128x200)";
    return false;
  }
  const std::string specs[2] = {leftSpec, rightSpec};
  for (int i = 0; i < 2; ++i) {
    side_[i] = makeSimulatedScene(scenePath, specs[i], opt_.threads, error);
    if (!side_[i]) {
      error = std::string(kSideName[i]) + " side: " + error;
      return false;
    }
  }
  for (int i = 0; i < 2; ++i) {
    render::RendererOptions ro;
    ro.width = sideW_[i];
    ro.height = sideH_;
    renderer_[i] = render::Renderer::create(ro, &error);
    if (!renderer_[i]) {
      error = "renderer: " + error;
      return false;
    }
    if (!side_[i]->prepare(*renderer_[i], error)) {
      error = scenePath + ": " + error;
      return false;
    }
    input_[i].mode = opt_.view;
    input_[i].overlay.enabled = opt_.overlay;
  }
  text_ = render::TextRenderer::create(render::RendererOptions{}.fontPath, &error);
  if (!text_) return false;
  const int sceneFrames = std::max(1, side_[0]->sceneFrames() / std::max(1, opt_.frameEvery));
  frames_ = opt_.frames > 0 ? opt_.frames : sceneFrames;
  totalSteps_ = frames_ * std::max(1, opt_.frameEvery);
  for (int i = 0; i < 2; ++i)
    if (!checkStepsAvailable(*side_[i], totalSteps_, error)) {
      error = std::string(kSideName[i]) + " side: " + error;
      return false;
    }
  emitted_ = 0;
  return true;
}

bool ComparisonClip::next(std::vector<uint8_t>& rgba, std::string& error) {
  if (emitted_ >= frames_) {
    error = "comparison: no frames left";
    return false;
  }
  // Both sides step in lockstep so every frame shows them at the same simulated time; the sink
  // encodes while the frames are drawn, not beside the steps.
  {
    const EncodingHold hold(holdWhileStepping_);
    for (int k = 0; k < opt_.frameEvery; ++k)
      for (int i = 0; i < 2; ++i)
        if (!side_[i]->step(error)) {
          error = std::string(kSideName[i]) + " side: " + error;
          return false;
        }
  }
  const int w = opt_.width;
  rgba.assign(size_t(w) * size_t(opt_.height) * 4, 0);
  render::Canvas canvas(rgba.data(), w, opt_.height);
  canvas.clear(kPanel);
  for (int i = 0; i < 2; ++i) {
    side_[i]->buildFrame(input_[i]);
    if (!renderer_[i]->render(input_[i], pixels_[i], &error)) {
      error = std::string(kSideName[i]) + " side: rendering: " + error;
      return false;
    }
    const int x0 = i == 0 ? 0 : w / 2 + 1;
    const size_t rowBytes = size_t(sideW_[i]) * 4;
    for (int y = 0; y < sideH_; ++y)
      std::memcpy(&rgba[(size_t(labelH_ + y) * size_t(w) + size_t(x0)) * 4], &pixels_[i][size_t(y) * rowBytes],
                  rowBytes);
  }
  drawLabels(canvas);
  drawStrip(canvas);
  ++emitted_;
  return true;
}

void ComparisonClip::drawLabels(render::Canvas& canvas) {
  const float s = uiScale(opt_.height);
  const int big = std::max(9, int(std::lround(16.f * s))), small = std::max(8, int(std::lround(13.f * s)));
  const float bar = std::max(2.f, std::round(3.f * s)), pad = std::round(10.f * s);
  for (int i = 0; i < 2; ++i) {
    const float x0 = i == 0 ? 0.f : float(opt_.width / 2 + 1), x1 = x0 + float(sideW_[i]);
    canvas.fillRect(x0, float(labelH_) - bar, x1, float(labelH_), kSideColour[i]);
    const float base = (float(labelH_) - bar) * 0.5f + text_->ascent(big) * 0.5f;
    canvas.setClip(int(x0), 0, int(x1), labelH_);
    const float adv = text_->draw(canvas, x0 + pad, base, side_[i]->spec(), big, kText);
    text_->draw(canvas, x0 + pad + adv + big * 0.8f, base, side_[i]->description(), small, kDimText);
    canvas.resetClip();
  }
}

void ComparisonClip::drawStrip(render::Canvas& canvas) {
  const float s = uiScale(opt_.height);
  const int y0 = opt_.height - stripH_, w = opt_.width;
  canvas.fillRect(0.f, float(y0), float(w), float(opt_.height), kPanel);
  canvas.fillRect(0.f, float(y0), float(w), float(y0) + 1.f, render::Rgba{70, 76, 90, 255});
  render::ChartStyle style;
  style.compact = true;
  style.fontSize = std::max(8, int(std::lround(12.f * s)));
  style.background = render::Rgba{0, 0, 0, 0};
  style.plotBackground = render::Rgba{255, 255, 255, 14};
  style.axis = render::Rgba{170, 176, 190, 255};
  style.grid = render::Rgba{255, 255, 255, 34};
  style.text = kText;

  render::ChartSpec time, iters;
  time.title = "step time (ms)";
  iters.title = "solver iterations per step";
  for (int i = 0; i < 2; ++i) {
    const StepHistory& h = side_[i]->history();
    time.series.push_back({side_[i]->spec(), paddedTo(h.totalMs, totalSteps_), kSideColour[i],
                           render::ChartSeries::Style::Line, 1.4f * std::max(1.f, s)});
    iters.series.push_back({side_[i]->spec(), paddedTo(h.iterations, totalSteps_), kSideColour[i],
                            render::ChartSeries::Style::Line, 1.6f * std::max(1.f, s)});
    if (side_[i]->budgetMs() > 0.f)
      time.hlines.push_back({side_[i]->spec() + " budget", side_[i]->budgetMs(), kSideColour[i], true});
  }
  // A one-off stall (the first step, a page fault, the OS) should not flatten everything else.
  std::vector<float> all = side_[0]->history().totalMs;
  all.insert(all.end(), side_[1]->history().totalMs.begin(), side_[1]->history().totalMs.end());
  time.yMax = render::robustTimeTop(std::move(all), std::max(side_[0]->budgetMs(), side_[1]->budgetMs()));
  float maxIterations = 1.f;
  for (int i = 0; i < 2; ++i)
    for (float v : side_[i]->history().iterations) maxIterations = std::max(maxIterations, v);
  iters.yMax = std::ceil(maxIterations * 1.15f);  // headroom so a flat line at the maximum stays readable
  const int pad = int(std::lround(6.f * s));
  render::drawChart(canvas, *text_, pad, y0 + pad, w / 2 - pad, opt_.height - pad, time, style);
  render::drawChart(canvas, *text_, w / 2 + pad, y0 + pad, w - pad, opt_.height - pad, iters, style);
}

std::vector<FrameRegion> ComparisonClip::timingRegions() const {
  std::vector<FrameRegion> regions;
  if (opt_.overlay)
    for (int i = 0; i < 2; ++i) {
      const render::PanelRect r = render::overlayPanelRect(input_[i].overlay, sideW_[i], sideH_);
      const int x0 = i == 0 ? 0 : opt_.width / 2 + 1;
      regions.push_back(
          {std::string(kSideName[i]) + " overlay", PixelRect{x0 + r.x0, labelH_ + r.y0, x0 + r.x1, labelH_ + r.y1}});
    }
  regions.push_back({"chart strip", PixelRect{0, opt_.height - stripH_, opt_.width, opt_.height}});
  return regions;
}

}  // namespace haif
#endif
