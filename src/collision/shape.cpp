#include "collision/shape.h"

#include "collision/compound.h"

namespace haif {

const char* shapeTypeName(ShapeType t) {
  switch (t) {
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Box: return "box";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::ConvexHull: return "hull";
    case ShapeType::TriangleMesh: return "mesh";
    case ShapeType::Plane: return "plane";
    case ShapeType::Compound: return "compound";
    default: return "unknown";
  }
}

Shape Shape::sphere(float r) { Shape s; s.type = ShapeType::Sphere; s.radius = r; return s; }
Shape Shape::box(const Vec3& h) { Shape s; s.type = ShapeType::Box; s.halfExtents = h; return s; }
Shape Shape::capsule(float r, float hh) {
  Shape s; s.type = ShapeType::Capsule; s.radius = r; s.halfHeight = hh; return s;
}
Shape Shape::plane(const Vec3& n, float d) {
  Shape s; s.type = ShapeType::Plane; s.planeNormal = n.normalized(); s.planeOffset = d; return s;
}
Shape Shape::convexHull(std::shared_ptr<const ConvexHull> h) {
  Shape s; s.type = ShapeType::ConvexHull; s.hull = std::move(h); return s;
}
Shape Shape::triangleMesh(std::shared_ptr<const TriangleMesh> m) {
  Shape s; s.type = ShapeType::TriangleMesh; s.mesh = std::move(m); return s;
}
Shape Shape::compoundOf(std::shared_ptr<const CompoundShape> c) {
  Shape s; s.type = ShapeType::Compound; s.compound = std::move(c); return s;
}

MassProperties computeMassProperties(const Shape& s, float density) {
  MassProperties mp;
  switch (s.type) {
    case ShapeType::Sphere: {
      const float r = s.radius;
      mp.mass = density * (4.0f / 3.0f) * kPi * r * r * r;
      mp.inertia = Mat3::Identity() * (0.4f * mp.mass * r * r);
      break;
    }
    case ShapeType::Box: {
      const Vec3 e = 2.0f * s.halfExtents;
      mp.mass = density * e.x() * e.y() * e.z();
      const float k = mp.mass / 12.0f;
      mp.inertia = Vec3(k * (e.y() * e.y() + e.z() * e.z()), k * (e.x() * e.x() + e.z() * e.z()),
                        k * (e.x() * e.x() + e.y() * e.y())).asDiagonal();
      break;
    }
    case ShapeType::Capsule: {
      // Cylinder of height 2h plus two hemispheres whose centres of mass sit 3r/8 beyond the ends.
      const float r = s.radius, h = s.halfHeight;
      const float mc = density * kPi * r * r * 2.0f * h;
      const float ms = density * (4.0f / 3.0f) * kPi * r * r * r;
      mp.mass = mc + ms;
      const float iyy = mc * r * r * 0.5f + ms * 0.4f * r * r;
      const float ixx = mc * (r * r / 4.0f + h * h / 3.0f) +
                        ms * (0.4f * r * r + h * h + 0.75f * h * r);
      mp.inertia = Vec3(ixx, iyy, ixx).asDiagonal();
      break;
    }
    case ShapeType::ConvexHull:
      if (s.hull) {
        mp.mass = density * s.hull->volume;
        mp.inertia = density * s.hull->inertiaPerDensity;
      }
      break;
    case ShapeType::Compound:
      if (s.compound) {
        mp.mass = density * s.compound->volume;
        mp.inertia = density * s.compound->inertiaPerDensity;
      }
      break;
    default:
      break;  // planes and meshes are static: no mass
  }
  return mp;
}

MassProperties bodyMassProperties(const Shape& s, float density, float mass) {
  const MassProperties unit = computeMassProperties(s, 1.0f);
  MassProperties mp;
  mp.mass = mass > 0.0f ? mass : computeMassProperties(s, density).mass;
  // Inertia scales with mass for a given shape: take the unit-density tensor and rescale.
  mp.inertia = unit.mass > 0.0f ? Mat3(unit.inertia * (mp.mass / unit.mass)) : Mat3(Mat3::Identity() * mp.mass);
  return mp;
}

Aabb computeAabb(const Shape& s, const Transform& xf) {
  Aabb b;
  switch (s.type) {
    case ShapeType::Sphere:
      b.lo = xf.p - Vec3::Constant(s.radius);
      b.hi = xf.p + Vec3::Constant(s.radius);
      break;
    case ShapeType::Box: {
      const Vec3 e = xf.q.toRotationMatrix().cwiseAbs() * s.halfExtents;
      b.lo = xf.p - e;
      b.hi = xf.p + e;
      break;
    }
    case ShapeType::Capsule: {
      const Vec3 axis = xf.q * Vec3(0.0f, s.halfHeight, 0.0f);
      const Vec3 e = axis.cwiseAbs() + Vec3::Constant(s.radius);
      b.lo = xf.p - e;
      b.hi = xf.p + e;
      break;
    }
    case ShapeType::ConvexHull:
      for (const Vec3& v : s.hull->vertices) b.include(xf.apply(v));
      break;
    case ShapeType::TriangleMesh: {
      const Aabb& r = s.mesh->nodes.empty() ? Aabb{Vec3::Zero(), Vec3::Zero()} : s.mesh->nodes[0].box;
      const Mat3 R = xf.q.toRotationMatrix();
      const Vec3 c = xf.apply(r.center());
      const Vec3 e = R.cwiseAbs() * (0.5f * r.extent());
      b.lo = c - e;
      b.hi = c + e;
      break;
    }
    case ShapeType::Compound:
      for (const CompoundShape::Part& part : s.compound->parts) {
        const Transform at{xf.apply(part.local.p), xf.q * part.local.q};
        b = b.merged(computeAabb(part.shape, at));
      }
      break;
    case ShapeType::Plane:
    default:
      b.lo = Vec3::Constant(-1e18f);
      b.hi = Vec3::Constant(1e18f);
      break;
  }
  return b;
}

float smallestExtent(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere: return 2.0f * s.radius;
    case ShapeType::Box: return 2.0f * s.halfExtents.minCoeff();
    case ShapeType::Capsule: return 2.0f * s.radius;
    case ShapeType::ConvexHull: {
      float m = 1e30f;
      for (const auto& f : s.hull->faces) {
        float lo = 1e30f;
        for (const Vec3& v : s.hull->vertices) lo = std::min(lo, f.normal.dot(v));
        m = std::min(m, f.offset - lo);
      }
      return m;
    }
    case ShapeType::Compound: {
      float m = 1e30f;
      for (const CompoundShape::Part& part : s.compound->parts) m = std::min(m, smallestExtent(part.shape));
      return m;
    }
    default: return 1e30f;
  }
}

}  // namespace haif
