#include "tools/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace haif {

std::string temporaryPathFor(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
}

bool writeFileAtomic(const std::string& path, const std::string& content, std::string& error) {
  const std::string tmp = temporaryPathFor(path);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) {
    error = path + ": cannot write (" + std::strerror(errno) + ")";
    return false;
  }
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    error = path + ": write failed (" + std::strerror(errno) + ")";
    std::remove(tmp.c_str());
    return false;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = path + ": cannot rename temporary file (" + std::strerror(errno) + ")";
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

bool ensureWritableDir(const std::string& dir, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    error = dir + ": cannot create output folder (" + ec.message() + ")";
    return false;
  }
  if (!std::filesystem::is_directory(dir)) {
    error = dir + ": output path exists and is not a folder";
    return false;
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    error = dir + ": output folder is not writable (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

}  // namespace haif
