// Google Benchmark of the renderer's frame (not a unit test: timings on a shared machine are noisy,
// so they are measured here, medians over repetitions, and never asserted).
//   ./build/bench_render --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "render/renderer.h"
#include "render/render_test_util.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace haif::render {
namespace {

// The performance target of the renderer: stacks_2000 (2000 boxes in stacks of 10) at the default
// 1280x720, 4x MSAA and a 1024 shadow map; with the overlay charts when `overlay`.
FrameInput stacks2000(bool overlay) {
  FrameInput f;
  f.instances.push_back(test::groundBox());
  const int n = 2000, k = static_cast<int>(std::ceil(std::sqrt(std::ceil(n / 10.0))));
  for (int i = 0; i < n; ++i) {
    Instance b;
    b.bodyId = static_cast<uint32_t>(i);
    const int s = i / 10, h = i % 10;
    b.position[0] = 3.f * static_cast<float>(s % k);
    b.position[1] = 0.5f + 1.01f * static_cast<float>(h);
    b.position[2] = 3.f * static_cast<float>(s / k);
    f.instances.push_back(b);
  }
  for (int i = 0; i < 240; ++i) {
    f.overlay.iterations.push_back(10.f);
    f.overlay.collisionMs.push_back(2.f);
    f.overlay.solveMs.push_back(4.f);
  }
  f.overlay.enabled = overlay;
  return f;
}

void BM_Stacks2000Frame(benchmark::State& state) {
  std::string error;
  auto r = Renderer::create(RendererOptions{}, &error);
  if (!r) {
    state.SkipWithError(error.c_str());
    return;
  }
  const FrameInput f = stacks2000(state.range(0) != 0);
  std::vector<uint8_t> px;
  if (!r->render(f, px, &error)) {  // warm-up: font, buffers
    state.SkipWithError(error.c_str());
    return;
  }
  for (auto _ : state) {
    r->render(f, px, &error);
    benchmark::DoNotOptimize(px.data());
  }
  state.SetLabel(state.range(0) ? "overlay on" : "overlay off");
}
BENCHMARK(BM_Stacks2000Frame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace haif::render

BENCHMARK_MAIN();
