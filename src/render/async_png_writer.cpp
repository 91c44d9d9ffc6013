#include "render/async_png_writer.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>

#include "render/png_io.h"

namespace haif::render {

AsyncPngWriter::AsyncPngWriter(int maxPending) : ring_(static_cast<size_t>(std::max(1, maxPending))) {
  thread_ = std::thread([this] { run(); });
}

AsyncPngWriter::~AsyncPngWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    held_ = false;
  }
  changed_.notify_all();
  thread_.join();
}

bool AsyncPngWriter::submit(const std::string& path, int w, int h, std::vector<uint8_t>& rgba, std::string* error) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (count_ == ring_.size() && held_) {  // waiting for a held thread would never end
    held_ = false;
    changed_.notify_all();
  }
  changed_.wait(lock, [&] { return count_ < ring_.size() || !error_.empty(); });
  if (!error_.empty()) {
    if (error) *error = error_;
    return false;
  }
  Job& job = ring_[(head_ + count_) % ring_.size()];
  job.path = path;
  job.w = w;
  job.h = h;
  job.rgba.swap(rgba);  // the frame moves in; the slot's old buffer (or a spare) goes back out
  if (rgba.empty() && !spare_.empty()) {
    rgba.swap(spare_.back());
    spare_.pop_back();
  }
  ++count_;
  lock.unlock();
  changed_.notify_all();
  return true;
}

void AsyncPngWriter::hold(bool held) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = held;
  }
  if (!held) changed_.notify_all();
}

bool AsyncPngWriter::finish(std::string* error) {
  std::unique_lock<std::mutex> lock(mutex_);
  held_ = false;
  changed_.notify_all();
  changed_.wait(lock, [&] { return (count_ == 0 && !busy_) || !error_.empty(); });
  if (error_.empty()) return true;
  if (error) *error = error_;
  return false;
}

double AsyncPngWriter::medianWriteMs() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (writeMs_.empty()) return 0.0;
  std::vector<double> v = writeMs_;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void AsyncPngWriter::run() {
  // Writing frames is background work: at the lowest priority it waits for the simulation, whose
  // step it otherwise preempted (a budgeted step then overran: docs/renderer.md).
  ::setpriority(PRIO_PROCESS, pid_t(::syscall(SYS_gettid)), 19);
  std::vector<uint8_t> pixels;  // the job being written, outside the lock
  for (;;) {
    Job* job = nullptr;
    bool failed = false;  // after one failure the rest are dropped, not written
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return (count_ > 0 && !held_) || stop_; });
      if (count_ == 0) return;  // stopping and nothing left
      job = &ring_[head_];
      pixels.swap(job->rgba);
      busy_ = true;
      failed = !error_.empty();
      // The slot stays counted until the write is done, so submit() cannot reuse it meanwhile.
    }
    std::string why;
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = !failed && writePng(job->path, job->w, job->h, pixels.data(), &why);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (ok) writeMs_.push_back(ms);
      else if (error_.empty()) error_ = why;
      spare_.push_back(std::move(pixels));
      pixels = std::vector<uint8_t>();
      head_ = (head_ + 1) % ring_.size();
      --count_;
      busy_ = false;
    }
    changed_.notify_all();
  }
}

}  // namespace haif::render
