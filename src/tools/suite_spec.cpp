#include "tools/suite_spec.h"

#include "scene/json_document.h"
#include "scene/json_positions.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"
#include "scene/stress_parse.h"
#include "scene/text_file.h"
#include "tools/frame_diff.h"
#include "tools/run_report.h"

#include <algorithm>
#include <filesystem>
#include <map>

namespace haif {

namespace fs = std::filesystem;

namespace {

// The set-up keys a job of each kind takes; "defaults" may give any of them, and a job takes from
// it only the keys its kind takes.
const std::vector<std::string> kSimulateKeys = {"frames", "mode", "iterations", "budget_ms", "error_every",
                                                "threads"};
const std::vector<std::string> kRenderKeys = {"width", "height", "frame_every"};
const std::vector<std::string> kStressKeys = {"quick", "threads"};

std::vector<std::string> keysOf(SuiteJobKind kind) {
  std::vector<std::string> keys;
  if (kind == SuiteJobKind::Stress) return kStressKeys;
  keys = kSimulateKeys;
  if (kind == SuiteJobKind::Render) keys.insert(keys.end(), kRenderKeys.begin(), kRenderKeys.end());
  return keys;
}

std::vector<std::string> defaultsKeys() {
  std::vector<std::string> keys = kSimulateKeys;
  keys.insert(keys.end(), kRenderKeys.begin(), kRenderKeys.end());
  keys.push_back("quick");
  return keys;
}

// A job's own member `key`, else the suite's default for it.
JsonNode setting(const JsonNode& job, const JsonNode& defaults, const std::string& key) {
  const JsonNode own = job.member(key);
  return own.present() ? own : defaults.member(key);
}

// A job name is also a folder name under the report's jobs/ and a JUnit test name.
bool plainName(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.size() > 100) return false;
  return name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") ==
         std::string::npos;
}

std::string stemOf(const std::string& path) { return fs::path(path).stem().string(); }

std::string resolve(const std::string& baseDir, const std::string& given) {
  const fs::path p(given);
  return p.is_absolute() || baseDir.empty() ? p.string() : (fs::path(baseDir) / p).string();
}

// Reads the suite; the scenes it names are loaded once each.
class SuiteReader {
 public:
  SuiteReader(const std::string& baseDir, const SuiteLoadOptions& options) : baseDir_(baseDir), options_(options) {}

  void read(const JsonNode& root, SuiteSpec& spec) {
    requireObject(root);
    checkKeys(root, {"name", "defaults", "jobs"});
    if (root.member("name").present()) spec.name = readString(root.member("name"));
    const JsonNode defaults = root.member("defaults");
    if (defaults.present()) {
      requireObject(defaults);
      checkKeys(defaults, defaultsKeys());
    }
    const JsonNode jobs = requireMember(root, "jobs", "an array of {\"kind\": run|render|stress, \"scene\": FILE, ...}");
    requireArray(jobs);
    if (jobs.size() == 0) fail(jobs, "is empty: a suite needs at least one job");
    std::map<std::string, std::string> names;  // name -> place of the job that has it
    for (size_t i = 0; i < jobs.size(); ++i) {
      SuiteJob job;
      job.index = i;
      readJob(jobs.element(i), defaults, job);
      const auto [it, fresh] = names.emplace(job.name, job.where);
      if (!fresh) {
        const JsonNode node = jobs.element(i).member("name");
        fail(node.present() ? node : jobs.element(i),
             "two jobs are named '" + job.name + "' (" + it->second + " and " + job.where +
                 "): give each job its own \"name\" (it names the job's folder and its JUnit test)");
      }
      spec.jobs.push_back(std::move(job));
    }
  }

 private:
  void readJob(const JsonNode& node, const JsonNode& defaults, SuiteJob& job) {
    requireObject(node);
    job.where = node.place;
    const JsonNode kindNode = requireMember(node, "kind", "run, render or stress");
    const std::string kind = readString(kindNode);
    if (kind == "run") job.kind = SuiteJobKind::Run;
    else if (kind == "render") job.kind = SuiteJobKind::Render;
    else if (kind == "stress") job.kind = SuiteJobKind::Stress;
    else fail(kindNode, "unknown job kind '" + kind + "' (expected run, render or stress)" +
                            didYouMean(kind, {"run", "render", "stress"}));
    std::vector<std::string> keys = {"name", "kind", "scene"};
    const std::vector<std::string> setup = keysOf(job.kind);
    keys.insert(keys.end(), setup.begin(), setup.end());
    if (job.kind != SuiteJobKind::Stress) keys.push_back("checks");
    if (job.kind == SuiteJobKind::Render) keys.insert(keys.end(), {"reference", "diff"});
    checkKeys(node, keys);

    const JsonNode sceneNode = requireMember(node, "scene", "a scene file, relative to the suite file");
    job.sceneGiven = readString(sceneNode);
    job.scenePath = resolve(baseDir_, job.sceneGiven);
    const JsonNode nameNode = node.member("name");
    job.name = nameNode.present() ? readString(nameNode) : stemOf(job.sceneGiven);
    if (!plainName(job.name))
      fail(nameNode.present() ? nameNode : node,
           "job name '" + job.name + "' must be 1 to 100 letters, digits, '.', '_' or '-'" +
               (nameNode.present() ? "" : " (it defaults to the scene file's stem: give \"name\")"));

    // Settings from the job or the suite's defaults. A default that is wrong for this job says so.
    try {
      readSetup(node, defaults, job);
    } catch (SceneError& e) {
      if (e.place.rfind("defaults.", 0) == 0) e.message += " (the default for " + job.where + ")";
      throw;
    }
    const SceneDesc& scene = loadScene(sceneNode, job.scenePath);
    if (job.kind == SuiteJobKind::Stress) {
      if (!scene.stress.given)
        fail(sceneNode, job.scenePath + " has no \"stress\" block: a stress job runs a stress scene (docs/stress.md)");
      return;
    }
    const JsonNode checks = node.member("checks");
    if (checks.present()) {
      requireArray(checks);
      for (size_t k = 0; k < checks.size(); ++k) job.checks.push_back(readCheck(checks.element(k), scene, job));
    }
    if (job.kind == SuiteJobKind::Render) readRender(node, job);
  }

