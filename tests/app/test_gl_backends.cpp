// haif run --gl: frames drawn through OSMesa and through EGL pass haif diff against each other;
// an unknown back end is bad input.
#include "haif_process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace haif::test {
namespace {

TEST(GlBackendCommand, OsMesaAndEglFramesPassHaifDiff) {
  const auto dir = scratchDir("haif_gl_backends");
  const std::string scene = std::string(HAIF_SOURCE_DIR) + "/scenes/pyramid_15.json";
  for (const char* gl : {"osmesa", "egl"}) {
    const ProcessResult r = runHaif("run '" + scene + "' --frames 4 --threads 1 --width 320 --height 240 --error-every 0 --gl " +
                                        gl + " --out '" + (dir / gl).string() + "'",
                                    dir);
    if (r.exitCode != 0 && r.err.find("this build has no") != std::string::npos)
      GTEST_SKIP() << "this build has only one GL back end: " << r.err;
    ASSERT_EQ(r.exitCode, 0) << gl << ": " << r.err;
    ASSERT_TRUE(std::filesystem::exists(dir / gl / "frames" / "frame_00003.png")) << gl;
  }
  const ProcessResult diff = runHaif("diff '" + (dir / "osmesa").string() + "' '" + (dir / "egl").string() + "' --out '" +
                                         (dir / "diff").string() + "'",
                                     dir);
  EXPECT_EQ(diff.exitCode, 0) << diff.out << diff.err;
  EXPECT_NE(diff.out.find("pass"), std::string::npos) << diff.out;

  const ProcessResult bad = runHaif("run '" + scene + "' --frames 1 --gl vulkan --out '" + (dir / "bad").string() + "'", dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--gl: expected osmesa, egl or auto, got 'vulkan'"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace haif::test
