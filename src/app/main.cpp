// haif: the command users run. Every task is a subcommand.
#include "app/commands.h"

#include <cstdio>
#include <cstring>

namespace {

void usage(FILE* out) {
  std::fputs(
      "usage: haif <command> [options]\n"
      "\n"
      "commands:\n"
      "  run SCENE       simulate a scene; write frames, stats.csv, summary.json (and charts, video)\n"
      "                  [--frames N] [--out DIR] [--no-render] [--threads T]\n"
      "                  [--mode fixed|adaptive|model|replay] [--iterations I] [--budget-ms B]\n"
      "                  [--replay RUN/stats.csv] [--calibration FILE] [--i-min N]\n"
      "                  [--width W --height H] [--view normal|island|sleep|heat] [--contacts]\n"
      "                  [--no-overlay] [--overlay-corner tl|tr|bl|br] [--frame-every K]\n"
      "                  [--error-every K] [--video FILE.mp4]\n"
      "  bench           the seed's table: sequential fixed-10 against HAIF adaptive on stacks_N\n"
      "                  [--scenes a,b,..] [--steps N] [--budget-ms B] [--threads T] [--out DIR]\n"
      "  calibrate       measure this machine's cost model [--out FILE] [--threads T]\n"
      "  assets          write the generated mesh assets (OBJ, STL, PLY, glTF, GLB) [--out DIR]\n"
      "  help            this text\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  const char* cmd = argv[1];
  if (!std::strcmp(cmd, "help") || !std::strcmp(cmd, "--help") || !std::strcmp(cmd, "-h")) {
    usage(stdout);
    return 0;
  }
  if (!std::strcmp(cmd, "run")) return haif::commandRun(argc, argv);
  if (!std::strcmp(cmd, "bench")) return haif::commandBench(argc, argv);
  if (!std::strcmp(cmd, "calibrate")) return haif::commandCalibrate(argc, argv);
  if (!std::strcmp(cmd, "assets")) return haif::commandAssets(argc, argv);
  std::fprintf(stderr, "haif: unknown command '%s' (see 'haif help')\n", cmd);
  return 2;
}
