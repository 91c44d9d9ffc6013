// Video output through Debian's ffmpeg (a separate program found on PATH): frames are streamed as
// raw RGBA into ffmpeg's stdin and encoded to H.264 (yuv420p, even dimensions, +faststart) under a
// temporary name that is renamed into place when the video is complete. Without ffmpeg, frames go
// to PNG files instead.
#pragma once

#include "tools/staged_output.h"

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>

namespace haif {

/// True when an `ffmpeg` executable is on PATH.
bool ffmpegAvailable();

/// Where rendered frames go, one after the other, all of one size.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// Adds one frame of width*height RGBA8 pixels, top row first.
  virtual bool write(const uint8_t* rgba, std::string& error) = 0;
  /// Completes the output (the video is renamed into place). Nothing may be written after it.
  virtual bool finish(std::string& error) = 0;
  /// Where the output is (the video file or the frame folder).
  virtual std::string where() const = 0;
  /// Pauses (true) or resumes (false) encoding that runs beside the caller: see EncodingHold.
  virtual void hold(bool) {}
};

/// Holds a sink's background encoding for as long as it lives (nothing for null): put around the
/// budgeted steps of a run that is filmed. An encoder running beside a step shares its cores, and
/// on a machine of two the step then overran a 4 ms budget in 21 % of the README demo's steps (6 %
/// without the video), whatever its priority (a lower one did not help: the cores are virtual and
/// shared underneath, their caches too). Held, it encodes while frames are drawn.
class EncodingHold {
 public:
  explicit EncodingHold(FrameSink* sink) : sink_(sink) {
    if (sink_) sink_->hold(true);
  }
  ~EncodingHold() {
    if (sink_) sink_->hold(false);
  }
  EncodingHold(const EncodingHold&) = delete;
  EncodingHold& operator=(const EncodingHold&) = delete;

 private:
  FrameSink* sink_;
};

/// An ffmpeg process fed through a pipe.
class VideoEncoder : public FrameSink {
 public:
  ~VideoEncoder() override;  ///< an unfinished encoder stops ffmpeg and removes its temporary file
  /// Starts ffmpeg for width x height frames at `fps`, writing `outPath` (.mp4). One error line on failure.
  bool open(const std::string& outPath, int width, int height, double fps, std::string& error);
  bool write(const uint8_t* rgba, std::string& error) override;
  bool finish(std::string& error) override;
  std::string where() const override { return outPath_; }
  int framesWritten() const { return frames_; }
  /// Stops (true) or continues (false) the ffmpeg process (SIGSTOP / SIGCONT).
  void hold(bool held) override;

 private:
  void abort();
  bool waitForExit(std::string& error);
  std::string outPath_, tmpPath_;
  pid_t pid_ = -1;
  int fd_ = -1;
  size_t frameBytes_ = 0;
  int frames_ = 0;
  bool held_ = false;
};

/// PNG files dir/frame_00000.png, ... (the fallback without ffmpeg), written into a temporary
/// folder that finish() moves into place (tools/staged_output.h).
class PngFrameSink : public FrameSink {
 public:
  bool open(const std::string& dir, int width, int height, std::string& error);
  bool write(const uint8_t* rgba, std::string& error) override;
  bool finish(std::string& error) override { return folder_.commit(error); }
  std::string where() const override { return dir_; }
  /// Where files beside the frames go until finish() (masks.json).
  const std::string& stagingDir() const { return folder_.path(); }

 private:
  StagedFolder folder_;
  std::string dir_;
  int width_ = 0, height_ = 0, frames_ = 0;
};

/// The video `outPath` when ffmpeg is on PATH; otherwise PNG frames in "<outPath without extension>_frames/"
/// with `notice` saying so. nullptr and `error` when neither can be opened.
std::unique_ptr<FrameSink> openVideoOrFrames(const std::string& outPath, int width, int height, double fps,
                                             std::string& notice, std::string& error);

}  // namespace haif
