#include "scene/build_world.h"

#include "collision/compound.h"
#include "collision/convex_hull.h"
#include "collision/triangle_mesh.h"

#include <algorithm>

namespace haif {

namespace {

BodyKind kindOf(MotionType m) {
  switch (m) {
    case MotionType::Static: return BodyKind::Static;
    case MotionType::Kinematic: return BodyKind::Kinematic;
    default: return BodyKind::Dynamic;
  }
}

// The joint's world anchors and axis from the scene description, then its frames at the bodies' poses.
bool addSceneJoint(const SceneDesc& scene, const JointDesc& j, uint32_t firstBody, World& world, std::string& error) {
  auto id = [&](int32_t i) { return i < 0 ? kWorldBody : firstBody + uint32_t(i); };
  auto sceneXf = [&](int32_t i) {
    Transform t;
    if (i >= 0) {
      t.p = scene.bodies[size_t(i)].position;
      t.q = scene.bodies[size_t(i)].orientation.normalized();
    }
    return t;
  };
  const Vec3 anchorA = j.localAnchors ? sceneXf(j.bodyA).apply(j.anchorA) : j.anchorA;
  const Vec3 anchorB = j.localAnchors ? sceneXf(j.bodyB).apply(j.anchorB) : j.anchorB;
  const Vec3 axis = j.localAxis ? sceneXf(j.bodyA).rotate(j.axis) : j.axis;
  const uint32_t a = id(j.bodyA), b = id(j.bodyB);
  const Transform xa = a == kWorldBody ? Transform{} : world.bodies().xf[a];
  const Transform xb = b == kWorldBody ? Transform{} : world.bodies().xf[b];
  JointDef d = jointAtWorld(j.params.type, a, b, xa, xb, anchorA, axis, anchorB);
  if (j.localAnchors) d.localAnchorB = xb.applyInverse(anchorB);  // B's point as given, even if apart from A's
  const JointDef geometry = d;
  d = j.params;
  d.bodyA = a;
  d.bodyB = b;
  d.localAnchorA = geometry.localAnchorA;
  d.localAnchorB = geometry.localAnchorB;
  d.localFrameA = geometry.localFrameA;
  d.localFrameB = geometry.localFrameB;
  if (d.type == JointType::Distance) {
    // Unset bounds come from the initial distance, widened to include the other bound.
    const float len = (anchorB - anchorA).norm();
    if (d.minDistance < 0.0f) d.minDistance = d.maxDistance >= 0.0f ? std::min(len, d.maxDistance) : len;
    if (d.maxDistance < 0.0f) d.maxDistance = std::max(len, d.minDistance);
    if (!(d.maxDistance > 0.0f)) {
      error = scene.sourcePath + ": " + j.where + ": the anchors coincide; a distance joint needs a length > 0";
      return false;
    }
  }
  world.addJoint(d);
  return true;
}

// The engine shape for a scene shape; `centroid` is where its centre of mass sits in the scene's
// body frame (hulls and compounds are re-centred on it).
bool shapeFor(const ShapeDesc& s, Shape& out, Vec3& centroid, std::string& error) {
  centroid = Vec3::Zero();
  std::string why;
  switch (s.type) {
    case ShapeType::Sphere: out = Shape::sphere(s.radius); return true;
    case ShapeType::Box: out = Shape::box(s.halfExtents); return true;
    case ShapeType::Capsule: out = Shape::capsule(s.radius, s.halfHeight); return true;
    case ShapeType::Plane: out = Shape::plane(s.planeNormal, s.planeOffset); return true;
    case ShapeType::ConvexHull: {
      auto hull = buildConvexHull(s.points, &why);
      if (!hull) {
        error = "cannot build convex hull: " + why;
        return false;
      }
      centroid = hull->centroid;
      out = Shape::convexHull(std::move(hull));
      return true;
    }
    case ShapeType::TriangleMesh: {
      auto mesh = buildTriangleMesh(s.meshVertices, s.meshIndices, &why);
      if (!mesh) {
        error = "cannot build triangle mesh: " + why;
        return false;
      }
      out = Shape::triangleMesh(std::move(mesh));
      return true;
    }
    case ShapeType::Compound: {
      std::vector<Shape> parts(s.parts.size());
      std::vector<Transform> poses(s.parts.size());
      for (size_t i = 0; i < s.parts.size(); ++i) {
        Vec3 unused;  // buildCompound places a hull part by its own centroid
        if (!shapeFor(s.parts[i].shape, parts[i], unused, error)) {
          error = "parts[" + std::to_string(i) + "]: " + error;
          return false;
        }
        poses[i] = Transform{s.parts[i].position, s.parts[i].orientation};
      }
      auto compound = buildCompound(parts, poses, &why);
      if (!compound) {
        error = "cannot build compound: " + why;
        return false;
      }
      centroid = compound->centroid;
      out = Shape::compoundOf(std::move(compound));
      return true;
    }
    default:
      error = "unsupported shape type";
      return false;
  }
}

}  // namespace

bool bodyDefFor(const SceneDesc& scene, const BodyDesc& b, BodyDef& def, std::string& error) {
  def = BodyDef{};
  def.kind = kindOf(b.motion);
  def.xf.p = b.position;
  def.xf.q = b.orientation.normalized();
  def.linearVelocity = b.linearVelocity;
  def.angularVelocity = b.angularVelocity;
  def.mass = b.mass;
  const MaterialDesc& mat = scene.materials.at(b.material < scene.materials.size() ? b.material : 0);
  def.density = mat.density;
  def.friction = mat.friction;
  def.restitution = mat.restitution;
  def.rollingResistance = mat.rollingResistance;
  def.linearDamping = b.linearDamping;
  def.angularDamping = b.angularDamping;
  Vec3 centroid = Vec3::Zero();
  if (!shapeFor(b.shape, def.shape, centroid, error)) {
    error = scene.sourcePath + ": " + b.where + ".shape: " + error;
    return false;
  }
  // Hulls and compounds were re-centred on their centre of mass: move the body there.
  def.xf.p += def.xf.q * centroid;
  return true;
}

bool buildWorld(const SceneDesc& scene, World& world, std::string& error) {
  const uint32_t firstBody = world.bodyCount();
  for (const BodyDesc& b : scene.bodies) {
    BodyDef def;
    if (!bodyDefFor(scene, b, def, error)) return false;
    world.addBody(def);
  }
  for (const JointDesc& j : scene.joints)
    if (!addSceneJoint(scene, j, firstBody, world, error)) return false;
  for (const WaterDesc& w : scene.water) {
    WaterVolume v;
    v.box = {w.lo, w.hi};
    v.density = w.density;
    v.linearDrag = w.linearDrag;
    v.angularDrag = w.angularDrag;
    world.addWater(v);
  }
  return true;
}

}  // namespace haif
