#include "tools/run_report.h"

#include "scene/text_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace haif {

namespace {

std::string stageNames(uint32_t s) {
  static const char* names[] = {"broad", "narrow", "buoyancy", "mesh", "joints", "solve", "sleep"};
  std::string out;
  for (int i = 0; i < 7; ++i) {
    if (!(s & (1u << i))) continue;
    if (!out.empty()) out += '|';
    out += names[i];
  }
  return out;
}

}  // namespace

std::string statsCsv(const std::vector<StepStats>& steps) {
  std::string out =
      "step,collision_ms,solve_ms,integrate_ms,total_ms,budget_ms,deadline_miss,iterations_chosen,"
      "iterations_min,iterations_mean,iterations_max,row_iterations,residual,solve_error,islands,"
      "largest_island,awake_bodies,sleeping_bodies,contacts,contact_points,new_pairs,stages,joint_error_m,"
      "joint_error_rad,speed_limited,pinched,turn_projected\n";
  char line[512];
  for (const StepStats& s : steps) {
    char err[32];
    if (std::isnan(s.solveError)) err[0] = '\0';
    else std::snprintf(err, sizeof err, "%.6g", s.solveError);
    std::snprintf(line, sizeof line,
                  "%llu,%.4f,%.4f,%.4f,%.4f,%.3f,%d,%d,%d,%.3f,%d,%llu,%.6g,%s,%u,%u,%u,%u,%u,%u,%u,%s,%.6g,%.6g,%u,%u,%u\n",
                  (unsigned long long)s.step, s.collisionMs, s.solveMs, s.integrateMs, s.totalMs, s.budgetMs,
                  s.deadlineMiss ? 1 : 0, s.iterationsChosen, s.iterationsMin, s.iterationsMean, s.iterationsMax,
                  (unsigned long long)s.rowIterations, double(s.residual), err, s.islands, s.largestIsland,
                  s.awakeBodies, s.sleepingBodies, s.contacts, s.contactPoints, s.newPairs,
                  stageNames(s.stages).c_str(), double(s.jointErrorM), double(s.jointErrorRad), s.speedLimited,
                  s.pinchedBodies, s.turnProjected);
    out += line;
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0));
  return v[k];
}

std::string summaryJson(const RunInfo& info, const std::vector<StepStats>& steps, const RunMetrics& m,
                        const World& world) {
  std::vector<double> ms;
  ms.reserve(steps.size());
  double misses = 0, itSum = 0, errSum = 0;
  uint64_t limited = 0, limitedSteps = 0, pinchedSteps = 0, turnProjected = 0;
  uint32_t pinchedMax = 0;
  int itMin = steps.empty() ? 0 : 1 << 30, itMax = 0, errCount = 0;
  for (const StepStats& s : steps) {
    ms.push_back(s.totalMs);
    limited += s.speedLimited;
    limitedSteps += s.speedLimited > 0 ? 1 : 0;
    pinchedSteps += s.pinchedBodies > 0 ? 1 : 0;
    pinchedMax = std::max(pinchedMax, s.pinchedBodies);
    turnProjected += s.turnProjected;
    misses += s.deadlineMiss ? 1 : 0;
    itSum += s.iterationsChosen;
    itMin = std::min(itMin, s.iterationsChosen);
    itMax = std::max(itMax, s.iterationsChosen);
    if (!std::isnan(s.solveError)) {
      errSum += s.solveError;
      ++errCount;
    }
  }
  const double n = steps.empty() ? 1.0 : double(steps.size());
  nlohmann::ordered_json j;
  j["scene"] = info.scene;
  j["scene_hash"] = hashText(info.sceneHash);
  j["bodies"] = info.bodies;
  j["steps"] = steps.size();
  j["threads"] = info.threads;
  j["mode"] = info.mode;
  j["budget_ms"] = info.budgetMs;
  j["residual_tolerance"] = info.residualTolerance;
  j["ms_per_step_median"] = quantile(ms, 0.5);
  j["ms_per_step_p95"] = quantile(ms, 0.95);
  j["ms_per_step_p99"] = quantile(ms, 0.99);
  j["deadline_miss_rate"] = info.budgetMs > 0 ? misses / n : 0.0;
  if (info.budgetMs > 0) {
    // The floor: steps run at the fewest iterations the controller may choose. Those that still
    // overran are misses no choice of the controller could avoid; when they are more than 1 % of
    // the steps (the miss rate the controller aims under), the budget is infeasible for the scene.
    std::vector<double> floorMs;
    size_t floorMisses = 0;
    for (const StepStats& s : steps)
      if (s.iterationsChosen <= info.iMin) {
        floorMs.push_back(s.totalMs);
        floorMisses += s.deadlineMiss ? 1 : 0;
      }
    j["i_min"] = info.iMin;
    j["floor_steps"] = floorMs.size();
    j["floor_misses"] = floorMisses;
    if (floorMs.empty()) j["floor_ms_median"] = nullptr;
    else j["floor_ms_median"] = quantile(floorMs, 0.5);
    j["budget_feasible"] = double(floorMisses) <= 0.01 * n;
  }
  j["iterations_mean"] = itSum / n;
  j["iterations_min"] = itMin;
  j["iterations_max"] = itMax;
  j["max_penetration_m"] = m.maxPenetration();
  j["max_penetration_fraction"] = m.maxPenetrationFraction();
  j["rms_penetration_m"] = m.rmsPenetration();
  j["mean_drop_m"] = m.meanDrop(world);
  j["max_drop_m"] = m.maxDrop(world);
  j["rms_velocity_last_s"] = m.rmsVelocityLastSecond();
  if (errCount > 0) j["solve_error_mean"] = errSum / errCount;
  else j["solve_error_mean"] = nullptr;
  j["solve_error_samples"] = errCount;
  j["energy_drift_relative"] = m.energyDriftRelative(world);
  uint32_t broken = 0;
  for (uint32_t i = 0; i < world.jointCount(); ++i) broken += world.joint(i).broken ? 1u : 0u;
  j["joints"] = world.jointCount();
  j["joints_broken"] = broken;
  j["max_joint_error_m"] = m.maxJointError();
  j["rms_joint_error_m"] = m.rmsJointError();
  j["max_joint_error_rad"] = m.maxJointErrorAngle();
  j["nan_detected"] = m.nanDetected();
  j["speed_limited"] = limited;
  j["speed_limited_steps"] = limitedSteps;
  j["pinched_steps"] = pinchedSteps;
  j["pinched_max"] = pinchedMax;
  j["turn_projected"] = turnProjected;
  j["state_hash"] = hashText(info.stateHash);
  if (info.renderMsPerFrameMedian >= 0) j["render_ms_per_frame_median"] = info.renderMsPerFrameMedian;
  if (!info.renderPhaseMsMedian.empty()) {
    nlohmann::ordered_json phases = nlohmann::ordered_json::object();
    for (const auto& [name, ms] : info.renderPhaseMsMedian) phases[name] = ms;
    j["render_phase_ms_median"] = phases;
  }
  return j.dump(2) + "\n";
}

