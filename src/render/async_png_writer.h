// Writes PNG frames on one background thread, so encoding a frame overlaps rendering the next one
// and the simulation steps in between. The thread is created once per writer (once per run), the
// pixel buffers are recycled, and every file is written atomically by writePng, in submit order.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace haif::render {

class AsyncPngWriter {
 public:
  /// Starts the writer thread. At most `maxPending` frames wait to be written; submit() blocks
  /// while that many are queued, so memory stays bounded when encoding is slower than rendering.
  explicit AsyncPngWriter(int maxPending = 2);
  /// Waits for the queued frames (errors are only reported through finish()).
  ~AsyncPngWriter();
  AsyncPngWriter(const AsyncPngWriter&) = delete;
  AsyncPngWriter& operator=(const AsyncPngWriter&) = delete;

  /// Queues w*h RGBA pixels (top row first) for `path`. Takes the contents of `rgba` and hands back
  /// a recycled buffer in its place (any size: the renderer resizes it). Returns false with
  /// *error when an earlier frame failed; nothing more is written after a failure.
  bool submit(const std::string& path, int w, int h, std::vector<uint8_t>& rgba, std::string* error);
  /// Waits until every queued frame is on disk. False with *error (the first failure) if any failed.
  bool finish(std::string* error);
  /// While held (true), the thread starts no new frame (one it is writing goes on): a filmed run
  /// holds it during each budgeted step, so frames are encoded while the next ones are drawn
  /// (tools/video.h, EncodingHold). A full queue, finish() and the destructor lift the hold.
  void hold(bool held);
  /// Median time to encode and write one frame so far, in ms (0 before the first).
  double medianWriteMs();

 private:
  struct Job {
    std::string path;
    int w = 0, h = 0;
    std::vector<uint8_t> rgba;
  };
  void run();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Job> ring_;               // maxPending slots
  size_t head_ = 0, count_ = 0;         // oldest queued job and number queued
  bool busy_ = false;                   // the thread is writing a job it has taken out
  bool stop_ = false;
  bool held_ = false;
  std::string error_;                   // first failure; empty while all went well
  std::vector<std::vector<uint8_t>> spare_;  // recycled pixel buffers
  std::vector<double> writeMs_;
  std::thread thread_;
};

}  // namespace haif::render
