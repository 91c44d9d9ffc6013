#include "tools/suite_runner.h"

#include "render/png_io.h"
#include "tools/atomic_file.h"
#include "tools/frame_diff.h"
#include "tools/run_report.h"
#include "tools/staged_output.h"
#include "tools/stress_probe.h"
#include "tools/stress_suite.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace haif {

namespace fs = std::filesystem;

namespace {

// The first failing frames a render job lists one by one; the rest are counted.
constexpr size_t kFramesListed = 5;

std::string percent(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * ratio);
  return text;
}

SuiteCheckOutcome fromStress(const StressCheckResult& c) {
  SuiteCheckOutcome o;
  o.check = c.check;
  o.criterion = c.criterion;
  o.value = c.value;
  o.limit = c.limit;
  o.pass = c.pass;
  return o;
}

// The no-NaN rule every simulating job has, listed first as `haif stress` lists it.
SuiteCheckOutcome noNanCheck(bool nan) {
  SuiteCheckOutcome o;
  o.check = "no_nan";
  o.criterion = "no NaN or inf in the state";
  o.value = nan ? 1.0 : 0.0;
  o.pass = !nan;
  return o;
}

// A bound on a number of summary.json; a number the run did not write fails with a reason.
SuiteCheckOutcome judgeSummary(const SuiteCheck& c, const nlohmann::json& summary) {
  SuiteCheckOutcome o;
  o.check = c.key;
  if (c.hasMin && c.hasMax)
    o.criterion = suiteNumber(c.min) + " <= " + c.key + " <= " + suiteNumber(c.max);
  else
    o.criterion = c.key + (c.hasMin ? " >= " + suiteNumber(c.min) : " <= " + suiteNumber(c.max));
  o.limit = c.hasMax ? c.max : c.min;
  const auto it = summary.find(c.key);
  if (it == summary.end() || !it->is_number()) {
    o.criterion += " (not in this run's summary.json)";
    return o;
  }
  o.value = it->get<double>();
  o.pass = (!c.hasMin || o.value >= c.min) && (!c.hasMax || o.value <= c.max);
  return o;
}

// Fills the result's verdict: why it could not run first, then its failed checks, then the rest.
void conclude(SuiteJobResult& r, const std::string& error) {
  std::vector<std::string> reasons;
  if (!error.empty()) reasons.push_back(error);
  for (const SuiteCheckOutcome& c : r.checks)
    if (!c.pass) reasons.push_back(c.criterion + ": got " + suiteNumber(c.value));
  r.failures.insert(r.failures.begin(), reasons.begin(), reasons.end());
  r.error = !error.empty();
  r.pass = !r.error && r.failures.empty();
}

struct Clock {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

class JobRunner {
 public:
  JobRunner(const SuiteJob& job, const SuiteRunContext& ctx) : job_(job), ctx_(ctx) {
    threads_ = job.threads > 0 ? job.threads : ctx.threads;
    rel_ = "jobs/" + job.name;
    dir_ = ctx.reportDir + "/" + rel_;
    r_.index = job.index;
    r_.name = job.name;
    r_.kind = suiteJobKindName(job.kind);
    r_.scene = job.sceneGiven;
  }

  SuiteJobResult run() {
    const Clock clock;
    std::string error;
    const bool ok = job_.kind == SuiteJobKind::Stress ? runStress(error) : simulate(error);
    conclude(r_, ok ? std::string() : error);
    r_.wallSeconds = clock.seconds();
    return std::move(r_);
  }

 private:
  bool runStress(std::string& error) {
    StressSceneResult s;
    if (!runStressScene(job_.scenePath, job_.quick, threads_, s, error)) return false;
    r_.setup = {{"mode", "fixed"}, {"iterations", s.iterations}, {"frames", s.steps}, {"quick", job_.quick},
                {"threads", threads_}, {"dt", s.dt}};
    if (s.skipped) {
      r_.skipped = true;
      r_.notes.push_back(s.note.empty() ? "not in the quick set" : s.note);
      return true;
    }
    r_.metrics["nan_detected"] = s.nan;
    r_.metrics["steps_run"] = s.stepsRun;
    r_.metrics["bodies"] = s.bodies;
    for (const auto& [key, value] : s.metrics) r_.metrics[key] = value;
    r_.checks.push_back(noNanCheck(s.nan));
    for (const StressCheckResult& c : s.checks) r_.checks.push_back(fromStress(c));
    return true;
  }