const std::vector<std::string>& summaryNumberKeys() {
  static const std::vector<std::string> keys = [] {
    World empty;  // no bodies: summaryJson only reads counts from it
    RunInfo info;
    info.budgetMs = 1.0;  // a budgeted run also writes i_min, floor_* and budget_feasible
    info.renderMsPerFrameMedian = 0.0;
    RunMetrics metrics;
    metrics.begin(empty, 1);
    std::vector<std::string> out;
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(summaryJson(info, {}, metrics, empty));
    for (const auto& [key, value] : j.items())
      if (value.is_number() || value.is_null()) out.push_back(key);
    return out;
  }();
  return keys;
}

std::string hashText(uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", (unsigned long long)hash);
  return text;
}

bool readChosenIterations(const std::string& path, std::vector<int>& out, std::string& error) {
  std::string text;
  if (!readTextFile(path, "replay log", text, error)) return false;
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) {
    error = path + ":1: empty replay log";
    return false;
  }
  int column = -1, k = 0;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ','); ++k)
    if (cell == "iterations_chosen") column = k;
  if (column < 0) {
    error = path + ":1: no iterations_chosen column (is this a HAIF stats.csv?)";
    return false;
  }
  out.clear();
  for (int row = 2; std::getline(in, line); ++row) {
    std::stringstream ls(line);
    std::string cell;
    for (int c = 0; c <= column && std::getline(ls, cell, ','); ++c) {}
    char* end = nullptr;
    const long v = std::strtol(cell.c_str(), &end, 10);
    if (cell.empty() || *end != '\0' || v < 1 || v > 100000) {
      error = path + ":" + std::to_string(row) + ": iterations_chosen: not a positive integer ('" + cell + "')";
      return false;
    }
    out.push_back(int(v));
  }
  return true;
}

bool readReplayLog(const std::string& statsPath, ReplayLog& out, std::string& error) {
  ReplayLog log;
  if (!readChosenIterations(statsPath, log.iterations, error)) return false;
  const std::string path = (std::filesystem::path(statsPath).parent_path() / "summary.json").string();
  std::string text;
  if (!readTextFile(path, "run summary", text, error)) {
    error += ": replay reads the run's summary.json beside its stats.csv";
    return false;
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    error = path + ": not a HAIF summary.json (no JSON object)";
    return false;
  }
  const auto hash = j.find("scene_hash");
  if (hash == j.end() || !hash->is_string() || hash->get<std::string>().size() != 16) {
    error = path + ": no scene_hash (written by an older haif?): run the scene again to replay it";
    return false;
  }
  log.sceneHash = hash->get<std::string>();
  const auto scene = j.find("scene");
  if (scene != j.end() && scene->is_string()) log.scene = scene->get<std::string>();
  const auto tol = j.find("residual_tolerance");
  if (tol == j.end() || !tol->is_number() || !(tol->get<double>() >= 0.0) || !(tol->get<double>() < 1e30)) {
    error = path + ": residual_tolerance: expected a number >= 0 (the run's early-stopping rule)";
    return false;
  }
  log.residualTolerance = tol->get<float>();
  const auto iMin = j.find("i_min");
  if (iMin != j.end()) {
    if (!iMin->is_number_integer() || iMin->get<int64_t>() < 1 || iMin->get<int64_t>() > 100000) {
      error = path + ": i_min: expected an integer in [1, 100000]";
      return false;
    }
    log.iMin = int(iMin->get<int64_t>());
  }
  const auto budget = j.find("budget_ms");
  if (budget != j.end() && budget->is_number()) log.hadBudget = budget->get<double>() > 0.0;
  out = std::move(log);
  return true;
}

}  // namespace haif
