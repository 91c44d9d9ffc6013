#include "tools/video.h"

#include "tools/atomic_file.h"

#include <cstdio>
#include <cstdlib>
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

namespace {

/// Runs argv without a shell (no quoting problems with odd file names); returns the exit status.
int runProgram(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    ::execvp(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

bool encodeVideoFromFrames(const std::string& framesDir, double fps, const std::string& outPath, std::string& error) {
  if (!ffmpegAvailable()) {
    error = outPath + ": ffmpeg not found on PATH (apt-get install ffmpeg); the PNG frames are in " + framesDir;
    return false;
  }
  const std::filesystem::path out(outPath);
  if (out.has_parent_path() && !ensureWritableDir(out.parent_path().string(), error)) return false;
  // ffmpeg picks the container from the extension: keep it on the temporary name.
  const std::string tmp = (out.parent_path() / ("." + out.stem().string() + ".tmp" + out.extension().string())).string();
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  const int rc = runProgram({"ffmpeg", "-loglevel", "error", "-y", "-framerate", rate, "-i",
                             framesDir + "/frame_%05d.png", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v",
                             "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart", tmp});
  if (rc != 0) {
    std::remove(tmp.c_str());
    error = outPath + ": ffmpeg failed (exit status " + std::to_string(rc) + ")";
    return false;
  }
  if (std::rename(tmp.c_str(), outPath.c_str()) != 0) {
    std::remove(tmp.c_str());
    error = outPath + ": cannot rename the encoded video into place";
    return false;
  }
  return true;
}

}  // namespace haif
