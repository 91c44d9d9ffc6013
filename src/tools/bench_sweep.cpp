#include "tools/bench_sweep.h"

#include "tools/engine_metrics.h"
#include "tools/run_report.h"

#include <algorithm>
#include <ctime>

namespace haif {

namespace {

double processCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

}  // namespace

BenchResult combineRounds(const std::vector<BenchResult>& runs) {
  auto lowerMedian = [&](double BenchResult::*field) {
    std::vector<double> v;
    for (const BenchResult& r : runs) v.push_back(r.*field);
    std::nth_element(v.begin(), v.begin() + (v.size() - 1) / 2, v.end());
    return v[(v.size() - 1) / 2];
  };
  const double ms = lowerMedian(&BenchResult::msMedian);
  BenchResult out = *std::find_if(runs.begin(), runs.end(), [&](const BenchResult& r) { return r.msMedian == ms; });
  out.msP95 = lowerMedian(&BenchResult::msP95);
  out.cpuMsMedian = lowerMedian(&BenchResult::cpuMsMedian);
  out.rounds = int(runs.size());
  out.msMin = out.msMax = ms;
  for (const BenchResult& r : runs) {
    out.msMin = std::min(out.msMin, r.msMedian);
    out.msMax = std::max(out.msMax, r.msMedian);
  }
  return out;
}

bool runBenchPoint(const std::string& scenePath, const BenchPoint& point, int steps, int errorEvery,
                   BenchResult& out, std::string& error) {
  std::unique_ptr<EngineRun> run = makeEngineRun(point.spec, scenePath, point.threads, error);
  if (!run) return false;
  run->setSolveErrorInterval(errorEvery);
  EngineMetrics metrics;
  metrics.begin(*run, uint64_t(steps));
  std::vector<double> ms, cpu;
  ms.reserve(size_t(steps));
  cpu.reserve(size_t(steps));
  double iterations = 0, misses = 0, errSum = 0;
  int errCount = 0, done = 0;
  for (; done < steps; ++done) {
    const double cpu0 = processCpuMs();
    const EngineStepInfo info = run->step();
    // Steps that measured the solve error include its reference solve here; the median shrugs them off.
    cpu.push_back(processCpuMs() - cpu0);
    ms.push_back(info.ms);
    iterations += info.iterations;
    misses += info.deadlineMiss ? 1 : 0;
    if (!std::isnan(info.solveError)) {
      errSum += info.solveError;
      ++errCount;
    }
    if (!metrics.afterStep(*run)) {
      ++done;
      break;  // NaN: the run is over, and says so in its row
    }
  }
  BenchResult r;
  r.scene = run->scene().name;
  r.bodies = run->bodyCount();
  r.engine = run->engine();
  r.mode = point.spec.solver.mode;
  r.param = r.mode == "fixed" ? double(point.spec.solver.iterations) : point.spec.solver.budgetMs;
  r.label = run->label();
  r.threads = run->threads();
  r.steps = done;
  r.msMedian = quantile(ms, 0.5);
  r.msMin = r.msMax = r.msMedian;
  r.msP95 = quantile(ms, 0.95);
  r.cpuMsMedian = quantile(cpu, 0.5);
  r.iterationsMean = done ? iterations / done : 0.0;
  r.missRate = done ? misses / done : 0.0;
  r.solveError = errCount ? errSum / errCount : NAN;
  r.maxPenetration = metrics.maxPenetration();
  r.rmsPenetration = metrics.rmsPenetration();
  r.maxPenetrationFraction = metrics.maxPenetrationFraction();
  r.meanDrop = metrics.meanDrop();
  r.maxDrop = metrics.maxDrop();
  r.jitter = metrics.jitter();
  r.nan = metrics.nanDetected();
  r.stateHash = run->stateHash();
  out = r;
  return true;
}

const std::vector<BenchMetric>& benchErrorMetrics() {
  static const std::vector<BenchMetric> metrics = {
      {"solve_error", "solve error e", [](const BenchResult& r) { return r.solveError; }},
      {"max_penetration", "max penetration (m)", [](const BenchResult& r) { return r.maxPenetration; }},
      {"mean_drop", "mean drop (m)", [](const BenchResult& r) { return r.meanDrop; }},
      {"jitter", "jitter: RMS speed, last second (m/s)", [](const BenchResult& r) { return r.jitter; }},
  };
  return metrics;
}

std::string benchCurveName(const BenchResult& r) {
  return r.engine + " " + r.mode + ", " + std::to_string(r.threads) + (r.threads == 1 ? " thread" : " threads");
}

}  // namespace haif
