// Google Benchmark of growing the world's largest arrays: a contact-sized element (364 bytes)
// appended until the array grows from N to 2N, as std::vector and as GrowingArray
// (core/growing_array.h). Each iteration builds an array of N elements (not timed) and times the one
// push that grows it: a vector's copy and first touch of its new block, against a remap.
//   ./build/bench_growth --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "core/growing_array.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

namespace haif {
namespace {

struct ContactSized {
  uint32_t id = 0;
  float payload[90] = {};
};
static_assert(sizeof(ContactSized) == 364, "a contact's size (dynamics/contact.h)");

template <class Array>
void growthPush(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    Array a;
    ContactSized c;
    while (a.size() < a.capacity() || a.size() < n) {  // fill to the brim: the next push grows it
      c.id = uint32_t(a.size());
      a.push_back(c);
    }
    state.ResumeTiming();
    a.push_back(c);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
    state.PauseTiming();
    a = Array();  // freed outside the timing
    state.ResumeTiming();
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int64_t n : {8192, 65536}) b->Arg(n);
  b->Unit(benchmark::kMillisecond)->Iterations(5);
}

BENCHMARK_TEMPLATE(growthPush, std::vector<ContactSized>)->Apply(sizes);
BENCHMARK_TEMPLATE(growthPush, GrowingArray<ContactSized>)->Apply(sizes);

}  // namespace
}  // namespace haif

BENCHMARK_MAIN();
