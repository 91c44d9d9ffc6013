#include "scene/scene_loader.h"

#include "scene/body_parse.h"
#include "scene/generator_parse.h"
#include "scene/joint_parse.h"
#include "scene/json_document.h"
#include "scene/json_positions.h"
#include "scene/json_reader.h"
#include "scene/scene_validate.h"
#include "scene/stress_parse.h"
#include "scene/text_file.h"

namespace haif {

namespace {

std::string directoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return "";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string stemOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

// "FILE:LINE:COL" of a byte offset.
std::string formatLocation(const std::string& path, const std::string& text, size_t offset) {
  const TextLocation loc = locationOfOffset(text, offset);
  return oneLine(path) + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column);
}

std::string formatError(const std::string& path, const std::string& text, size_t offset, const std::string& place,
                        const std::string& message) {
  return formatLocation(path, text, offset) + ": " + oneLine(place) + ": " + oneLine(message);
}

void parseSettings(const JsonNode& node, SimSettings& settings) {
  WorldSettings& s = settings.world;
  checkKeys(node, {"dt", "gravity", "iterations", "omega", "beta", "slop", "skin", "sleeping", "accelerate", "momentum_layers",
                   "chain_solve", "exact_mass_ratio", "deep_layers_per_sweep", "moving_layers_per_sweep", "tolerance_thickness", "wide_solve", "reuse_manifolds", "rest_damping", "frames"});
  s.dt = optPositive(node, "dt", s.dt);
  if (s.dt > 1.0f) fail(node.member("dt"), "must be <= 1 s (got " + formatNumber(s.dt) + "; 60 Hz is 0.0166666667)");
  const JsonNode g = node.member("gravity");
  if (g.present()) s.gravity = g.json().is_number() ? Vec3(0.0f, readFloat(g), 0.0f) : readVec3(g);
  s.iterations = optInt(node, "iterations", s.iterations, 1, 100000);
  const JsonNode omega = node.member("omega");
  if (omega.present()) {
    s.contact.omega = readFloat(omega);
    if (!(s.contact.omega >= 1.0f && s.contact.omega < 2.0f)) fail(omega, "must be in [1, 2) (got " + formatNumber(s.contact.omega) + ")");
  }
  const JsonNode beta = node.member("beta");
  if (beta.present()) {
    s.contact.beta = readFloat(beta);
    if (!(s.contact.beta >= 0.0f && s.contact.beta <= 1.0f)) fail(beta, "must be in [0, 1] (got " + formatNumber(s.contact.beta) + ")");
  }
  s.contact.slop = optNonNegative(node, "slop", s.contact.slop);
  s.contact.skin = optNonNegative(node, "skin", s.contact.skin);
  if (node.member("sleeping").present()) s.sleeping = readBool(node.member("sleeping"));
  if (node.member("accelerate").present()) s.accelerate = readBool(node.member("accelerate"));
  s.momentumLayers = optNonNegative(node, "momentum_layers", s.momentumLayers);
  if (node.member("chain_solve").present()) s.chainSolve = readBool(node.member("chain_solve"));
  s.exactMassRatio = optNonNegative(node, "exact_mass_ratio", s.exactMassRatio);
  s.deepLayersPerSweep = optNonNegative(node, "deep_layers_per_sweep", s.deepLayersPerSweep);
  s.movingLayersPerSweep = optNonNegative(node, "moving_layers_per_sweep", s.movingLayersPerSweep);
  s.toleranceThickness = optNonNegative(node, "tolerance_thickness", s.toleranceThickness);
  if (node.member("wide_solve").present()) s.wideSolve = readBool(node.member("wide_solve"));
  if (node.member("reuse_manifolds").present()) s.reuseManifolds = readBool(node.member("reuse_manifolds"));
  const JsonNode rest = node.member("rest_damping");
  if (rest.present()) {
    s.restDamping = readFloat(rest);
    if (!(s.restDamping >= 0.0f && s.restDamping <= 1.0f))
      fail(rest, "must be in [0, 1] (got " + formatNumber(s.restDamping) + "; 0 turns it off)");
  }
  settings.frames = optInt(node, "frames", settings.frames, 1, 100000000);
}

// Materials: {"name": {friction, restitution, rolling_resistance, density}}; "default" may be redefined.
void parseMaterials(const JsonNode& node, std::vector<MaterialDesc>& materials) {
  requireObject(node);
  for (auto it = node.json().begin(); it != node.json().end(); ++it) {
    const JsonNode m = node.member(it.key());
    if (it.key().empty()) failAtKey(node, "", "a material needs a name");
    checkKeys(m, {"friction", "restitution", "rolling_resistance", "density"});
    MaterialDesc desc;
    desc.name = it.key();
    desc.friction = optNonNegative(m, "friction", desc.friction);
    const JsonNode r = m.member("restitution");
    if (r.present()) {
      desc.restitution = readFloat(r);
      if (!(desc.restitution >= 0.0f && desc.restitution <= 1.0f))
        fail(r, "must be in [0, 1] (got " + formatNumber(desc.restitution) + ")");
    }
    desc.rollingResistance = optNonNegative(m, "rolling_resistance", desc.rollingResistance);
    desc.density = optPositive(m, "density", desc.density);
    if (desc.name == "default") materials[0] = desc;
    else materials.push_back(desc);
  }
}

void parseCamera(const JsonNode& node, CameraDesc& c) {
  checkKeys(node, {"eye", "target", "up", "fov_deg"});
  c.given = true;
  c.eye = optVec3(node, "eye", c.eye);
  c.target = optVec3(node, "target", c.target);
  if ((c.eye - c.target).norm() < 1e-6f) fail(node.member("target").present() ? node.member("target") : node, "must differ from eye");
  const JsonNode up = node.member("up");
  if (up.present()) {
    c.up = readVec3(up);
    if (!(c.up.norm() > 1e-6f)) fail(up, "must not be the zero vector");
    if (c.up.normalized().cross((c.target - c.eye).normalized()).norm() < 1e-4f) fail(up, "must not be parallel to the view direction");
    c.up.normalize();
  }
  const JsonNode fov = node.member("fov_deg");
  if (fov.present()) {
    c.fovYDeg = readFloat(fov);
    if (!(c.fovYDeg > 0.0f && c.fovYDeg < 180.0f)) fail(fov, "must be in (0, 180) degrees (got " + formatNumber(c.fovYDeg) + ")");
  }
}

WaterDesc parseWater(const JsonNode& node) {
  checkKeys(node, {"min", "max", "density", "linear_drag", "angular_drag"});
  WaterDesc w;
  w.lo = readVec3(requireMember(node, "min", "lower corner [x, y, z]"));
  const JsonNode maxNode = requireMember(node, "max", "upper corner [x, y, z]; the surface is at max.y");
  w.hi = readVec3(maxNode);
  for (int a = 0; a < 3; ++a)
    if (!(w.hi[a] > w.lo[a])) fail(maxNode.element(static_cast<size_t>(a)), "must be greater than min (" + formatNumber(w.lo[a]) + ")");
  w.density = optPositive(node, "density", w.density);
  w.linearDrag = optNonNegative(node, "linear_drag", w.linearDrag);
  w.angularDrag = optNonNegative(node, "angular_drag", w.angularDrag);
  return w;
}

// Reads the whole document; throws SceneError at the first problem.
void parseDocument(const JsonNode& root, ParseContext& ctx, SceneDesc& scene) {
  if (!root.json().is_object()) fail(root, "a scene file must hold one JSON object {...} (got " + describeValue(root.json()) + ")");
  checkKeys(root, {"name", "description", "settings", "materials", "camera", "bodies", "water", "generators", "joints",
                  "stress"});
  if (root.member("name").present()) {
    scene.name = readString(root.member("name"));
    const std::string problem = sceneNameProblem(scene.name);
    if (!problem.empty()) fail(root.member("name"), problem);
  }
  if (root.member("description").present()) readString(root.member("description"));
  if (root.member("settings").present()) parseSettings(root.member("settings"), scene.settings);
  ctx.materials.assign(1, MaterialDesc{});
  if (root.member("materials").present()) parseMaterials(root.member("materials"), ctx.materials);
  if (root.member("camera").present()) parseCamera(root.member("camera"), scene.camera);

  const JsonNode bodies = root.member("bodies");
  if (bodies.present()) {
    requireArray(bodies);
    if (static_cast<int64_t>(bodies.size()) > kMaxSceneBodies) fail(bodies, "too many bodies (at most " + std::to_string(kMaxSceneBodies) + ")");
    for (size_t i = 0; i < bodies.size(); ++i) {
      const JsonNode b = bodies.element(i);
      scene.bodies.push_back(parseBody(b, ctx));
      ctx.bodyPointers.push_back(b.pointer);
    }
  }
  const JsonNode generators = root.member("generators");
  if (generators.present()) {
    requireArray(generators);
    for (size_t i = 0; i < generators.size(); ++i) expandGenerator(generators.element(i), ctx, scene.bodies);
  }
  const JsonNode water = root.member("water");
  if (water.present()) {
    requireArray(water);
    for (size_t i = 0; i < water.size(); ++i) scene.water.push_back(parseWater(water.element(i)));
  }
  const JsonNode joints = root.member("joints");  // after the bodies: joints name them
  if (joints.present()) {
    requireArray(joints);
    const BodyNames names(scene);
    for (size_t i = 0; i < joints.size(); ++i) scene.joints.push_back(parseJoint(joints.element(i), scene, names));
  }
  scene.materials = ctx.materials;
  // Checked here so a typo is caught by every command, used only by `haif stress`.
  if (root.member("stress").present()) scene.stress = parseStress(root.member("stress"), scene);
}

// JSON pointer of a validation issue, for its line:column.
std::string issuePointer(const SceneIssue& issue, const ParseContext& ctx) {
  std::string base;
  if (issue.body >= 0 && static_cast<size_t>(issue.body) < ctx.bodyPointers.size()) base = ctx.bodyPointers[static_cast<size_t>(issue.body)];
  else if (issue.water >= 0) base = "/water/" + std::to_string(issue.water);
  else if (issue.joint >= 0) base = "/joints/" + std::to_string(issue.joint);
  std::string field = issue.field;
  for (char& c : field)
    if (c == '.') c = '/';
  return field.empty() ? base : base + "/" + field;
}

}  // namespace

