// haif bench: run time against error. For each scene, sweeps fixed iteration counts on every engine
// and adaptive budgets on HAIF, plus the seed's three set-ups (sequential fixed:10 on one thread,
// HAIF adaptive, Bullet fixed:10), measuring ms/step and the errors of docs/metrics.md. Writes
// DIR/results.csv, DIR/report.md and DIR/pareto_<scene>.png.
#include "app/cli.h"
#include "app/commands.h"
#include "scene/scene_loader.h"
#include "tools/atomic_file.h"
#include "tools/bench_plots.h"
#include "tools/bench_report.h"
#include "tools/bench_scaling.h"
#include "tools/bench_sweep.h"
#include "tools/interrupts.h"
#include "tools/staged_output.h"

#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <sstream>

namespace haif {

namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string s; std::getline(ss, s, ',');)
    if (!s.empty()) out.push_back(s);
  return out;
}

// A scene given by name (stacks_100: scenes/stacks_100.json here or in the source tree) or by path.
std::string findScene(const std::string& name) {
  if (std::filesystem::exists(name) || name.find('/') != std::string::npos ||
      (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0))
    return name;
  for (const std::string& dir : {std::string("scenes/"), std::string(HAIF_SOURCE_DIR) + "/scenes/"}) {
    const std::string p = dir + name + ".json";
    if (std::filesystem::exists(p)) return p;
  }
  return "scenes/" + name + ".json";  // let the loader say it is missing
}

// "--iterations 1,2,4": positive numbers within [lo, hi].
bool parseNumbers(const std::string& option, const std::string& text, double lo, double hi, bool integers,
                  std::vector<double>& out, std::string& error) {
  out.clear();
  for (const std::string& s : splitList(text)) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (*end != '\0' || !(v >= lo && v <= hi) || (integers && v != double(long(v)))) {
      error = "haif bench: " + option + ": '" + s + "' is not " + (integers ? "an integer" : "a number") +
              " in [" + std::to_string(int(lo)) + ", " + std::to_string(int(hi)) + "]";
      return false;
    }
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  if (out.empty()) {
    error = "haif bench: " + option + ": expected a comma-separated list";
    return false;
  }
  return true;
}

BenchPoint point(const std::string& engine, const std::string& mode, double param, int threads) {
  BenchPoint p;
  p.spec.engine = engine;
  p.spec.solver.mode = mode;
  if (mode == "fixed")
    p.spec.solver.iterations = int(param);
  else
    p.spec.solver.budgetMs = param;
  p.threads = engine == "bullet" ? 1 : threads;
  return p;
}

bool samePoint(const BenchPoint& a, const BenchPoint& b) {
  return a.spec.engine == b.spec.engine && a.spec.solver.mode == b.spec.solver.mode && a.threads == b.threads &&
         a.spec.solver.iterations == b.spec.solver.iterations && a.spec.solver.budgetMs == b.spec.solver.budgetMs;
}

// Writes a bench's folder as one unit (staged, then renamed into place): the plots first, since the
// report names those written, then the CSV (markers[0]) and report.md. On failure: one message, 1.
int writeBenchOutput(const std::string& outDir, const std::vector<std::string>& markers,
                     const std::function<bool(const std::string& dir, std::string& error)>& writePlots,
                     const std::string& csv, const std::function<std::string()>& report) {
  std::string error;
  StagedFolder output;
  if (!output.open(outDir, markers, error) || !writePlots(output.path(), error) ||
      !writeFileAtomic(output.path() + "/" + markers[0], csv, error) ||
      !writeFileAtomic(output.path() + "/report.md", report(), error) || !output.commit(error)) {
    waitIfInterrupted();
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  return 0;
}

// --scaling: the stacks and pile families at each size, smallest first; DIR/scaling.csv,
// DIR/report.md and DIR/scaling.png.
int benchScaling(const std::vector<double>& sizes, int steps, int threads, const std::string& outDir) {
  std::string error;
  const std::vector<std::string> markers = {"scaling.csv", "report.md"};
  if (!checkOutputFolder(outDir, markers, error)) {
    std::fprintf(stderr, "haif bench: %s\n", error.c_str());
    return 1;
  }
  std::vector<ScalingResult> rows;
  for (const std::string family : {"stacks", "pile"}) {
    for (double n : sizes) {
      ScalingResult r;
      if (!runScalingPoint(family, int(n), steps, threads, r, error)) {
        waitIfInterrupted();
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
      }
      std::printf("%-7s %7d bodies  %2d thr  %9.3f ms/step (p95 %9.3f)  world %8.1f MB%s\n", r.family.c_str(),
                  r.bodies, r.threads, r.msMedian, r.msP95, r.worldMb, r.nan ? "  NaN!" : "");
      std::fflush(stdout);
      rows.push_back(r);
    }
  }
  std::string plot;
  if (writeBenchOutput(
          outDir, markers, [&](const std::string& dir, std::string& e) { return writeScalingPlot(dir, rows, plot, e); },
          scalingCsv(rows), [&] { return scalingMarkdown(rows, plot); }) != 0)
    return 1;
  std::printf("wrote %s/scaling.csv, %s/report.md%s\n", outDir.c_str(), outDir.c_str(),
              plot.empty() ? "" : (" and " + outDir + "/" + plot).c_str());
  return 0;
}

}  // namespace

