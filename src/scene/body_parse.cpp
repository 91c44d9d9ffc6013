#include "scene/body_parse.h"

#include "collision/compound.h"

#include "scene/asset_import.h"
#include "scene/scene_validate.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace haif {

MotionType parseMotionType(const JsonNode& node) {
  const std::string s = readString(node);
  if (s == "dynamic") return MotionType::Dynamic;
  if (s == "static") return MotionType::Static;
  if (s == "kinematic") return MotionType::Kinematic;
  fail(node, "unknown body type '" + s + "'" + didYouMean(s, {"static", "dynamic", "kinematic"}) +
                 "; use static, dynamic or kinematic");
}

uint32_t parseMaterialRef(const JsonNode& node, const ParseContext& ctx) {
  const std::string name = readString(node);
  std::vector<std::string> names;
  for (size_t i = 0; i < ctx.materials.size(); ++i) {
    if (ctx.materials[i].name == name) return static_cast<uint32_t>(i);
    names.push_back(ctx.materials[i].name);
  }
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  const std::string hint = didYouMean(name, names);
  fail(node, "unknown material '" + name + "'" + (hint.empty() ? " (defined: " + known + ")" : hint));
}

Quat parseOrientation(const JsonNode& node) {
  const Json& v = node.json();
  if (v.is_object()) {
    checkKeys(node, {"euler_deg"});
    const Vec3 e = readVec3(requireMember(node, "euler_deg", "or give a quaternion [x, y, z, w]"));
    const double k = 3.14159265358979323846 / 180.0;
    const Eigen::Quaterniond q = Eigen::AngleAxisd(e.z() * k, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(e.y() * k, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(e.x() * k, Eigen::Vector3d::UnitX());
    return q.normalized().cast<float>();
  }
  if (!v.is_array() || v.size() != 4)
    fail(node, "must be a quaternion [x, y, z, w] or {\"euler_deg\": [rx, ry, rz]} (got " + describeValue(v) + ")");
  const Eigen::Vector4d q(readFloat(node.element(0)), readFloat(node.element(1)), readFloat(node.element(2)),
                          readFloat(node.element(3)));
  const double n = q.norm();
  if (!(n > 1e-6)) fail(node, "must not be the zero quaternion (a rotation needs norm > 0)");
  const Eigen::Vector4d u = q / n;
  return Quat(static_cast<float>(u[3]), static_cast<float>(u[0]), static_cast<float>(u[1]), static_cast<float>(u[2]));
}

namespace {

const std::vector<std::string> kShapeTypes{"sphere", "box", "capsule", "hull", "mesh", "plane", "compound"};

ShapeType shapeTypeFromName(const JsonNode& node) {
  const std::string s = readString(node);
  if (s == "sphere") return ShapeType::Sphere;
  if (s == "box") return ShapeType::Box;
  if (s == "capsule") return ShapeType::Capsule;
  if (s == "hull") return ShapeType::ConvexHull;
  if (s == "mesh") return ShapeType::TriangleMesh;
  if (s == "plane") return ShapeType::Plane;
  if (s == "compound") return ShapeType::Compound;
  fail(node, "unknown shape type '" + s + "'" + didYouMean(s, kShapeTypes) +
                 "; use sphere, box, capsule, hull, mesh, plane or compound");
}

std::vector<Vec3> readPoints(const JsonNode& node) {
  requireArray(node);
  std::vector<Vec3> points;
  points.reserve(node.size());
  for (size_t i = 0; i < node.size(); ++i) points.push_back(readVec3(node.element(i)));
  return points;
}

std::string resolveAssetPath(const std::string& sceneDir, const std::string& asset) {
  if (asset.empty() || asset[0] == '/' || sceneDir.empty()) return asset;
  return sceneDir + "/" + asset;
}

// Reads the "asset" (and "scale") of `owner` into vertices/indices; errors name the field and the resolved file.
void readAsset(const JsonNode& owner, const ParseContext& ctx, std::string& asset, Vec3& scale,
               std::vector<Vec3>& vertices, std::vector<uint32_t>& indices) {
  const JsonNode assetNode =
      requireMember(owner, "asset", "a mesh file (OBJ, glTF/GLB, STL, PLY) relative to the scene file");
  asset = readString(assetNode);
  if (asset.empty()) fail(assetNode, "must name a mesh file");
  const JsonNode scaleNode = owner.member("scale");
  if (scaleNode.present()) scale = readPositiveVec3(scaleNode);
  const std::string path = resolveAssetPath(ctx.sceneDir, asset);
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail(assetNode, "cannot open asset file '" + path + "' (" + std::strerror(errno) + ")");
    if (std::filesystem::is_directory(path)) fail(assetNode, "asset '" + path + "' is a directory, not a mesh file");
  }
  std::string error;
  if (!importMeshAsset(path, scale, vertices, indices, error)) fail(assetNode, error);
}

void loadAsset(const JsonNode& shape, const ParseContext& ctx, ShapeDesc& s) {
  readAsset(shape, ctx, s.asset, s.assetScale, s.meshVertices, s.meshIndices);
}

}  // namespace

ShapeDesc parseShape(const JsonNode& node, MotionType motion, const ParseContext& ctx) {
  requireObject(node);
  const JsonNode typeNode = requireMember(node, "type", "one of sphere, box, capsule, hull, mesh, plane, compound");
  ShapeDesc s;
  s.type = shapeTypeFromName(typeNode);
  if (isStaticOnlyShape(s.type) && motion != MotionType::Static)
    fail(typeNode, std::string("shape '") + shapeTypeName(s.type) + "' is static-only; a " +
                       (motion == MotionType::Dynamic ? "dynamic" : "kinematic") +
                       " body needs sphere, box, capsule or hull");
  switch (s.type) {
    case ShapeType::Sphere:
      checkKeys(node, {"type", "radius"});
      s.radius = optPositive(node, "radius", 0.5f);
      break;
    case ShapeType::Box: {
      checkKeys(node, {"type", "half_extents", "size"});
      const JsonNode half = node.member("half_extents"), size = node.member("size");
      if (half.present() && size.present()) failAtKey(node, "size", "give either half_extents or size (full edge lengths), not both");
      if (half.present()) s.halfExtents = readPositiveVec3(half);
      if (size.present()) s.halfExtents = 0.5f * readPositiveVec3(size);
      break;
    }
    case ShapeType::Capsule:
      checkKeys(node, {"type", "radius", "half_height"});
      s.radius = optPositive(node, "radius", 0.5f);
      s.halfHeight = optNonNegative(node, "half_height", 0.5f);
      break;
    case ShapeType::ConvexHull: {
      checkKeys(node, {"type", "points", "asset", "scale"});
      const JsonNode points = node.member("points"), asset = node.member("asset");
      if (points.present() == asset.present())
        fail(node, points.present() ? "give either points or asset for a hull, not both"
                                    : "a hull needs 'points' ([[x, y, z], ...], at least 4) or an 'asset' file");
      if (points.present()) {
        if (node.member("scale").present()) failAtKey(node, "scale", "scale applies to assets only; write the points scaled");
        s.points = readPoints(points);
        const std::string problem = hullPointsProblem(s.points);
        if (!problem.empty()) fail(points, problem);
      } else {
        loadAsset(node, ctx, s);
        s.points = std::move(s.meshVertices);  // a hull only needs the point cloud
        s.meshVertices.clear();
        s.meshIndices.clear();
        const std::string problem = hullPointsProblem(s.points);
        if (!problem.empty()) fail(asset, problem);
      }
      break;
    }
    case ShapeType::TriangleMesh: {
      checkKeys(node, {"type", "vertices", "indices", "asset", "scale"});
      const JsonNode vertices = node.member("vertices"), asset = node.member("asset");
      if (vertices.present() == asset.present())
        fail(node, vertices.present() ? "give either vertices/indices or asset for a mesh, not both"
                                      : "a mesh needs 'vertices' and 'indices' or an 'asset' file");
      if (asset.present()) {
        loadAsset(node, ctx, s);
        break;
      }
      if (node.member("scale").present()) failAtKey(node, "scale", "scale applies to assets only; write the vertices scaled");
      s.meshVertices = readPoints(vertices);
      const JsonNode indices = requireMember(node, "indices", "3 vertex indices per triangle");
      requireArray(indices);
      if (indices.size() == 0 || indices.size() % 3 != 0)
        fail(indices, "must hold 3 vertex indices per triangle (got " + std::to_string(indices.size()) + " indices)");
      const int maxIndex = static_cast<int>(s.meshVertices.size()) - 1;
      if (maxIndex < 0) fail(vertices, "a mesh needs at least 3 vertices");
      for (size_t i = 0; i < indices.size(); ++i) s.meshIndices.push_back(static_cast<uint32_t>(readInt(indices.element(i), 0, maxIndex)));
      break;
    }
    case ShapeType::Plane: {
      checkKeys(node, {"type", "normal", "offset"});
      const JsonNode normal = node.member("normal");
      if (normal.present()) {
        s.planeNormal = readVec3(normal);
        if (!(s.planeNormal.norm() > 1e-6f)) fail(normal, "must not be the zero vector");
        s.planeNormal.normalize();
      }
      s.planeOffset = optFloat(node, "offset", 0.0f);
      break;
    }
    case ShapeType::Compound: {
      checkKeys(node, {"type", "parts"});
      const JsonNode parts = requireMember(node, "parts", "[{\"shape\": {...}, \"position\": [x, y, z]}, ...]");
      requireArray(parts);
      if (parts.size() == 0) fail(parts, "a compound needs at least one part");
      if (parts.size() > kMaxCompoundParts)
        fail(parts, "a compound has at most " + std::to_string(kMaxCompoundParts) + " parts (got " +
                        std::to_string(parts.size()) + ")");
      for (size_t i = 0; i < parts.size(); ++i) {
        const JsonNode part = parts.element(i);
        requireObject(part);
        checkKeys(part, {"shape", "position", "orientation", "draw"});
        const JsonNode shape = requireMember(part, "shape", "e.g. {\"type\": \"box\", \"size\": [1, 1, 1]}");
        CompoundPartDesc p;
        // Parsed as a static body's shape so a mesh or plane part reaches the message below.
        p.shape = parseShape(shape, MotionType::Static, ctx);
        if (!compoundPartType(p.shape.type))
          fail(shape.member("type"), notAPartMessage(p.shape.type));
        const JsonNode position = part.member("position"), orientation = part.member("orientation");
        if (position.present()) p.position = readVec3(position);
        if (orientation.present()) p.orientation = parseOrientation(orientation);
        const JsonNode draw = part.member("draw");
        if (draw.present()) p.draw = readBool(draw);
        s.parts.push_back(std::move(p));
      }
      break;
    }
    default: break;
  }
  return s;
}

void parseDamping(const JsonNode& node, BodyDesc& body) {
  if (node.json().is_number()) {
    body.linearDamping = body.angularDamping = readNonNegative(node);
    return;
  }
  if (!node.json().is_object()) fail(node, "must be a number or {\"linear\": l, \"angular\": a} (got " + describeValue(node.json()) + ")");
  checkKeys(node, {"linear", "angular"});
  body.linearDamping = optNonNegative(node, "linear", 0.0f);
  body.angularDamping = optNonNegative(node, "angular", 0.0f);
}

float parseMass(const JsonNode& node, MotionType motion) {
  if (motion != MotionType::Dynamic)
    fail(node, std::string("only dynamic bodies have a mass (this body is ") + (motion == MotionType::Static ? "static" : "kinematic") + ")");
  const float m = readFloat(node);
  if (!(m > 0.0f)) fail(node, "must be > 0 for a dynamic body (got " + formatNumber(m) + ")");
  return m;
}

BodyDesc parseBody(const JsonNode& node, const ParseContext& ctx) {
  checkKeys(node, {"name", "type", "shape", "position", "orientation", "velocity", "angular_velocity", "mass",
                   "material", "damping", "render_mesh"});
  BodyDesc b;
  b.where = node.place;
  if (node.member("name").present()) b.name = readString(node.member("name"));
  if (node.member("type").present()) b.motion = parseMotionType(node.member("type"));
  b.shape = parseShape(requireMember(node, "shape", "e.g. {\"type\": \"box\", \"half_extents\": [0.5, 0.5, 0.5]}"), b.motion, ctx);
  b.position = optVec3(node, "position", Vec3::Zero());
  if (node.member("orientation").present()) b.orientation = parseOrientation(node.member("orientation"));
  for (const char* key : {"velocity", "angular_velocity"}) {
    const JsonNode v = node.member(key);
    if (!v.present()) continue;
    const Vec3 value = readVec3(v);
    if (b.motion == MotionType::Static && !value.isZero())
      fail(v, "a static body cannot move (make it \"kinematic\" to give it a velocity)");
    (std::strcmp(key, "velocity") == 0 ? b.linearVelocity : b.angularVelocity) = value;
  }
  if (node.member("mass").present()) b.mass = parseMass(node.member("mass"), b.motion);
  if (node.member("material").present()) b.material = parseMaterialRef(node.member("material"), ctx);
  if (node.member("damping").present()) parseDamping(node.member("damping"), b);
  const JsonNode render = node.member("render_mesh");
  if (render.present()) {
    requireObject(render);
    checkKeys(render, {"asset", "scale"});
    RenderMeshDesc& r = b.renderMesh;
    readAsset(render, ctx, r.asset, r.scale, r.vertices, r.indices);
  }
  return b;
}

}  // namespace haif
