#include "tools/progress.h"

#include <cstdio>
#include <unistd.h>

namespace haif {

namespace {
constexpr double kQuietSeconds = 2.0;  // nothing is printed before this
constexpr double kTerminalInterval = 1.0;  // a rewritten line can update often
constexpr double kLogInterval = 10.0;      // a log gets one line per interval
}  // namespace

Progress::Progress(std::string what, std::string unit, int total)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), tty_(::isatty(2) != 0) {
  start_ = last_ = std::chrono::steady_clock::now();
}

void Progress::advance(int done) {
  lastDone_ = done;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double interval = tty_ ? kTerminalInterval : kLogInterval;
  if (elapsed < kQuietSeconds || (printed_ && std::chrono::duration<double>(now - last_).count() < interval)) return;
  last_ = now;
  printed_ = true;
  const double rate = done / elapsed;
  const double left = rate > 0 ? (total_ - done) / rate : 0.0;
  // On a terminal the line is rewritten in place; in a log every update is its own line.
  std::fprintf(stderr, "%s%s: %s %d/%d (%d%%), %.1f %ss/s, %.0f s left%s", tty_ ? "\r" : "", what_.c_str(),
               unit_.c_str(), done, total_, total_ > 0 ? int(100.0 * done / total_) : 100, rate, unit_.c_str(), left,
               tty_ ? "\033[K" : "\n");
  std::fflush(stderr);
}

void Progress::finish() {
  if (!printed_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s: %d %ss in %.1f s%s\n", tty_ ? "\r" : "", what_.c_str(), lastDone_, unit_.c_str(),
               elapsed, tty_ ? "\033[K" : "");
  printed_ = false;
}

}  // namespace haif
