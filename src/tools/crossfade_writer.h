// Strings clips together into one FrameSink with optional cross-fades: the last frames of one clip
// are held back and blended, frame by frame, into the first frames of the next.
#pragma once

#include "tools/video.h"

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace haif {

class CrossfadeWriter {
 public:
  /// Frames of width x height go to `out`.
  CrossfadeWriter(FrameSink& out, int width, int height);

  /// Starts the next clip. Its first `fadeIn` frames blend with the previous clip's held-back tail
  /// (which must be that long: the `holdOut` of the previous call); its last `holdOut` frames are held
  /// back for the clip after it. A clip must be at least fadeIn + holdOut frames long.
  bool beginClip(int fadeIn, int holdOut, std::string& error);
  /// Adds one frame of the current clip.
  bool write(const uint8_t* rgba, std::string& error);
  /// Emits whatever is held back; call once after the last clip.
  bool finish(std::string& error);
  /// Frames handed to `out` so far.
  int framesOut() const { return framesOut_; }

 private:
  bool emit(const uint8_t* rgba, std::string& error);
  std::vector<uint8_t> takeBuffer();

  FrameSink& out_;
  size_t frameBytes_;
  std::deque<std::vector<uint8_t>> held_;    // tail of the current clip, oldest first
  std::deque<std::vector<uint8_t>> fading_;  // tail of the previous clip, being blended in
  std::vector<std::vector<uint8_t>> spare_;  // recycled frame buffers
  std::vector<uint8_t> blended_;
  int hold_ = 0, fadeDone_ = 0, fadeTotal_ = 0, framesOut_ = 0;
};

}  // namespace haif
