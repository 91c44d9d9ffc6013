#include "scene/build_world.h"

#include "collision/convex_hull.h"
#include "collision/triangle_mesh.h"

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
  for (const BodyDesc& b : scene.bodies) {
    BodyDef def;
    if (!bodyDefFor(scene, b, def, error)) return false;
    world.addBody(def);
  }
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
