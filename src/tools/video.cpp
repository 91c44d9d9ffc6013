#include "tools/video.h"

#include "render/png_io.h"
#include "tools/frame_masks.h"
#include "tools/atomic_file.h"
#include "tools/interrupts.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace haif {

bool ffmpegAvailable() {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  for (std::string dir; std::getline(ss, dir, ':');)
    if (!dir.empty() && ::access((dir + "/ffmpeg").c_str(), X_OK) == 0) return true;
  return false;
}

VideoEncoder::~VideoEncoder() { abort(); }

bool VideoEncoder::open(const std::string& outPath, int width, int height, double fps, std::string& error) {
  abort();
  if (!ffmpegAvailable()) {
    error = outPath + ": ffmpeg not found on PATH (apt-get install ffmpeg)";
    return false;
  }
  if (width < 2 || height < 2 || !(fps > 0.0)) {
    error = outPath + ": invalid video size " + std::to_string(width) + "x" + std::to_string(height);
    return false;
  }
  const std::filesystem::path out(outPath);
  if (out.has_parent_path() && !ensureWritableDir(out.parent_path().string(), error)) return false;
  // ffmpeg picks the container from the extension: keep it on the temporary name.
  tmpPath_ = (out.parent_path() / ("." + out.stem().string() + ".tmp" + std::to_string(::getpid()) +
                                   out.extension().string()))
                 .string();
  outPath_ = outPath;
  registerTemporary(tmpPath_);
  frameBytes_ = size_t(width) * size_t(height) * 4;
  frames_ = 0;

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    error = outPath + ": cannot create a pipe to ffmpeg (" + std::strerror(errno) + ")";
    return false;
  }
  char size[32], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%g", fps);
  // Odd sizes are padded by one pixel: yuv420p needs even dimensions.
  const std::vector<std::string> args = {
      "ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-f", "rawvideo", "-pix_fmt", "rgba",
      "-video_size", size, "-framerate", rate, "-i", "pipe:0", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
      "-c:v", "libx264", "-preset", "medium", "-crf", "20", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
      tmpPath_};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // A dead ffmpeg must show up as a write error here, not kill haif with SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  pid_ = ::fork();
  if (pid_ < 0) {
    error = outPath + ": cannot start ffmpeg (" + std::strerror(errno) + ")";
    ::close(fds[0]);
    ::close(fds[1]);
    return false;
  }
  if (pid_ == 0) {
    // -nostdin only stops ffmpeg reading keys; the frames come in on fd 0 as pipe:0.
    ::dup2(fds[0], 0);
    // Ctrl-C reaches haif alone, which stops ffmpeg itself and removes its unfinished video
    // (tools/interrupts.h); haif blocks the signals, and ffmpeg must not inherit that.
    ::setpgid(0, 0);
    unblockInterruptsInChild();
    // Encoding is background work: at the lowest priority it waits for the simulation, whose
    // budgeted steps it otherwise preempted (and it is held while they run: EncodingHold).
    if (::nice(19) == -1) { /* still encodes, at normal priority */ }
    ::execvp(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(fds[0]);
  fd_ = fds[1];
  registerChild(pid_);
  return true;
}

bool VideoEncoder::write(const uint8_t* rgba, std::string& error) {
  if (fd_ < 0) {
    error = outPath_ + ": the video is not open";
    return false;
  }
  size_t done = 0;
  while (done < frameBytes_) {
    const ssize_t n = ::write(fd_, rgba + done, frameBytes_ - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int saved = errno;
      std::string why;
      ::close(fd_);
      fd_ = -1;
      if (!waitForExit(why)) error = why;
      else error = outPath_ + ": writing to ffmpeg failed (" + std::strerror(saved) + ")";
      abort();
      return false;
    }
    done += size_t(n);
  }
  ++frames_;
  return true;
}

bool VideoEncoder::waitForExit(std::string& error) {
  if (pid_ <= 0) return true;
  hold(false);  // a stopped encoder never exits
  int status = 0;
  pid_t r;
  do r = ::waitpid(pid_, &status, 0);
  while (r < 0 && errno == EINTR);
  releaseChild(pid_);
  pid_ = -1;
  if (r < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const int code = r >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    error = outPath_ + ": ffmpeg failed (exit status " + std::to_string(code) + ")" +
            (code == 127 ? ": it could not be started" : "");
    return false;
  }
  return true;
}

bool VideoEncoder::finish(std::string& error) {
  if (fd_ < 0 && pid_ < 0) {
    error = outPath_ + ": the video is not open";
    return false;
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!waitForExit(error)) {
    abort();
    return false;
  }
  if (frames_ == 0) {
    error = outPath_ + ": no frames were rendered";
    abort();
    return false;
  }
  if (std::rename(tmpPath_.c_str(), outPath_.c_str()) != 0) {
    error = outPath_ + ": cannot rename the encoded video into place (" + std::strerror(errno) + ")";
    abort();
    return false;
  }
  releaseTemporary(tmpPath_);
  tmpPath_.clear();
  return true;
}

void VideoEncoder::hold(bool held) {
  if (pid_ <= 0 || held == held_) return;
  // Stops all its threads. Should haif die while ffmpeg is stopped, ffmpeg's process group (its
  // own: open) is orphaned, and the kernel then sends it SIGHUP and SIGCONT: it does not linger.
  ::kill(pid_, held ? SIGSTOP : SIGCONT);
  held_ = held;
}

void VideoEncoder::abort() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ > 0) {
    hold(false);
    ::kill(pid_, SIGTERM);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    releaseChild(pid_);
    pid_ = -1;
  }
  if (!tmpPath_.empty()) {
    std::remove(tmpPath_.c_str());
    releaseTemporary(tmpPath_);
  }
  tmpPath_.clear();
}

bool PngFrameSink::open(const std::string& dir, int width, int height, std::string& error) {
  if (!folder_.open(dir, {"frame_00000.png", kFrameMasksFile}, error)) return false;
  dir_ = dir;
  width_ = width;
  height_ = height;
  frames_ = 0;
  return true;
}

bool PngFrameSink::write(const uint8_t* rgba, std::string& error) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%05d.png", frames_);
  if (!render::writePng(folder_.path() + name, width_, height_, rgba, &error)) return false;
  ++frames_;
  return true;
}

std::unique_ptr<FrameSink> openVideoOrFrames(const std::string& outPath, int width, int height, double fps,
                                             std::string& notice, std::string& error) {
  notice.clear();
  if (ffmpegAvailable()) {
    auto video = std::make_unique<VideoEncoder>();
    if (!video->open(outPath, width, height, fps, error)) return nullptr;
    return video;
  }
  const std::filesystem::path p(outPath);
  const std::string dir = (p.parent_path() / (p.stem().string() + "_frames")).string();
  auto frames = std::make_unique<PngFrameSink>();
  if (!frames->open(dir, width, height, error)) return nullptr;
  notice = "ffmpeg not found on PATH (apt-get install ffmpeg): writing PNG frames to " + dir + " instead of " + outPath;
  return frames;
}

}  // namespace haif
