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

void BM_Stacks2000Frame(benchmark::State& state) {
  std::string error;
  auto r = Renderer::create(RendererOptions{}, &error);
  if (!r) {
    state.SkipWithError(error.c_str());
    return;
  }
  FrameInput f = test::stacks2000Frame();
  f.overlay.enabled = state.range(0) != 0;
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
