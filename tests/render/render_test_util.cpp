#include "render_test_util.h"

#include "support/scratch_folder.h"

namespace haif::render::test {

std::string tempDir() {
  // One folder per process, made on first use and removed when the process ends.
  static const std::string dir = haif::test::scratchDir("haif_render_test").string();
  return dir;
}

}  // namespace haif::render::test
