#include "scene/scene_validate.h"

#include "collision/compound.h"

#include "collision/shape.h"
#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>

namespace haif {

std::string SceneIssue::describe(const SceneDesc& scene) const {
  std::string place;
  if (body >= 0 && body < static_cast<int>(scene.bodies.size())) {
    const std::string& w = scene.bodies[static_cast<size_t>(body)].where;
    place = w.empty() ? "bodies[" + std::to_string(body) + "]" : w;
  } else if (water >= 0) {
    place = "water[" + std::to_string(water) + "]";
  } else if (joint >= 0) {
    place = joint < static_cast<int>(scene.joints.size()) && !scene.joints[size_t(joint)].where.empty()
                ? scene.joints[size_t(joint)].where
                : "joints[" + std::to_string(joint) + "]";
  }
  if (!field.empty()) place += (place.empty() ? "" : ".") + field;
  return (place.empty() ? "scene" : place) + ": " + message;
}

bool isStaticOnlyShape(ShapeType t) { return t == ShapeType::Plane || t == ShapeType::TriangleMesh; }

std::string hullPointsProblem(const std::vector<Vec3>& points) {
  if (points.size() < 4) return "a hull needs at least 4 points (got " + std::to_string(points.size()) + ")";
  // Extreme points: p0, farthest from p0, farthest from that line, farthest from that plane.
  const Vec3 p0 = points[0];
  Vec3 p1 = p0;
  for (const Vec3& p : points)
    if ((p - p0).squaredNorm() > (p1 - p0).squaredNorm()) p1 = p;
  const float size = (p1 - p0).norm();
  if (!(size > 0.0f)) return "all hull points are the same point";
  const Vec3 axis = (p1 - p0) / size;
  Vec3 p2 = p0;
  float best = 0.0f;
  for (const Vec3& p : points) {
    const float d = ((p - p0) - axis * axis.dot(p - p0)).norm();
    if (d > best) best = d, p2 = p;
  }
  if (best <= 1e-5f * size) return "all hull points lie on one line";
  const Vec3 normal = (p1 - p0).cross(p2 - p0).normalized();
  float depth = 0.0f;
  for (const Vec3& p : points) depth = std::max(depth, std::fabs(normal.dot(p - p0)));
  if (depth <= 1e-5f * size) return "all hull points lie in one plane (a hull needs volume)";
  return "";
}

bool hasTriangleWithArea(const std::vector<Vec3>& vertices, const std::vector<uint32_t>& indices) {
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= vertices.size() || indices[t + 1] >= vertices.size() || indices[t + 2] >= vertices.size())
      continue;
    const Vec3 a = vertices[indices[t]], e1 = vertices[indices[t + 1]] - a, e2 = vertices[indices[t + 2]] - a;
    // Relative to the edges: collinear points give a cross product of rounding size only.
    const float area2 = e1.cross(e2).norm();
    if (area2 > 0.0f && area2 > 1e-6f * e1.norm() * e2.norm()) return true;
  }
  return false;
}

Vec3 shapeHalfBox(const ShapeDesc& s) {
  Vec3 half = Vec3::Zero();
  switch (s.type) {
    case ShapeType::Sphere: half = Vec3::Constant(s.radius); break;
    case ShapeType::Box: half = s.halfExtents; break;
    case ShapeType::Capsule: half = Vec3(s.radius, s.radius + s.halfHeight, s.radius); break;
    case ShapeType::ConvexHull:
      for (const Vec3& p : s.points) half = half.cwiseMax(p.cwiseAbs());
      break;
    case ShapeType::Compound:
      for (const CompoundPartDesc& p : s.parts)
        half = half.cwiseMax(p.position.cwiseAbs() + p.orientation.toRotationMatrix().cwiseAbs() * shapeHalfBox(p.shape));
      break;
    default: break;
  }
  return half;
}

