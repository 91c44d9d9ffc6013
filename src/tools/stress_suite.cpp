#include "tools/stress_suite.h"

#include "tools/run_report.h"
#include "tools/simulation.h"
#include "tools/stress_probe.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace haif {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

StressCheckResult judgeStressCheck(const StressCheck& c, size_t i, const StressProbe& probe, const RunMetrics& metrics,
                                   const World& world) {
  StressCheckResult r;
  r.check = c.name;
  r.limit = c.limit;
  const std::string of = c.body >= 0 ? "(body " + std::to_string(c.body) + ")" : "";
  bool atLeast = false;  // the metric must reach the limit rather than stay below it
  switch (c.kind) {
    case StressCheckKind::MaxDrop: r.value = c.body >= 0 ? probe.followed(i) : metrics.maxDrop(world); break;
    case StressCheckKind::MinDrop:
      r.value = probe.followed(i);
      atLeast = true;
      break;
    case StressCheckKind::MaxPenetration: r.value = metrics.maxPenetration(); break;
    case StressCheckKind::FinalPenetration: r.value = currentMaxPenetration(world); break;
    case StressCheckKind::PeakSpeed: r.value = c.body >= 0 ? probe.followed(i) : probe.peakSpeed(); break;
    case StressCheckKind::EnergyGainRatio: r.value = probe.energyGainRatio(); break;
    case StressCheckKind::AngularMomentumDrift: r.value = probe.angularMomentumDrift(); break;
    case StressCheckKind::MaxJointError: r.value = metrics.maxJointError(); break;
    case StressCheckKind::SpeedLimited: r.value = double(probe.speedLimited()); break;
    case StressCheckKind::IntermediateAxisFlip:
      r.value = probe.followed(i);
      atLeast = true;
      break;
    case StressCheckKind::NoTunnel:
      // The centre must stay strictly on its start side of the plane.
      r.value = probe.followed(i);
      r.pass = r.value > c.limit;
      r.criterion = "no_tunnel" + of + ": distance on the start side > 0 m";
      return r;
  }
  r.pass = atLeast ? r.value >= c.limit : r.value <= c.limit;
  r.criterion = c.name + of + (atLeast ? " >= " : " <= ") + number(c.limit);
  return r;
}

bool findStressScenes(const std::string& dir, std::vector<std::string>& paths, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    error = dir + ": not a folder of stress scenes";
    return false;
  }
  paths.clear();
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".json") paths.push_back(e.path().string());
  if (ec) {
    error = dir + ": cannot list (" + ec.message() + ")";
    return false;
  }
  if (paths.empty()) {
    error = dir + ": no stress scenes (*.json) in it";
    return false;
  }
  std::sort(paths.begin(), paths.end());
  return true;
}

bool runStressScene(const std::string& path, bool quick, int threads, StressSceneResult& out, std::string& error) {
  Simulation sim;
  SolverSpec spec;  // fixed mode, the scene's iteration count
  if (!makeSimulation(path, spec, threads, sim, error)) return false;
  const StressDesc& desc = sim.scene.stress;
  if (!desc.given) {
    error = path + ": no \"stress\" block: a stress scene needs {\"steps\": N, \"checks\": [...]} (docs/stress.md)";
    return false;
  }
  StressSceneResult r;
  r.name = sim.scene.name;
  r.file = path;
  r.bodies = sim.world->bodyCount();
  r.steps = quick ? desc.quickSteps : desc.steps;
  r.iterations = sim.world->settings().iterations;
  r.dt = sim.world->settings().dt;
  if (quick) r.note = desc.quickNote;
  if (quick && !desc.inQuick) {
    r.skipped = true;
    r.steps = 0;
    out = std::move(r);
    return true;
  }

  World& world = *sim.world;
  RunMetrics metrics;
  metrics.begin(world, uint64_t(r.steps));
  StressProbe probe;
  probe.begin(world, desc.checks);
  std::vector<StepStats> stats;
  const auto t0 = std::chrono::steady_clock::now();
  r.nan = !runSteps(sim, r.steps, stats, metrics, [&](const World& w) { probe.afterStep(w); });
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.stepsRun = int(stats.size());

  std::vector<double> ms;
  for (const StepStats& s : stats) ms.push_back(s.totalMs);
  r.metrics = {{"max_drop_m", metrics.maxDrop(world)},
               {"mean_drop_m", metrics.meanDrop(world)},
               {"max_penetration_m", metrics.maxPenetration()},
               {"final_penetration_m", currentMaxPenetration(world)},
               {"peak_speed", probe.peakSpeed()},
               {"energy_gain_ratio", probe.energyGainRatio()},
               {"angular_momentum_drift", probe.angularMomentumDrift()},
               {"max_joint_error_m", metrics.maxJointError()},
               {"speed_limited", double(probe.speedLimited())},
               {"rms_velocity_last_s", metrics.rmsVelocityLastSecond()},
               {"ms_per_step_median", quantile(ms, 0.5)}};
  r.pass = !r.nan;
  for (size_t i = 0; i < desc.checks.size(); ++i) {
    r.checks.push_back(judgeStressCheck(desc.checks[i], i, probe, metrics, world));
    if (!r.checks.back().pass || r.nan) r.checks.back().pass = false;
    r.pass = r.pass && r.checks.back().pass;
  }
  out = std::move(r);
  return true;
}

