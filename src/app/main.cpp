// haif: the command users run. Every task is a subcommand.
#include "app/commands.h"
#include "tools/interrupts.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

namespace {

const char* const kUsage =
      "usage: haif <command> [options]\n"
      "\n"
      "commands:\n"
      "  run SCENE       simulate a scene; write frames, stats.csv, summary.json (and charts, video)\n"
      "                  [--frames N] [--out DIR] [--no-render] [--threads T]\n"
      "                  [--mode fixed|adaptive|model|replay] [--iterations I] [--budget-ms B]\n"
      "                  [--replay RUN/stats.csv] [--calibration FILE] [--i-min N]\n"
      "                  [--width W --height H] [--view normal|island|sleep|heat] [--contacts]\n"
      "                  [--no-overlay] [--overlay-corner tl|tr|bl|br] [--frame-every K]\n"
      "                  [--error-every K] [--video FILE.mp4] [--render-phases] [--gl osmesa|egl|auto]\n"
      "  bench           run time against error: iteration and budget sweeps per scene and engine,\n"
      "                  the seed's table (sequential / HAIF / Bullet); results.csv, report.md, plots\n"
      "                  [--scenes a,b,..] [--engines haif,bullet] [--quick] [--steps N] [--threads T,..]\n"
      "                  [--iterations 1,2,..] [--budgets 1,2,..] [--budget-ms B] [--error-every K]\n"
      "                  [--repeat R] [--out DIR]\n"
      "                  --scaling: ms/step and memory against bodies (stacks and piles, 10^3 to 10^5),\n"
      "                  the fitted exponents; scaling.csv, report.md, scaling.png [--sizes N,..] [--steps N]\n"
      "  calibrate       measure this machine's cost model [--out FILE] [--threads T]\n"
      "  compare SCENE   two solver set-ups of one scene side by side in one video\n"
      "                  --left SPEC --right SPEC  (SPEC: fixed:N, adaptive:MS, model:MS, replay:STATS.csv,\n"
      "                  bullet:N) [--out FILE.mp4] [--frames N] [--frame-every K] [--width W --height H]\n"
      "                  [--threads T] [--view normal|island|sleep|heat] [--no-overlay] [--gl osmesa|egl|auto]\n"
      "  reel PLAYLIST   title cards, scenes and comparisons in sequence in one video\n"
      "                  [--out FILE.mp4] [--width W --height H] [--fps F] [--threads T] [--check]\n"
      "                  [--gl osmesa|egl|auto]\n"
      "  diff REF NEW    visual regression of two runs or frame folders; exit 0 pass, 1 fail, 2 bad input\n"
      "                  [--out DIR] [--threshold T] [--max-diff-ratio R] [--min-ssim S]\n"
      "                  [--mask overlay|none|X0:Y0:X1:Y1[,...]] [--no-aa] [--no-diff-images]\n"
      "                  [--allow-adaptive]\n"
      "  stress          stress scenes (scenes/stress/) judged by their checks; DIR/stress.json;\n"
      "                  exit 0 all pass, 1 some fail, 2 bad input [SCENE|DIR ...] [--quick] [--out DIR]\n"
      "                  [--threads T]\n"
      "  suite SUITE     run a suite file's jobs (run + checks, render + diff, stress) or one shard of them;\n"
      "                  one report: DIR/report.json, report.html, junit.xml; exit 0 all pass, 1 some fail,\n"
      "                  2 bad input [--out DIR] [--shard I/N] [--threads T] [--update-references]\n"
      "                  'haif suite merge OUT_DIR SHARD_DIR...' joins the shards' reports into one\n"
      "  assets          write the generated mesh assets (OBJ, STL, PLY, glTF, GLB) [--out DIR]\n"
      "  help [COMMAND]  this text, or one command's part of it (also: haif COMMAND --help)\n";

void usage(FILE* out) { std::fputs(kUsage, out); }

// One command's lines of the usage text: its own line (two spaces, then its name) and the lines
// indented under it. False when there is no such command.
bool commandUsage(const char* name, FILE* out) {
  const std::string text(kUsage), head = std::string("  ") + name;
  size_t at = 0;
  while ((at = text.find('\n' + head, at)) != std::string::npos) {
    const size_t start = at + 1, after = start + head.size();
    if (after < text.size() && (text[after] == ' ' || text[after] == '\n')) {
      size_t end = text.find('\n', start);
      // Continuation lines are indented deeper than a command's name.
      while (end != std::string::npos && text.compare(end + 1, 4, "    ") == 0) end = text.find('\n', end + 1);
      std::fprintf(out, "%s\n", text.substr(start, end - start).c_str());
      return true;
    }
    at = after;
  }
  return false;
}

bool asksForHelp(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  const char* cmd = argv[1];
  if (!std::strcmp(cmd, "help") || !std::strcmp(cmd, "--help") || !std::strcmp(cmd, "-h")) {
    if (argc > 2 && std::strcmp(cmd, "help") == 0) {
      if (commandUsage(argv[2], stdout)) return 0;
      std::fprintf(stderr, "haif help: unknown command '%s' (see 'haif help')\n", argv[2]);
      return 2;
    }
    usage(stdout);
    return 0;
  }
  using Command = int (*)(int, char**);
  const std::pair<const char*, Command> commands[] = {
      {"run", haif::commandRun},         {"bench", haif::commandBench},   {"calibrate", haif::commandCalibrate},
      {"diff", haif::commandDiff},       {"compare", haif::commandCompare}, {"reel", haif::commandReel},
      {"stress", haif::commandStress},   {"suite", haif::commandSuite},   {"assets", haif::commandAssets}};
  for (const auto& [name, command] : commands) {
    if (std::strcmp(cmd, name) != 0) continue;
    if (asksForHelp(argc, argv)) return commandUsage(name, stdout) ? 0 : 2;
    // Before any thread starts: every thread inherits the blocked SIGINT and SIGTERM.
    haif::installInterruptHandler(std::string("haif ") + name);
    const int status = command(argc, argv);
    haif::waitIfInterrupted();  // an interrupted command ends with the handler's line and status
    return status;
  }
  std::fprintf(stderr, "haif: unknown command '%s' (see 'haif help')\n", cmd);
  return 2;
}