  void readSetup(const JsonNode& node, const JsonNode& defaults, SuiteJob& job) {
    auto get = [&](const std::string& key) { return setting(node, defaults, key); };
    if (get("threads").present()) job.threads = readInt(get("threads"), 1, 1024);
    if (job.kind == SuiteJobKind::Stress) {
      if (get("quick").present()) job.quick = readBool(get("quick"));
      return;
    }
    if (get("frames").present()) job.frames = readInt(get("frames"), 1, 10000000);
    if (get("error_every").present()) job.errorEvery = readInt(get("error_every"), 0, 1000000);
    if (get("iterations").present()) job.iterations = readInt(get("iterations"), 1, 100000);
    const JsonNode budget = get("budget_ms");
    if (budget.present()) {
      job.budgetMs = readNumber(budget);
      if (!(job.budgetMs > 0.0 && job.budgetMs <= 1e6))
        fail(budget, "must be > 0 and <= 1e6 ms (got " + formatNumber(job.budgetMs) + ")");
    }
    const JsonNode mode = get("mode");
    if (mode.present()) {
      job.mode = readString(mode);
      if (job.mode != "fixed" && job.mode != "adaptive" && job.mode != "model")
        fail(mode, "expected fixed, adaptive or model (got '" + job.mode + "')");
      // A render job is compared with stored frames: its pictures must not depend on the machine.
      if (job.kind == SuiteJobKind::Render && job.mode == "adaptive")
        fail(mode, "a render job needs a reproducible mode, fixed or model: adaptive runs follow the wall clock "
                   "and change from run to run");
    }
    if (job.kind != SuiteJobKind::Render) return;
    if (get("width").present()) job.width = readInt(get("width"), 16, 8192);
    if (get("height").present()) job.height = readInt(get("height"), 16, 8192);
    if (get("frame_every").present()) job.frameEvery = readInt(get("frame_every"), 1, 100000);
  }

  SuiteCheck readCheck(const JsonNode& node, const SceneDesc& scene, const SuiteJob& job) {
    requireObject(node);
    SuiteCheck c;
    c.where = node.place;
    const JsonNode nameNode = requireMember(node, "check", "a stress check or a summary.json number, e.g. max_drop_m");
    const std::string name = readString(nameNode);
    const std::vector<std::string>& stressNames = stressCheckNames();
    if (std::find(stressNames.begin(), stressNames.end(), name) != stressNames.end()) {
      c.stress = true;
      c.stressCheck = parseStressCheck(node, scene);
      return c;
    }
    const std::vector<std::string>& keys = summaryNumberKeys();
    if (std::find(keys.begin(), keys.end(), name) == keys.end()) {
      std::vector<std::string> all = stressNames;
      all.insert(all.end(), keys.begin(), keys.end());
      const std::string hint = didYouMean(name, all);
      fail(nameNode, "unknown check '" + name + "'" +
                         (hint.empty() ? " (a stress check of docs/stress.md or a number of summary.json, "
                                         "docs/metrics.md)"
                                       : hint));
    }
    if ((name == "solve_error_mean" || name == "solve_error_samples") && job.errorEvery == 0)
      fail(nameNode, name + " needs the solve error measured: give the job \"error_every\" (e.g. 10)");
    checkKeys(node, {"check", "min", "max"});
    c.key = name;
    c.hasMin = node.member("min").present();
    c.hasMax = node.member("max").present();
    if (c.hasMin) c.min = readNumber(node.member("min"));
    if (c.hasMax) c.max = readNumber(node.member("max"));
    if (!c.hasMin && !c.hasMax) fail(node, "a summary.json check needs \"min\", \"max\" or both");
    if (c.hasMin && c.hasMax && c.min > c.max)
      fail(node.member("min"), "is above max (" + formatNumber(c.min) + " > " + formatNumber(c.max) + ")");
    return c;
  }