int commandBench(int argc, char** argv) {
  CommandLine cl("bench",
                 {"--scenes", "--engines", "--steps", "--budget-ms", "--threads", "--out", "--error-every",
                  "--iterations", "--budgets", "--repeat", "--sizes"},
                 {"--quick", "--scaling"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  const bool isQuick = cl.has("--quick");
  if (cl.has("--scaling")) {
    int steps = isQuick ? 20 : 60, threads = int(tbb::info::default_concurrency());
    std::vector<double> sizes;
    if (!cl.getInt("--steps", 1, 1000000, steps, error) || !cl.getInt("--threads", 1, 1024, threads, error) ||
        !parseNumbers("--sizes", cl.get("--sizes", isQuick ? "1000,3000,10000" : "1000,3000,10000,30000,100000"), 10,
                      2000000, true, sizes, error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 2;
    }
    std::sort(sizes.begin(), sizes.end());
    return benchScaling(sizes, steps, threads, cl.get("--out", "output/bench"));
  }
  // --quick: fewer scenes, steps and sweep points, to finish in a few minutes on a small machine.
  int steps = isQuick ? 120 : 300, errorEvery = 0, rounds = 1;
  double seedBudget = 4.0;
  // --threads 1,2,4,8,16 sweeps thread counts (every set-up at each); the seed's table uses the most.
  std::vector<double> iterations, budgets, threadCounts;
  if (!cl.getInt("--steps", 1, 1000000, steps, error) ||
      !parseNumbers("--threads", cl.get("--threads", std::to_string(tbb::info::default_concurrency())), 1, 1024,
                    true, threadCounts, error) ||
      !cl.getInt("--repeat", 1, 100, rounds, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  // Ten solve-error samples per run by default (four with --quick): each costs a converged solve,
  // which on the big scenes takes longer than the steps themselves.
  errorEvery = std::max(1, steps / (isQuick ? 4 : 10));
  if (!cl.getInt("--error-every", 0, 100000, errorEvery, error) ||
      !cl.getDouble("--budget-ms", 0.01, 1e6, seedBudget, error) ||
      !parseNumbers("--iterations", cl.get("--iterations", isQuick ? "1,4,16,64" : "1,2,4,8,16,32,64"), 1, 10000,
                    true, iterations, error) ||
      !parseNumbers("--budgets", cl.get("--budgets", isQuick ? "1,4" : "1,2,4,8"), 0.01, 1e6, false, budgets,
                    error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  std::vector<std::string> engines = splitList(cl.get("--engines", bulletAvailable() ? "haif,bullet" : "haif"));
  for (const std::string& e : engines) {
    if (e != "haif" && e != "bullet") {
      std::fprintf(stderr, "haif bench: --engines: unknown engine '%s' (haif, bullet)\n", e.c_str());
      return 2;
    }
    if (e == "bullet" && !bulletAvailable()) {
      std::fprintf(stderr,
                   "haif bench: --engines: bullet: this haif was built without Bullet (install libbullet-dev, "
                   "then re-run cmake)\n");
      return 2;
    }
  }
  if (engines.empty()) {
    std::fprintf(stderr, "haif bench: --engines: expected haif, bullet or haif,bullet\n");
    return 2;
  }
  const std::string defaultScenes = isQuick ? "stacks_100,stacks_500,stacks_1000,pyramid_15"
                                            : "stacks_100,stacks_500,stacks_1000,stacks_2000,pyramid_15,"
                                              "large_pyramid,many_pyramids";
  const std::vector<std::string> scenes = splitList(cl.get("--scenes", defaultScenes));
  const std::string outDir = cl.get("--out", "output/bench");
  // Every scene must load before hours are spent on the others.
  std::vector<std::string> paths;
  for (const std::string& name : scenes) {
    SceneDesc scene;
    paths.push_back(findScene(name));
    if (!loadSceneFile(paths.back(), scene, error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "haif bench: --scenes: expected a comma-separated list of scene names or files\n");
    return 2;
  }
  // Checked now, written at the end: the report folder appears whole (tools/staged_output.h).
  const std::vector<std::string> markers = {"results.csv", "report.md"};
  if (!checkOutputFolder(outDir, markers, error)) {
    std::fprintf(stderr, "haif bench: %s\n", error.c_str());
    return 1;
  }
  const bool haif = std::find(engines.begin(), engines.end(), "haif") != engines.end();
  const bool bullet = std::find(engines.begin(), engines.end(), "bullet") != engines.end();

  // The sweep, then the seed's set-ups that the sweep did not already run.
  std::vector<BenchPoint> points;
  auto add = [&](const BenchPoint& p) {
    for (const BenchPoint& q : points)
      if (samePoint(p, q)) return;
    points.push_back(p);
  };
  std::sort(threadCounts.begin(), threadCounts.end());
  const int threads = int(threadCounts.back());
  for (double t : threadCounts) {
    for (const std::string& e : engines)
      for (double i : iterations) add(point(e, "fixed", i, int(t)));
    if (haif)
      for (double b : budgets) add(point("haif", "adaptive", b, int(t)));
  }
  if (haif) add(point("haif", "fixed", 10, 1));
  if (haif) add(point("haif", "adaptive", seedBudget, threads));
  if (bullet) add(point("bullet", "fixed", 10, 1));

  // --repeat: every set-up of a scene runs once per round, rounds one after another, so set-ups
  // that are compared see the same drifts of the machine's speed.
  std::vector<BenchResult> rows;
  for (const std::string& path : paths) {
    std::vector<std::vector<BenchResult>> runs(points.size());
    for (int round = 0; round < rounds; ++round) {
      for (size_t i = 0; i < points.size(); ++i) {
        BenchResult r;
        if (!runBenchPoint(path, points[i], steps, errorEvery, r, error)) {
          waitIfInterrupted();
          std::fprintf(stderr, "%s\n", error.c_str());
          return 1;
        }
        char solveError[32] = "n/a", roundText[32] = "";
        if (!std::isnan(r.solveError)) std::snprintf(solveError, sizeof solveError, "%.4f", r.solveError);
        if (rounds > 1) std::snprintf(roundText, sizeof roundText, "  (round %d/%d)", round + 1, rounds);
        std::printf("%-14s %-22s %2d thr  %9.3f ms/step (p95 %9.3f)  solve error %-7s  max pen %.4f m  "
                    "mean drop %.4f m  jitter %.4f m/s%s%s\n",
                    r.scene.c_str(), r.label.c_str(), r.threads, r.msMedian, r.msP95, solveError,
                    r.maxPenetration, r.meanDrop, r.jitter, r.nan ? "  NaN!" : "", roundText);
        std::fflush(stdout);
        runs[i].push_back(std::move(r));
      }
    }
    for (const std::vector<BenchResult>& r : runs) rows.push_back(combineRounds(r));
  }

  BenchReportInfo info;
  info.steps = steps;
  info.threads = threads;
  for (double t : threadCounts) info.threadCounts.push_back(int(t));
  info.errorEvery = errorEvery;
  info.seedBudgetMs = seedBudget;
  info.quick = isQuick;
  info.rounds = rounds;
  info.engines = engines;
  if (!benchPlotsAvailable()) info.plotsNote = "this haif was built without the renderer (HAIF_BUILD_RENDER=OFF)";
  if (writeBenchOutput(
          outDir, markers,
          [&](const std::string& dir, std::string& e) { return writeBenchPlots(dir, rows, info.plots, e); },
          benchResultsCsv(rows), [&] { return benchReportMarkdown(rows, info); }) != 0)
    return 1;
  std::printf("wrote %s/results.csv, %s/report.md and %zu plot(s)\n", outDir.c_str(), outDir.c_str(),
              info.plots.size());
  return 0;
}

}  // namespace haif
