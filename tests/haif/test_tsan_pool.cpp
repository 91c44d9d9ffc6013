// The thread pool that replaces TBB under ThreadSanitizer (haif/tsan_pool.h): every index is visited
// once, and a loop started inside a chunk runs there.
#include "haif/tsan_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <vector>

using namespace haif;

TEST(TsanPool, VisitsEveryIndexOnceAcrossThreads) {
  TsanPool pool(3);
  for (int round = 0; round < 50; ++round) {
    const uint32_t n = 1000 + uint32_t(round);
    std::vector<std::atomic<int>> seen(n);
    std::mutex m;
    std::set<int> threads;
    pool.run(n, 7, [&](uint32_t b, uint32_t e) {
      for (uint32_t i = b; i < e; ++i) seen[i].fetch_add(1);
      std::lock_guard<std::mutex> lock(m);
      threads.insert(TsanPool::threadIndex());
    });
    for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << "round " << round << " index " << i;
    for (const int t : threads) EXPECT_TRUE(t >= 0 && t < 3);
  }
}

TEST(TsanPool, NestedLoopRunsInsideItsChunk) {
  TsanPool pool(2);
  std::atomic<int> inner{0};
  pool.run(8, 1, [&](uint32_t, uint32_t) {
    pool.run(10, 1, [&](uint32_t b, uint32_t e) { inner.fetch_add(int(e - b)); });
  });
  EXPECT_EQ(inner.load(), 80);
}
