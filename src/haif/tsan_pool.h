// A plain thread pool that stands in for TBB in ThreadSanitizer builds (HAIF_SANITIZE=thread).
//
// Debian's libtbb is not instrumented: TSan cannot see a task handed from one thread to another, so
// it reported every read of a handed-over range as a race (421 reports in test_haif, issue 31), and
// a real race between two strips of a giant island would have been lost among them. This pool hands
// work over through a mutex and condition variables, which TSan sees; every report left is about
// HAIF's own memory. Chunks are claimed in order by whichever thread is free, as TBB's are, so the
// same pairs of chunks run at the same time. A loop started inside a chunk runs there, serially.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace haif {

class TsanPool {
 public:
  /// `threads` in all: the caller of run() and threads − 1 workers, started here once.
  explicit TsanPool(int threads);
  ~TsanPool();
  TsanPool(const TsanPool&) = delete;
  TsanPool& operator=(const TsanPool&) = delete;

  /// f(begin, end) over [0, n) in chunks of `grain`, on every thread; returns when all are done.
  void run(uint32_t n, uint32_t grain, const std::function<void(uint32_t, uint32_t)>& f);
  /// The calling thread's index: 0 outside the workers, 1 … threads − 1 in them.
  static int threadIndex();

 private:
  void work(int index);
  void drain(const std::function<void(uint32_t, uint32_t)>& f);

  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_, done_;
  const std::function<void(uint32_t, uint32_t)>* job_ = nullptr;
  uint32_t n_ = 0, grain_ = 1, next_ = 0;
  size_t busy_ = 0;         // workers not yet done with this run
  uint64_t generation_ = 0;  // runs started
  bool stop_ = false;
};

}  // namespace haif
