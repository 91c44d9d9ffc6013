#include "render_test_util.h"

#include <unistd.h>

#include <filesystem>

namespace haif::render::test {

std::string tempDir() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("haif_render_test_" + std::to_string(static_cast<long>(getpid())));
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace haif::render::test
