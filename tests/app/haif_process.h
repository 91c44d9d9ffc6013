// Running the built haif command from a test: exit status, stdout and stderr.
#pragma once

#include "support/scratch_folder.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace haif::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string readWholeFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs `haif ARGS` through the shell (ARGS are shell words) with `envPrefix` (e.g. "PATH=/x ")
/// in front; output is captured in files under `scratch`.
inline ProcessResult runHaif(const std::string& args, const std::filesystem::path& scratch,
                             const std::string& envPrefix = "") {
  std::filesystem::create_directories(scratch);
  const auto out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string cmd = envPrefix + "'" + std::string(HAIF_BINARY) + "' " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.out = readWholeFile(out);
  r.err = readWholeFile(err);
  return r;
}

}  // namespace haif::test
