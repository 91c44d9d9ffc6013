// Frame-by-frame comparison of two frame folders (or two runs, whose frames are in RUN/frames):
// pairing the frames by name, checking sizes, comparing each pair and writing diff images.
#pragma once

#include "tools/frame_masks.h"
#include "tools/image_diff.h"

#include <functional>
#include <string>
#include <vector>

namespace haif {

/// One side of a diff, resolved from the path the user gave.
struct FrameFolder {
  std::string given;                ///< the path as given
  std::string runDir;               ///< the run folder when `given` is a run (holds stats.csv), else ""
  std::string framesDir;            ///< folder holding the PNG frames
  std::vector<std::string> frames;  ///< PNG file names, sorted
  int width = 0, height = 0;        ///< size of the first frame
  bool hasMasks = false;            ///< framesDir/masks.json exists and was read
  FrameMasks masks;
};

/// Resolves `path` (a run folder with frames/, or a folder of PNG frames) and reads the first frame's
/// size. False with one error line ("reference 'x': no such folder") when it is unusable.
bool openFrameFolder(const std::string& path, const std::string& label, FrameFolder& out, std::string& error);

/// Both folders hold the same frame names and every pair has one size. False with the first mismatch.
bool checkFramePairs(const FrameFolder& reference, const FrameFolder& test, std::string& error);

/// Limits a frame must stay within.
struct FrameThresholds {
  double maxDiffRatio = 0.001;  ///< differing / compared pixels
  double minSsim = 0.98;        ///< mean SSIM
};

/// The outcome for one frame pair.
struct FrameVerdict {
  std::string name;       ///< frame file name
  DiffResult result;
  bool pass = true;
  std::string diffImage;  ///< path of the written diff image ("" when none was written)
};

/// Compares every pair (in parallel), writing diffDir/NAME when diffDir is not empty. `onFrame` (may be
/// empty) is called with the number of frames done so far. False with an error on a read/write failure.
bool diffFrameFolders(const FrameFolder& reference, const FrameFolder& test, const DiffOptions& options,
                      const FrameThresholds& thresholds, const std::string& diffDir, std::vector<FrameVerdict>& out,
                      std::string& error, const std::function<void(int)>& onFrame = {});

}  // namespace haif
