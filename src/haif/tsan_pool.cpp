#include "haif/tsan_pool.h"

#include <algorithm>

namespace haif {

namespace {
thread_local int tIndex = 0;
thread_local bool tInChunk = false;
}  // namespace

TsanPool::TsanPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

TsanPool::~TsanPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

int TsanPool::threadIndex() { return tIndex; }

void TsanPool::drain(const std::function<void(uint32_t, uint32_t)>& f) {
  tInChunk = true;
  for (;;) {
    uint32_t b, e;
    {
      std::lock_guard<std::mutex> lock(m_);
      if (next_ >= n_) break;
      b = next_;
      e = std::min(n_, b + grain_);
      next_ = e;
    }
    f(b, e);
  }
  tInChunk = false;
}

void TsanPool::run(uint32_t n, uint32_t grain, const std::function<void(uint32_t, uint32_t)>& f) {
  if (tInChunk || workers_.empty()) {
    if (n > 0) f(0, n);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    job_ = &f;
    n_ = n;
    grain_ = std::max(1u, grain);
    next_ = 0;
    busy_ = workers_.size();
    ++generation_;
  }
  wake_.notify_all();
  drain(f);
  std::unique_lock<std::mutex> lock(m_);
  done_.wait(lock, [&] { return busy_ == 0; });
  job_ = nullptr;
}

void TsanPool::work(int index) {
  tIndex = index;
  uint64_t seen = 0;
  for (;;) {
    const std::function<void(uint32_t, uint32_t)>* job;
    {
      std::unique_lock<std::mutex> lock(m_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
    }
    drain(*job);
    std::lock_guard<std::mutex> lock(m_);
    if (--busy_ == 0) done_.notify_one();
  }
}

}  // namespace haif
