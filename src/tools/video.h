// Video encoding through Debian's ffmpeg (a separate program, found on PATH).
#pragma once

#include <string>

namespace haif {

/// True when an `ffmpeg` executable is on PATH.
bool ffmpegAvailable();

/// Encodes framesDir/frame_%05d.png at `fps` into `outPath` (H.264, yuv420p, faststart), writing
/// to a temporary name first. A clear message when ffmpeg is missing or fails.
bool encodeVideoFromFrames(const std::string& framesDir, double fps, const std::string& outPath, std::string& error);

}  // namespace haif
