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
      "  bench           run time against error: iteration and budget sweeps per scene and engine,\n"
      "                  the seed's table (sequential / HAIF / Bullet); results.csv, report.md, plots\n"
      "                  [--scenes a,b,..] [--engines haif,bullet] [--quick] [--steps N] [--threads T]\n"
      "                  [--iterations 1,2,..] [--budgets 1,2,..] [--budget-ms B] [--error-every K]\n"
      "                  [--out DIR]\n"
      "  calibrate       measure this machine's cost model [--out FILE] [--threads T]\n"
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
  std::fprintf(stderr, "haif: unknown command '%s' (see 'haif help')\n", cmd);
  return 2;
}
