#include "scene/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace haif {

bool readTextFile(const std::string& path, const std::string& what, std::string& text, std::string& error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    error = path + ": is a directory, not a " + what;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open " + what + " (" + std::strerror(errno) + ")";
    return false;
  }
  // In chunks, up to a bound: /dev/zero or an endless pipe would otherwise fill the memory.
  std::string all;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    all.append(chunk, size_t(in.gcount()));
    if (all.size() > kMaxTextFileBytes) {
      error = path + ": " + what + " is larger than " + std::to_string(kMaxTextFileBytes >> 20) + " MiB";
      return false;
    }
  }
  if (in.bad()) {
    error = path + ": cannot read " + what + " (" + std::strerror(errno) + ")";
    return false;
  }
  text = std::move(all);
  return true;
}

}  // namespace haif
