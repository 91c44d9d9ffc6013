// haif bench: the seed paper's comparison on the stacks_N scenes, sequential (1 thread, fixed 10
// iterations) against HAIF (all threads, adaptive, 4 ms budget): step time, FPS, improvement, and
// the solve error each one costs. Writes DIR/bench.csv and DIR/bench.md.
#include "app/cli.h"
#include "app/commands.h"
#include "tools/atomic_file.h"
#include "tools/run_report.h"
#include "tools/simulation.h"

#include <tbb/info.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace haif {

namespace {

struct BenchRow {
  std::string scene, setup;
  uint32_t bodies = 0;
  int threads = 1;
  double median = 0, p95 = 0, missRate = 0, iterMean = 0, solveError = NAN, meanDrop = 0, maxPen = 0;
};

std::string findScene(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  for (const std::string& dir : {std::string("scenes/"), std::string(HAIF_SOURCE_DIR) + "/scenes/"}) {
    const std::string p = dir + name + ".json";
    if (std::filesystem::exists(p)) return p;
  }
  return "scenes/" + name + ".json";  // let the loader say it is missing
}

bool benchOne(const std::string& scenePath, const SolverSpec& spec, int threads, int steps, int errorEvery,
              BenchRow& row, std::string& error) {
  Simulation sim;
  if (!makeSimulation(scenePath, spec, threads, sim, error)) return false;
  sim.world->setSolveErrorInterval(errorEvery);
  std::vector<StepStats> stats;
  RunMetrics metrics;
  metrics.begin(*sim.world, uint64_t(steps));
  runSteps(sim, steps, stats, metrics);
  std::vector<double> ms;
  double miss = 0, it = 0, err = 0;
  int errN = 0;
  for (const StepStats& s : stats) {
    ms.push_back(s.totalMs);
    miss += s.deadlineMiss;
    it += s.iterationsChosen;
    if (!std::isnan(s.solveError)) {
      err += s.solveError;
      ++errN;
    }
  }
  row.scene = sim.scene.name;
  row.bodies = sim.world->bodyCount();
  row.threads = threads;
  row.median = quantile(ms, 0.5);
  row.p95 = quantile(ms, 0.95);
  row.missRate = spec.mode == "fixed" ? 0.0 : miss / double(stats.size());
  row.iterMean = it / double(stats.size());
  row.solveError = errN ? err / errN : NAN;
  row.meanDrop = metrics.meanDrop(*sim.world);
  row.maxPen = metrics.maxPenetration();
  return true;
}

}  // namespace

int commandBench(int argc, char** argv) {
  CommandLine cl("bench", {"--scenes", "--steps", "--budget-ms", "--threads", "--out", "--error-every"}, {});
  std::string error;
  int steps = 300, threads = int(tbb::info::default_concurrency()), errorEvery = 10;
  double budget = 4.0;
  if (!cl.parse(argc, argv, 2, error) || !cl.getInt("--steps", 1, 1000000, steps, error) ||
      !cl.getInt("--threads", 1, 1024, threads, error) || !cl.getInt("--error-every", 0, 100000, errorEvery, error) ||
      !cl.getDouble("--budget-ms", 0.01, 1e6, budget, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  const std::string outDir = cl.get("--out", "output/bench");
  if (!ensureWritableDir(outDir, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::vector<std::string> scenes;
  std::stringstream ss(cl.get("--scenes", "stacks_100,stacks_500,stacks_1000,stacks_2000"));
  for (std::string s; std::getline(ss, s, ',');)
    if (!s.empty()) scenes.push_back(s);

  std::string csv = "scene,setup,bodies,threads,ms_per_step_median,ms_per_step_p95,fps,deadline_miss_rate,"
                    "iterations_mean,solve_error_mean,mean_drop_m,max_penetration_m\n";
  std::string md = "| scene | bodies | sequential ms/step | sequential FPS | HAIF ms/step | HAIF FPS | improvement |"
                   " sequential solve error | HAIF solve error | HAIF iterations (mean) | HAIF deadline misses |\n"
                   "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  char line[512];
  for (const std::string& name : scenes) {
    const std::string path = findScene(name);
    SolverSpec seq;
    seq.mode = "fixed";
    seq.iterations = 10;
    SolverSpec hf;
    hf.mode = "adaptive";
    hf.budgetMs = budget;
    BenchRow a, b;
    if (!benchOne(path, seq, 1, steps, errorEvery, a, error) || !benchOne(path, hf, threads, steps, errorEvery, b, error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    a.setup = "sequential fixed:10";
    b.setup = "haif adaptive:" + std::to_string(budget).substr(0, 4);
    for (const BenchRow* r : {&a, &b}) {
      std::snprintf(line, sizeof line, "%s,%s,%u,%d,%.4f,%.4f,%.1f,%.4f,%.2f,%.5f,%.5f,%.5f\n", r->scene.c_str(),
                    r->setup.c_str(), r->bodies, r->threads, r->median, r->p95, 1000.0 / r->median, r->missRate,
                    r->iterMean, r->solveError, r->meanDrop, r->maxPen);
      csv += line;
    }
    std::snprintf(line, sizeof line, "| %s | %u | %.3f | %.0f | %.3f | %.0f | %.2fx | %.4f | %.4f | %.1f | %.1f%% |\n",
                  a.scene.c_str(), a.bodies, a.median, 1000.0 / a.median, b.median, 1000.0 / b.median,
                  a.median / b.median, a.solveError, b.solveError, b.iterMean, 100.0 * b.missRate);
    md += line;
    std::printf("%s", line);
    std::fflush(stdout);
  }
  md = "# HAIF bench: sequential against HAIF\n\nSequential: 1 thread, fixed 10 iterations. HAIF: " +
       std::to_string(threads) + " threads, adaptive, " + std::to_string(budget) + " ms budget. " +
       std::to_string(steps) + " steps per run; solve error (DESIGN.md §5) sampled every " +
       std::to_string(errorEvery) + " steps.\n\n" + md;
  if (!writeFileAtomic(outDir + "/bench.csv", csv, error) || !writeFileAtomic(outDir + "/bench.md", md, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("wrote %s/bench.csv and %s/bench.md\n", outDir.c_str(), outDir.c_str());
  return 0;
}

}  // namespace haif
