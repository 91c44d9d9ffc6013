// The report of `haif diff`: report.json (per-frame metrics, thresholds, verdict) and report.html
// (failures first, reference / new / diff side by side, the command that updates the reference on top).
#pragma once

#include "tools/frame_diff.h"
#include "tools/stats_diff.h"

#include <string>
#include <vector>

namespace haif {

struct DiffReport {
  FrameFolder reference, test;
  DiffOptions options;                ///< threshold, anti-aliasing, masks as applied
  FrameThresholds thresholds;
  std::vector<FrameRegion> masks;     ///< the applied masks with their names
  std::vector<FrameVerdict> frames;   ///< in frame order
  bool statsCompared = false;         ///< both sides are runs with a stats.csv
  StatsDiff stats;
  std::string stateHashReference, stateHashTest;  ///< from summary.json ("" when absent)
  std::vector<std::string> notes;     ///< things the reader should know (nothing masked, ...)
  std::string commandLine;            ///< how the report was made

  int failedFrames() const;
  bool statsPass() const;
  bool pass() const { return failedFrames() == 0 && statsPass(); }
  /// Shell command that makes the new run the reference.
  std::string updateCommand() const;
};

/// Quotes `s` for a POSIX shell.
std::string shellQuote(const std::string& s);

/// report.json text; image paths relative to `outDir`.
std::string diffReportJson(const DiffReport& report, const std::string& outDir);
/// report.html text; image links relative to `outDir`.
std::string diffReportHtml(const DiffReport& report, const std::string& outDir);

}  // namespace haif