std::string stressJson(const std::vector<StressSceneResult>& results, bool quick) {
  nlohmann::ordered_json j;
  int passed = 0, failed = 0, skipped = 0;
  for (const StressSceneResult& r : results) (r.skipped ? skipped : r.pass ? passed : failed) += 1;
  j["quick"] = quick;
  j["passed"] = passed;
  j["failed"] = failed;
  j["skipped"] = skipped;
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const StressSceneResult& r : results) {
    nlohmann::ordered_json s;
    s["name"] = r.name;
    s["file"] = r.file;
    if (r.skipped) s["pass"] = nullptr;
    else s["pass"] = r.pass;
    s["skipped"] = r.skipped;
    if (!r.note.empty()) s["note"] = r.note;
    s["bodies"] = r.bodies;
    s["steps"] = r.steps;
    s["steps_run"] = r.stepsRun;
    s["dt"] = r.dt;
    s["iterations"] = r.iterations;
    s["wall_s"] = r.wallSeconds;
    nlohmann::ordered_json m = nlohmann::ordered_json::object();
    if (!r.skipped) {
      m["nan_detected"] = r.nan;
      for (const auto& kv : r.metrics) m[kv.first] = kv.second;
    }
    s["metrics"] = m;
    nlohmann::ordered_json crit = nlohmann::ordered_json::array();
    if (!r.skipped)
      crit.push_back(
          {{"check", "no_nan"}, {"criterion", "no NaN or inf in the state"}, {"value", r.nan}, {"pass", !r.nan}});
    for (const StressCheckResult& c : r.checks)
      crit.push_back({{"check", c.check}, {"criterion", c.criterion}, {"value", c.value}, {"limit", c.limit},
                      {"pass", c.pass}});
    s["criterion"] = crit;
    scenes.push_back(s);
  }
  j["scenes"] = scenes;
  return j.dump(2) + "\n";
}

std::string stressLine(const StressSceneResult& r) {
  char buf[256];
  if (r.skipped) {
    std::snprintf(buf, sizeof buf, "%-24s SKIP  %s", r.name.c_str(),
                  r.note.empty() ? "not in the quick set" : r.note.c_str());
    return buf;
  }
  const StressCheckResult* key = r.checks.empty() ? nullptr : &r.checks.front();
  for (const StressCheckResult& c : r.checks)
    if (!c.pass) {
      key = &c;
      break;
    }
  std::string detail = r.nan ? "NaN after " + std::to_string(r.stepsRun) + " steps" : "";
  if (key) detail += (detail.empty() ? "" : "; ") + key->criterion + " (got " + number(key->value) + ")";
  std::snprintf(buf, sizeof buf, "%-24s %s  %s  [%d steps, %.1f s]", r.name.c_str(), r.pass ? "PASS" : "FAIL",
                detail.c_str(), r.steps, r.wallSeconds);
  return buf;
}

}  // namespace haif