  void readRender(const JsonNode& node, SuiteJob& job) {
    const JsonNode ref = requireMember(node, "reference", "a folder of reference PNG frames, relative to the suite file");
    job.referenceGiven = readString(ref);
    job.referencePath = resolve(baseDir_, job.referenceGiven);
    // One folder per job: two jobs diffing against one folder would overwrite each other's frames.
    const auto [other, fresh] = references_.emplace(fs::path(job.referencePath).lexically_normal().string(), job.where);
    if (!fresh) fail(ref, "is also the reference of " + other->second + ": give each render job its own folder");
    std::error_code ec;
    if (!options_.referencesMayBeMissing) {
      FrameFolder folder;
      std::string why;
      if (!openFrameFolder(job.referencePath, "reference", folder, why))
        fail(ref, why + " (haif suite SUITE --update-references renders it)");
    } else if (fs::exists(job.referencePath, ec) && !fs::is_directory(job.referencePath, ec)) {
      fail(ref, "'" + job.referencePath + "' is not a folder");
    }
    const JsonNode diff = node.member("diff");
    if (!diff.present()) return;
    requireObject(diff);
    checkKeys(diff, {"threshold", "max_diff_ratio", "min_ssim", "antialiasing", "masks"});
    auto inRange = [&](const std::string& key, double lo, double hi, double& out) {
      const JsonNode v = diff.member(key);
      if (!v.present()) return;
      out = readNumber(v);
      if (out < lo || out > hi)
        fail(v, "must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "] (got " + formatNumber(out) + ")");
    };
    inRange("threshold", 0.0, 1.0, job.diff.threshold);
    inRange("max_diff_ratio", 0.0, 1.0, job.diff.maxDiffRatio);
    inRange("min_ssim", -1.0, 1.0, job.diff.minSsim);
    if (diff.member("antialiasing").present()) job.diff.antialiasing = readBool(diff.member("antialiasing"));
    const JsonNode masks = diff.member("masks");
    if (!masks.present()) return;
    requireArray(masks);
    for (size_t i = 0; i < masks.size(); ++i) {
      const JsonNode m = masks.element(i);
      if (!m.json().is_array() || m.size() != 4) fail(m, "must be a pixel rectangle [x0, y0, x1, y1]");
      SuiteDiffSpec::Rect r;
      r.x0 = readInt(m.element(0), 0, 8192);
      r.y0 = readInt(m.element(1), 0, 8192);
      r.x1 = readInt(m.element(2), 0, 8192);
      r.y1 = readInt(m.element(3), 0, 8192);
      if (r.x1 <= r.x0 || r.y1 <= r.y0) fail(m, "is empty: need x0 < x1 and y0 < y1");
      job.diff.masks.push_back(r);
    }
  }

  const SceneDesc& loadScene(const JsonNode& node, const std::string& path) {
    const auto it = scenes_.find(path);
    if (it != scenes_.end()) return it->second;
    SceneDesc scene;
    std::string why;
    if (!loadSceneFile(path, scene, why)) fail(node, why);
    return scenes_.emplace(path, std::move(scene)).first->second;
  }

  std::string baseDir_;
  SuiteLoadOptions options_;
  std::map<std::string, SceneDesc> scenes_;
  std::map<std::string, std::string> references_;  // reference folder -> the job that has it
};

}  // namespace

const char* suiteJobKindName(SuiteJobKind kind) {
  switch (kind) {
    case SuiteJobKind::Run: return "run";
    case SuiteJobKind::Render: return "render";
    case SuiteJobKind::Stress: return "stress";
  }
  return "?";
}

bool loadSuiteFile(const std::string& path, const SuiteLoadOptions& options, SuiteSpec& out, std::string& error) {
  std::string text;
  if (!readTextFile(path, "suite file", text, error)) return false;
  return parseSuiteText(text, path, options, out, error);
}

bool parseSuiteText(const std::string& text, const std::string& path, const SuiteLoadOptions& options, SuiteSpec& out,
                    std::string& error) {
  auto at = [&](size_t offset) {
    const TextLocation loc = locationOfOffset(text, offset);
    return path + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) + ": ";
  };
  Json doc;
  JsonPositions positions;
  if (!parseJsonDocument(text, path, doc, positions, error)) return false;
  SuiteSpec spec;
  spec.path = path;
  spec.name = stemOf(path);
  spec.hash = hashText(fnv1aHash(text));  // as scene files are hashed
  JsonNode root;
  root.value = &doc;
  try {
    SuiteReader(fs::path(path).parent_path().string(), options).read(root, spec);
  } catch (const SceneError& e) {
    size_t offset = e.atKey ? positions.keyOffset(e.pointer) : std::string::npos;
    if (offset == std::string::npos) offset = positions.nearestValueOffset(e.pointer);
    error = at(offset) + (e.place == "scene" ? "suite" : e.place) + ": " + e.message;
    return false;
  }
  out = std::move(spec);
  return true;
}

}  // namespace haif