float shapeExtent(const ShapeDesc& s) {
  switch (s.type) {
    case ShapeType::Sphere: return 2.0f * s.radius;
    case ShapeType::Box: return 2.0f * s.halfExtents.maxCoeff();
    case ShapeType::Capsule: return 2.0f * (s.radius + s.halfHeight);
    case ShapeType::ConvexHull: {
      if (s.points.empty()) return 0.0f;
      Vec3 lo = s.points[0], hi = s.points[0];
      for (const Vec3& p : s.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      return (hi - lo).maxCoeff();
    }
    case ShapeType::Compound: {
      // Over the parts' boxes (each about its own place), not the symmetric half box: a part set off
      // to one side does not make the body twice as long.
      Vec3 lo = Vec3::Constant(1e30f), hi = Vec3::Constant(-1e30f);
      for (const CompoundPartDesc& p : s.parts) {
        const Vec3 half = p.orientation.toRotationMatrix().cwiseAbs() * shapeHalfBox(p.shape);
        lo = lo.cwiseMin(p.position - half);
        hi = hi.cwiseMax(p.position + half);
      }
      return s.parts.empty() ? 0.0f : (hi - lo).maxCoeff();
    }
    default: return 0.0f;
  }
}

namespace {

float shapeMass(const ShapeDesc& s, float density) {
  // The engine's own mass properties (collision/shape.h), so the check sees the mass it will use.
  switch (s.type) {
    case ShapeType::Sphere: return computeMassProperties(Shape::sphere(s.radius), density).mass;
    case ShapeType::Box: return computeMassProperties(Shape::box(s.halfExtents), density).mass;
    case ShapeType::Capsule: return computeMassProperties(Shape::capsule(s.radius, s.halfHeight), density).mass;
    case ShapeType::Compound: {
      float sum = 0.0f;
      for (const CompoundPartDesc& p : s.parts) {
        const float m = shapeMass(p.shape, density);
        if (m == 0.0f) return 0.0f;  // a hull part: not known yet
        sum += m;
      }
      return sum;
    }
    default: return 0.0f;
  }
}

}  // namespace

float bodyMass(const SceneDesc& scene, const BodyDesc& b) {
  if (b.mass > 0.0f) return b.mass;
  return shapeMass(b.shape, scene.materials[b.material].density);
}

namespace {

bool finite(float f) { return std::isfinite(f); }

// Helpers return false after filling the issue, so checks read as `if (!positive(...)) return false;`.
struct Checker {
  SceneIssue& issue;
  int body = -1;
  int water = -1;
  int joint = -1;

  bool bad(const std::string& field, const std::string& message) {
    issue.body = body;
    issue.water = water;
    issue.joint = joint;
    issue.field = field;
    issue.message = message;
    return false;
  }
  bool isFiniteNum(const std::string& field, float v) { return finite(v) || bad(field, "must be a finite number (got " + formatNumber(v) + ")"); }
  bool positive(const std::string& field, float v) {
    if (!isFiniteNum(field, v)) return false;
    return v > 0.0f || bad(field, "must be > 0 (got " + formatNumber(v) + ")");
  }
  bool nonNegative(const std::string& field, float v) {
    if (!isFiniteNum(field, v)) return false;
    return v >= 0.0f || bad(field, "must be >= 0 (got " + formatNumber(v) + ")");
  }
  bool finiteVec(const std::string& field, const Vec3& v) {
    return isFinite(v) || bad(field, "must be finite (got [" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + "])");
  }
  bool unitQuat(const std::string& field, const Quat& q) {
    const float n = q.norm();
    return (std::isfinite(n) && std::fabs(n - 1.0f) <= 1e-3f) ||
           bad(field, "must be a unit quaternion (norm " + formatNumber(n) + ")");
  }
  bool positiveVec(const std::string& field, const Vec3& v) {
    if (!finiteVec(field, v)) return false;
    return (v.array() > 0.0f).all() ||
           bad(field, "every component must be > 0 (got [" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + "])");
  }
};

bool checkShape(Checker& c, const ShapeDesc& s, MotionType motion) {
  if (isStaticOnlyShape(s.type) && motion != MotionType::Static)
    return c.bad("shape.type", std::string("shape '") + shapeTypeName(s.type) + "' is static-only; a " +
                                   (motion == MotionType::Dynamic ? "dynamic" : "kinematic") +
                                   " body needs sphere, box, capsule or hull");
  switch (s.type) {
    case ShapeType::Sphere: return c.positive("shape.radius", s.radius);
    case ShapeType::Box: return c.positiveVec("shape.half_extents", s.halfExtents);
    case ShapeType::Capsule: return c.positive("shape.radius", s.radius) && c.nonNegative("shape.half_height", s.halfHeight);
    case ShapeType::ConvexHull: {
      for (const Vec3& p : s.points)
        if (!c.finiteVec("shape.points", p)) return false;
      const std::string problem = hullPointsProblem(s.points);
      return problem.empty() || c.bad(s.asset.empty() ? "shape.points" : "shape.asset", problem);
    }
    case ShapeType::TriangleMesh: {
      if (s.meshIndices.empty() || s.meshIndices.size() % 3 != 0)
        return c.bad("shape.indices", "a mesh needs a positive multiple of 3 indices (got " + std::to_string(s.meshIndices.size()) + ")");
      for (const Vec3& v : s.meshVertices)
        if (!c.finiteVec("shape.vertices", v)) return false;
      for (uint32_t i : s.meshIndices)
        if (i >= s.meshVertices.size())
          return c.bad("shape.indices", "index " + std::to_string(i) + " is out of range (" + std::to_string(s.meshVertices.size()) + " vertices)");
      // Inline or from an asset, a mesh of only zero-area triangles has no surface to collide with.
      return hasTriangleWithArea(s.meshVertices, s.meshIndices) ||
             c.bad(s.asset.empty() ? "shape.indices" : "shape.asset",
                   "all " + std::to_string(s.meshIndices.size() / 3) +
                       " triangles are degenerate (zero area): a mesh needs at least one with area");
    }
    case ShapeType::Plane:
      if (!c.finiteVec("shape.normal", s.planeNormal) || !c.isFiniteNum("shape.offset", s.planeOffset)) return false;
      return s.planeNormal.norm() > 1e-6f || c.bad("shape.normal", "must not be the zero vector");
    case ShapeType::Compound: {
      if (s.parts.empty()) return c.bad("shape.parts", "a compound needs at least one part");
      for (size_t i = 0; i < s.parts.size(); ++i) {
        const CompoundPartDesc& p = s.parts[i];
        const std::string at = "shape.parts[" + std::to_string(i) + "]";
        if (!compoundPartType(p.shape.type))
          return c.bad(at + ".shape.type", notAPartMessage(p.shape.type));
        if (!c.finiteVec(at + ".position", p.position)) return false;
        if (!c.unitQuat(at + ".orientation", p.orientation)) return false;
        if (!checkShape(c, p.shape, MotionType::Static)) {
          c.issue.field = at + "." + c.issue.field;  // the part's own check names "shape.radius" etc.
          return false;
        }
      }
      return true;
    }
    default: return c.bad("shape.type", "unknown shape type");
  }
}

bool checkBody(Checker& c, const SceneDesc& scene, const BodyDesc& b) {
  if (!c.finiteVec("position", b.position) || !c.finiteVec("velocity", b.linearVelocity) ||
      !c.finiteVec("angular_velocity", b.angularVelocity))
    return false;
  // In double: the float square of 1e20 overflows, and the message would say "inf".
  const double speed = b.linearVelocity.cast<double>().norm(), spin = b.angularVelocity.cast<double>().norm();
  if (!(speed <= kMaxBodySpeed))
    return c.bad("velocity", "a speed of " + formatNumber(speed) +
                                 " m/s is outside the speeds the engine supports (up to " + formatNumber(kMaxBodySpeed) +
                                 " m/s)");
  if (!(spin <= kMaxBodySpin))
    return c.bad("angular_velocity", "a spin of " + formatNumber(spin) +
                                         " rad/s is outside the spins the engine supports (up to " +
                                         formatNumber(kMaxBodySpin) + " rad/s)");
  if (!c.unitQuat("orientation", b.orientation)) return false;
  if (b.material >= scene.materials.size())
    return c.bad("material", "material index " + std::to_string(b.material) + " is out of range");
  if (!c.nonNegative("damping.linear", b.linearDamping) || !c.nonNegative("damping.angular", b.angularDamping)) return false;
  if (!checkShape(c, b.shape, b.motion)) return false;
  if (!b.renderMesh.asset.empty()) {
    if (b.renderMesh.indices.empty() || b.renderMesh.indices.size() % 3 != 0)
      return c.bad("render_mesh.asset", "a render mesh needs triangles");
    for (const Vec3& v : b.renderMesh.vertices)
      if (!c.finiteVec("render_mesh.asset", v)) return false;
    for (uint32_t i : b.renderMesh.indices)
      if (i >= b.renderMesh.vertices.size()) return c.bad("render_mesh.asset", "index out of range");
  }
  if (!c.isFiniteNum("mass", b.mass)) return false;
  if (b.motion != MotionType::Static && !isStaticOnlyShape(b.shape.type)) {
    const float size = shapeExtent(b.shape);
    if (!(size >= kMinBodySize && size <= kMaxBodySize))
      return c.bad("shape", "a moving body of " + formatNumber(size) + " m is outside the sizes the engine supports (" +
                                formatNumber(kMinBodySize) + " to " + formatNumber(kMaxBodySize) + " m)");
  }
  if (b.motion == MotionType::Dynamic) {
    if (b.mass < 0.0f) return c.bad("mass", "must be > 0 for a dynamic body (got " + formatNumber(b.mass) + ")");
    if (b.mass == 0.0f && !(scene.materials[b.material].density > 0.0f))
      return c.bad("mass", "a dynamic body needs a mass or a material with density > 0");
    const float m = bodyMass(scene, b);
    if (m != 0.0f && !(m >= kMinBodyMass && m <= kMaxBodyMass))
      return c.bad("mass", "a mass of " + formatNumber(m) + " kg" + (b.mass > 0.0f ? "" : " (density x volume)") +
                               " is outside the masses the engine supports (" + formatNumber(kMinBodyMass) + " to " +
                               formatNumber(kMaxBodyMass) + " kg)");
  } else if (b.motion == MotionType::Static) {
    if (!b.linearVelocity.isZero() || !b.angularVelocity.isZero())
      return c.bad(b.linearVelocity.isZero() ? "angular_velocity" : "velocity",
                   "a static body cannot move (make it \"kinematic\" to give it a velocity)");
  }
  return true;
}

bool checkJoint(Checker& c, const SceneDesc& scene, const JointDesc& j) {
  const int32_t n = static_cast<int32_t>(scene.bodies.size());
  auto inRange = [&](int32_t b) { return b >= -1 && b < n; };
  if (!inRange(j.bodyA)) return c.bad("body_a", "body index " + std::to_string(j.bodyA) + " is out of range");
  if (!inRange(j.bodyB)) return c.bad("body_b", "body index " + std::to_string(j.bodyB) + " is out of range");
  if (j.bodyA == j.bodyB) return c.bad("body_b", "a joint needs two different bodies");
  auto dynamic = [&](int32_t i) { return i >= 0 && scene.bodies[size_t(i)].motion == MotionType::Dynamic; };
  if (!dynamic(j.bodyA) && !dynamic(j.bodyB)) return c.bad("body_b", "a joint needs a dynamic body");
  if (dynamic(j.bodyA) && dynamic(j.bodyB)) {
    const float ma = bodyMass(scene, scene.bodies[size_t(j.bodyA)]), mb = bodyMass(scene, scene.bodies[size_t(j.bodyB)]);
    if (ma > 0.0f && mb > 0.0f && std::max(ma, mb) > kMaxJointMassRatio * std::min(ma, mb))
      return c.bad("body_b", "joins bodies of " + formatNumber(ma) + " and " + formatNumber(mb) + " kg: a mass ratio of 1:" +
                                 formatNumber(std::max(ma, mb) / std::min(ma, mb)) + ", above the 1:" +
                                 formatNumber(kMaxJointMassRatio) + " the joint solver holds");
  }
  if (!c.finiteVec("anchor", j.anchorA) || !c.finiteVec("anchor", j.anchorB) || !c.finiteVec("axis", j.axis))
    return false;
  if (!(j.axis.norm() > 1e-6f)) return c.bad("axis", "must not be the zero vector");
  const JointDef& p = j.params;
  for (float v :
       {p.lower, p.upper, p.minDistance, p.maxDistance, p.swingLimit, p.twistLower, p.twistUpper, p.motorSpeed})
    if (!c.isFiniteNum("limits", v)) return false;
  if (p.limitEnabled && p.lower > p.upper) return c.bad("limits", "upper must be >= lower");
  if (p.twistLower > p.twistUpper) return c.bad("twist", "upper must be >= lower");
  if (p.motorEnabled && !(p.maxMotorForce > 0.0f)) return c.bad("motor.max_force", "must be > 0");
  for (size_t i = 1; i < p.servo.size(); ++i)
    if (!(p.servo[i].time > p.servo[i - 1].time)) return c.bad("servo.keys", "times must increase");
  if (!(p.breakForce > 0.0f) || !(p.breakTorque > 0.0f)) return c.bad("break_force", "must be > 0");
  return true;
}

}  // namespace

bool validateScene(const SceneDesc& scene, SceneIssue& issue) {
  issue = SceneIssue{};
  Checker c{issue};
  const WorldSettings& s = scene.settings.world;
  if (!c.positive("settings.dt", s.dt)) return false;
  if (!c.finiteVec("settings.gravity", s.gravity)) return false;
  if (s.iterations < 1) return c.bad("settings.iterations", "must be >= 1 (got " + std::to_string(s.iterations) + ")");
  if (!c.isFiniteNum("settings.omega", s.contact.omega)) return false;
  if (!(s.contact.omega >= 1.0f && s.contact.omega < 2.0f)) return c.bad("settings.omega", "must be in [1, 2) (got " + formatNumber(s.contact.omega) + ")");
  if (!c.nonNegative("settings.beta", s.contact.beta) || !c.nonNegative("settings.slop", s.contact.slop) ||
      !c.nonNegative("settings.skin", s.contact.skin) ||
      !c.nonNegative("settings.exact_mass_ratio", s.exactMassRatio) ||
      !c.nonNegative("settings.deep_layers_per_sweep", s.deepLayersPerSweep) ||
      !c.nonNegative("settings.moving_layers_per_sweep", s.movingLayersPerSweep) ||
      !c.nonNegative("settings.tolerance_thickness", s.toleranceThickness) ||
      !c.nonNegative("settings.momentum_layers", s.momentumLayers))
    return false;
  if (s.contact.beta > 1.0f) return c.bad("settings.beta", "must be in [0, 1] (got " + formatNumber(s.contact.beta) + ")");
  if (!c.nonNegative("settings.rest_damping", s.restDamping)) return false;
  if (s.restDamping > 1.0f)
    return c.bad("settings.rest_damping", "must be in [0, 1] (got " + formatNumber(s.restDamping) + "; 0 turns it off)");
  if (scene.settings.frames < 1)
    return c.bad("settings.frames", "must be >= 1 (got " + std::to_string(scene.settings.frames) + ")");

  if (scene.materials.empty()) return c.bad("materials", "materials[0] (\"default\") must exist");
  for (const MaterialDesc& m : scene.materials) {
    const std::string f = "materials." + m.name + ".";
    if (!c.nonNegative(f + "friction", m.friction) || !c.nonNegative(f + "restitution", m.restitution) ||
        !c.nonNegative(f + "rolling_resistance", m.rollingResistance) || !c.positive(f + "density", m.density))
      return false;
    if (m.restitution > 1.0f) return c.bad(f + "restitution", "must be in [0, 1] (got " + formatNumber(m.restitution) + ")");
  }
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    c.body = static_cast<int>(i);
    if (!checkBody(c, scene, scene.bodies[i])) return false;
  }
  c.body = -1;
  for (size_t i = 0; i < scene.water.size(); ++i) {
    c.water = static_cast<int>(i);
    const WaterDesc& w = scene.water[i];
    if (!c.finiteVec("min", w.lo) || !c.finiteVec("max", w.hi)) return false;
    if (!(w.lo.array() < w.hi.array()).all()) return c.bad("max", "must be greater than min in every component");
    if (!c.positive("density", w.density) || !c.nonNegative("linear_drag", w.linearDrag) ||
        !c.nonNegative("angular_drag", w.angularDrag))
      return false;
  }
  c.water = -1;
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    c.joint = static_cast<int>(i);
    if (!checkJoint(c, scene, scene.joints[i])) return false;
  }
  return true;
}

}  // namespace haif