bool parseSceneText(const std::string& text, const std::string& pathForMessages, SceneDesc& out, std::string& error) {
  const size_t deep = findTooDeepNesting(text);
  if (deep != std::string::npos) {
    error = formatError(pathForMessages, text, deep, "syntax error",
                        "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels of [ and {");
    return false;
  }
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::parse_error& e) {
    const size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    error = formatError(pathForMessages, text, offset, "syntax error", jsonSyntaxMessage(e.what()));
    return false;
  } catch (const Json::exception& e) {  // number overflow (out_of_range.406) carries no position
    const size_t at = findOverflowingNumber(text);
    error = formatError(pathForMessages, text, at == std::string::npos ? 0 : at, "syntax error",
                        at == std::string::npos ? jsonSyntaxMessage(e.what())
                                                : "number out of range (too large for a 64-bit float)");
    return false;
  }

  JsonPositions positions;
  std::string duplicate;
  if (!positions.scan(text, duplicate)) {
    const size_t slash = duplicate.rfind('/');
    error = formatError(pathForMessages, text, positions.keyOffset(duplicate), "duplicate key",
                        "'" + duplicate.substr(slash + 1) + "' appears twice in the same object (at " + duplicate + ")");
    return false;
  }

  SceneDesc scene;
  scene.sourcePath = pathForMessages;
  scene.sourceHash = fnv1aHash(text);
  scene.name = stemOf(pathForMessages);
  ParseContext ctx;
  ctx.sceneDir = directoryOf(pathForMessages);
  JsonNode root;
  root.value = &doc;
  try {
    parseDocument(root, ctx, scene);
  } catch (const SceneError& e) {
    size_t offset = e.atKey ? positions.keyOffset(e.pointer) : std::string::npos;
    if (offset == std::string::npos) offset = positions.nearestValueOffset(e.pointer);
    error = formatError(pathForMessages, text, offset, e.place, e.message);
    return false;
  }

  SceneIssue issue;
  if (!validateScene(scene, issue)) {
    error = formatLocation(pathForMessages, text, positions.nearestValueOffset(issuePointer(issue, ctx))) + ": " +
            oneLine(issue.describe(scene));
    return false;
  }
  out = std::move(scene);
  return true;
}

bool loadSceneFile(const std::string& path, SceneDesc& out, std::string& error) {
  std::string text;
  if (!readTextFile(path, "scene file", text, error)) return false;
  return parseSceneText(text, path, out, error);
}

std::string sceneNameProblem(const std::string& name) {
  const std::string why = " (the name is the default output folder, output/<name>)";
  if (name.empty()) return "must not be empty" + why;
  if (name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos)
    return "must be a plain name, not a path (got '" + name + "')" + why;
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "must not hold control characters" + why;
  return "";
}

}  // namespace haif
