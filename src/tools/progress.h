// Progress of long jobs on stderr ("compare: frame 120/300 (40%), 3.1 frames/s, 58 s left").
// Silent for jobs that finish within the first couple of seconds, so short runs and tests stay quiet.
#pragma once

#include <chrono>
#include <string>

namespace haif {

class Progress {
 public:
  /// `what` prefixes every line ("compare"), `unit` names the items ("frame"), `total` of them.
  Progress(std::string what, std::string unit, int total);
  /// Call after each item; prints at most once a second on a terminal, every 10 s into a log.
  void advance(int done);
  /// Ends an overwritten terminal line; prints the final count if anything was printed.
  void finish();

 private:
  std::string what_, unit_;
  int total_;
  bool printed_ = false, tty_;
  std::chrono::steady_clock::time_point start_, last_;
  int lastDone_ = 0;
};

}  // namespace haif