  // Run and render jobs: simulate like `haif run`, judge the checks, diff the frames.
  bool simulate(std::string& error) {
    SolverSpec spec;
    spec.mode = job_.mode;
    spec.iterations = job_.iterations;
    spec.budgetMs = job_.budgetMs;
    r_.setup = {{"mode", job_.mode},
                {"iterations", job_.iterations > 0 ? nlohmann::json(job_.iterations) : nlohmann::json(nullptr)},
                {"budget_ms", job_.mode == "fixed" ? nlohmann::json(nullptr) : nlohmann::json(job_.budgetMs)},
                {"threads", threads_},
                {"error_every", job_.errorEvery}};
    Simulation sim;
    if (!makeSimulation(job_.scenePath, spec, threads_, sim, error)) return false;
    World& world = *sim.world;
    const int frames = job_.frames > 0 ? job_.frames : sim.scene.settings.frames;
    r_.setup["frames"] = frames;
    if (job_.mode == "fixed") r_.setup["iterations"] = world.settings().iterations;
    world.setSolveErrorInterval(job_.errorEvery);
    if (!ensureWritableDir(dir_, error)) return false;

    std::vector<StressCheck> stressChecks;
    for (const SuiteCheck& c : job_.checks)
      if (c.stress) stressChecks.push_back(c.stressCheck);
    RunMetrics metrics;
    metrics.begin(world, uint64_t(frames));
    StressProbe probe;
    probe.begin(world, stressChecks);

    const bool render = job_.kind == SuiteJobKind::Render;
    const std::string framesDir = dir_ + "/frames";
    if (render) {
      r_.setup["width"] = job_.width;
      r_.setup["height"] = job_.height;
      r_.setup["frame_every"] = job_.frameEvery;
      r_.setup["reference"] = job_.referenceGiven;
      if (!ctx_.painter) {
        error = "this build has no renderer: render jobs cannot run";
        return false;
      }
      if (!ensureWritableDir(framesDir, error) || !ctx_.painter->begin(sim, job_.width, job_.height, error))
        return false;
    }
    std::vector<StepStats> stats;
    std::vector<uint8_t> pixels;
    std::string drawError;
    int frameIndex = 0;
    const bool finite = runSteps(sim, frames, stats, metrics, [&](const World& w) {
      probe.afterStep(w);
      if (!render || !drawError.empty() || w.lastStats().step % uint64_t(job_.frameEvery) != 0) return;
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%05d.png", frameIndex++);
      if (!ctx_.painter->paint(sim, pixels, drawError) ||
          !render::writePng(framesDir + name, job_.width, job_.height, pixels.data(), &drawError))
        drawError = "frame " + std::to_string(frameIndex - 1) + ": " + drawError;
    });
    if (!drawError.empty()) {
      error = drawError;
      return false;
    }

    RunInfo info = runInfoFor(sim, job_.budgetMs, threads_);
    info.stateHash = world.stateHash();
    const std::string summary = summaryJson(info, stats, metrics, world);
    if (!writeFileAtomic(dir_ + "/summary.json", summary, error) ||
        !writeFileAtomic(dir_ + "/stats.csv", statsCsv(stats), error))
      return false;
    r_.artifacts = {rel_ + "/summary.json", rel_ + "/stats.csv"};
    r_.metrics = nlohmann::json::parse(summary);
    r_.metrics["steps_run"] = stats.size();

    r_.checks.push_back(noNanCheck(!finite));
    size_t stressIndex = 0;
    for (const SuiteCheck& c : job_.checks) {
      if (!c.stress) {
        r_.checks.push_back(judgeSummary(c, r_.metrics));
        continue;
      }
      StressCheckResult s = judgeStressCheck(c.stressCheck, stressIndex++, probe, metrics, world);
      s.pass = s.pass && finite;
      r_.checks.push_back(fromStress(s));
    }
    if (!render) return true;
    r_.artifacts.push_back(rel_ + "/frames");
    return ctx_.updateReferences ? updateReference(framesDir, error) : diffWithReference(framesDir, error);
  }

