#include "scene/build_world.h"

#include "collision/convex_hull.h"
#include "collision/triangle_mesh.h"

#include <algorithm>

namespace haif {

WorldSettings worldSettingsFor(const SceneDesc& scene) {
  WorldSettings s;
  s.dt = scene.settings.dt;
  s.gravity = scene.settings.gravity;
  s.iterations = scene.settings.iterations;
  s.omega = scene.settings.omega;
  s.beta = scene.settings.beta;
  s.slop = scene.settings.slop;
  s.sleeping = scene.settings.sleeping;
  s.accelerate = scene.settings.accelerate;
  s.momentumLayers = scene.settings.momentumLayers;
  s.chainSolve = scene.settings.chainSolve;
  s.wideSolve = scene.settings.wideSolve;
  s.reuseManifolds = scene.settings.reuseManifolds;
  s.restDamping = scene.settings.restDamping;
  return s;
}

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
  def.linearDamping = b.linearDamping;
  def.angularDamping = b.angularDamping;
  const ShapeDesc& s = b.shape;
  std::string why;
  switch (s.type) {
    case ShapeType::Sphere: def.shape = Shape::sphere(s.radius); break;
    case ShapeType::Box: def.shape = Shape::box(s.halfExtents); break;
    case ShapeType::Capsule: def.shape = Shape::capsule(s.radius, s.halfHeight); break;
    case ShapeType::Plane: def.shape = Shape::plane(s.planeNormal, s.planeOffset); break;
    case ShapeType::ConvexHull: {
      auto hull = buildConvexHull(s.points, &why);
      if (!hull) {
        error = scene.sourcePath + ": " + b.where + ".shape: cannot build convex hull: " + why;
        return false;
      }
      // The hull was re-centred on its centre of mass: move the body there.
      def.xf.p += def.xf.q * hull->centroid;
      def.shape = Shape::convexHull(std::move(hull));
      break;
    }
    case ShapeType::TriangleMesh: {
      auto mesh = buildTriangleMesh(s.meshVertices, s.meshIndices, &why);
      if (!mesh) {
        error = scene.sourcePath + ": " + b.where + ".shape: cannot build triangle mesh: " + why;
        return false;
      }
      def.shape = Shape::triangleMesh(std::move(mesh));
      break;
    }
    default:
      error = scene.sourcePath + ": " + b.where + ".shape: unsupported shape type";
      return false;
  }
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
