#include "scene/stress_parse.h"

#include <algorithm>

namespace haif {

namespace {

struct CheckInfo {
  const char* name;
  StressCheckKind kind;
  const char* limitKey;  ///< "max", "min" or "min_flips"
  bool needsBody;        ///< must name one body
  bool allowsBody;       ///< may name one body
};

const CheckInfo kChecks[] = {
    {"max_drop_m", StressCheckKind::MaxDrop, "max", false, true},
    {"min_drop_m", StressCheckKind::MinDrop, "min", true, true},
    {"max_penetration_m", StressCheckKind::MaxPenetration, "max", false, false},
    {"final_penetration_m", StressCheckKind::FinalPenetration, "max", false, false},
    {"peak_speed", StressCheckKind::PeakSpeed, "max", false, true},
    {"energy_gain_ratio", StressCheckKind::EnergyGainRatio, "max", false, false},
    {"angular_momentum_drift", StressCheckKind::AngularMomentumDrift, "max", false, false},
    {"intermediate_axis_flip", StressCheckKind::IntermediateAxisFlip, "min_flips", true, true},
    {"no_tunnel", StressCheckKind::NoTunnel, "", true, true},
    {"max_joint_error_m", StressCheckKind::MaxJointError, "max", false, false},
    {"speed_limited", StressCheckKind::SpeedLimited, "max", false, false},
};

// A dynamic body named by its "name" or its index (generated bodies have no names).
int32_t parseStressBody(const JsonNode& node, const SceneDesc& scene) {
  const Json& v = node.json();
  int32_t index = -1;
  if (v.is_number_integer() || v.is_number_unsigned()) {
    if (scene.bodies.empty()) fail(node, "the scene has no bodies");
    index = readInt(node, 0, static_cast<int>(scene.bodies.size()) - 1);
  } else if (v.is_string()) {
    const std::string name = v.get<std::string>();
    std::vector<std::string> known;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].name.empty()) continue;
      if (scene.bodies[i].name == name) {
        if (index >= 0) fail(node, "body name '" + name + "' is ambiguous: " + scene.bodies[size_t(index)].where +
                                       " and " + scene.bodies[i].where + " both have it");
        index = static_cast<int32_t>(i);
      }
      known.push_back(scene.bodies[i].name);
    }
    if (index < 0) fail(node, "no body is named '" + name + "'" + didYouMean(name, known));
  } else {
    fail(node, "must be a body name or a body index (got " + describeValue(v) + ")");
  }
  if (scene.bodies[size_t(index)].motion != MotionType::Dynamic)
    fail(node, "must be a dynamic body (" + scene.bodies[size_t(index)].where + " is not)");
  return index;
}

double readLimit(const JsonNode& node) {
  const double x = readNumber(node);
  if (!(x >= 0.0)) fail(node, "must be >= 0 (got " + formatNumber(x) + ")");
  return x;
}

}  // namespace

StressCheck parseStressCheck(const JsonNode& node, const SceneDesc& scene) {
  requireObject(node);
  const JsonNode nameNode = requireMember(node, "check", "the check's name, e.g. max_drop_m");
  const std::string name = readString(nameNode);
  const std::vector<std::string>& names = stressCheckNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    const std::string hint = didYouMean(name, names);
    fail(nameNode, "unknown check '" + name + "'" + (hint.empty() ? " (known checks: " + list + ")" : hint));
  }
  const CheckInfo& info = kChecks[it - names.begin()];
  std::vector<std::string> keys{"check"};
  if (info.limitKey[0]) keys.push_back(info.limitKey);
  if (info.allowsBody) keys.push_back("body");
  if (info.kind == StressCheckKind::IntermediateAxisFlip) keys.push_back("axis");
  if (info.kind == StressCheckKind::NoTunnel) keys.insert(keys.end(), {"normal", "offset"});
  checkKeys(node, keys);

  StressCheck c;
  c.kind = info.kind;
  c.name = name;
  c.where = node.place;
  if (info.kind == StressCheckKind::IntermediateAxisFlip) {
    const JsonNode flips = node.member("min_flips");
    c.limit = flips.present() ? readInt(flips, 1, 1000000) : 1;
  } else if (info.limitKey[0]) {
    c.limit = readLimit(requireMember(node, info.limitKey, std::string("the limit the metric is held to")));
  }
  const JsonNode body = node.member("body");
  if (info.needsBody && !body.present()) requireMember(node, "body", "a body name or index");
  if (body.present()) c.body = parseStressBody(body, scene);
  if (info.kind == StressCheckKind::IntermediateAxisFlip || info.kind == StressCheckKind::NoTunnel) {
    const char* key = info.kind == StressCheckKind::NoTunnel ? "normal" : "axis";
    const JsonNode axis = requireMember(node, key, "[x, y, z]");
    c.axis = readVec3(axis);
    if (!(c.axis.norm() > 1e-6f)) fail(axis, "must not be the zero vector");
    c.axis.normalize();
    c.offset = optFloat(node, "offset", 0.0f);
  }
  return c;
}

const std::vector<std::string>& stressCheckNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const CheckInfo& c : kChecks) n.push_back(c.name);
    return n;
  }();
  return names;
}

StressDesc parseStress(const JsonNode& node, const SceneDesc& scene) {
  checkKeys(node, {"steps", "quick_steps", "quick", "quick_note", "checks"});
  StressDesc s;
  s.given = true;
  s.steps = readInt(requireMember(node, "steps", "how many steps the full run takes"), 1, 10000000);
  s.quickSteps = optInt(node, "quick_steps", s.steps, 1, 10000000);
  if (node.member("quick").present()) s.inQuick = readBool(node.member("quick"));
  if (node.member("quick_note").present()) s.quickNote = readString(node.member("quick_note"));
  const JsonNode checks = requireMember(node, "checks", "a list of {\"check\": NAME, ...}");
  requireArray(checks);
  if (checks.size() == 0) fail(checks, "must list at least one check");
  for (size_t i = 0; i < checks.size(); ++i) s.checks.push_back(parseStressCheck(checks.element(i), scene));
  return s;
}

}  // namespace haif