  // --update-references: the frames just drawn become the reference, replacing the old folder whole.
  bool updateReference(const std::string& framesDir, std::string& error) {
    StagedFolder ref;
    if (!ref.open(job_.referencePath, {"frame_00000.png"}, error)) return false;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(framesDir, ec)) {
      if (!fs::copy_file(e.path(), fs::path(ref.path()) / e.path().filename(), ec)) break;
    }
    if (ec) {
      error = "cannot copy the frames into the reference '" + job_.referencePath + "': " + ec.message();
      return false;
    }
    if (!ref.commit(error)) return false;
    r_.notes.push_back("reference frames written to " + job_.referenceGiven);
    return true;
  }

  bool diffWithReference(const std::string& framesDir, std::string& error) {
    FrameFolder reference, fresh;
    if (!openFrameFolder(job_.referencePath, "reference", reference, error) ||
        !openFrameFolder(framesDir, "new", fresh, error) || !checkFramePairs(reference, fresh, error))
      return false;
    DiffOptions options;
    options.threshold = job_.diff.threshold;
    options.detectAntialiasing = job_.diff.antialiasing;
    for (const SuiteDiffSpec::Rect& m : job_.diff.masks) options.masks.push_back(PixelRect{m.x0, m.y0, m.x1, m.y1});
    FrameThresholds limits;
    limits.maxDiffRatio = job_.diff.maxDiffRatio;
    limits.minSsim = job_.diff.minSsim;
    const std::string diffDir = dir_ + "/diff";
    std::vector<FrameVerdict> verdicts;
    if (!ensureWritableDir(diffDir, error) ||
        !diffFrameFolders(reference, fresh, options, limits, diffDir, verdicts, error))
      return false;
    r_.artifacts.push_back(rel_ + "/diff");

    double worstRatio = 0.0, lowestSsim = 1.0;
    size_t failed = 0;
    for (const FrameVerdict& v : verdicts) {
      worstRatio = std::max(worstRatio, v.result.diffRatio);
      lowestSsim = std::min(lowestSsim, v.result.ssim);
      if (v.pass) continue;
      if (++failed <= kFramesListed)
        r_.failures.push_back(v.name + ": " + percent(v.result.diffRatio) + " of pixels differ (limit " +
                              percent(limits.maxDiffRatio) + "), SSIM " + suiteNumber(v.result.ssim) + " (limit " +
                              suiteNumber(limits.minSsim) + ")");
    }
    if (failed > kFramesListed)
      r_.failures.push_back("... and " + std::to_string(failed - kFramesListed) + " more frames over the thresholds");
    // The diff is one more check, listed with the others; the failing frames follow as reasons.
    SuiteCheckOutcome check;
    check.check = "diff_frames_failed";
    check.criterion = "diff_frames_failed <= 0 (a frame fails with over " + percent(limits.maxDiffRatio) +
                      " of its pixels differing or SSIM under " + suiteNumber(limits.minSsim) + ")";
    check.value = double(failed);
    check.limit = 0.0;
    check.pass = failed == 0;
    r_.checks.push_back(check);
    r_.metrics["diff_frames"] = verdicts.size();
    r_.metrics["diff_frames_failed"] = failed;
    r_.metrics["diff_worst_ratio"] = worstRatio;
    r_.metrics["diff_lowest_ssim"] = lowestSsim;
    return true;
  }

  const SuiteJob& job_;
  const SuiteRunContext& ctx_;
  int threads_ = 1;
  std::string rel_, dir_;
  SuiteJobResult r_;
};

}  // namespace

SuiteJobResult runSuiteJob(const SuiteJob& job, const SuiteRunContext& ctx) { return JobRunner(job, ctx).run(); }

}  // namespace haif
