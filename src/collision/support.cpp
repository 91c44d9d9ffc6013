#include "collision/support.h"

#include "collision/compound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace haif {

float supportAlong(const Shape& s, const Transform& xf, const Vec3& d) {
  switch (s.type) {
    case ShapeType::Sphere: return d.dot(xf.p) + s.radius * d.norm();
    case ShapeType::Box: {
      const Vec3 local = xf.rotateInverse(d);
      return d.dot(xf.p) + local.cwiseAbs().dot(s.halfExtents);
    }
    case ShapeType::Capsule: {
      const Vec3 axis = xf.rotate(Vec3(0.0f, s.halfHeight, 0.0f));
      return d.dot(xf.p) + std::fabs(d.dot(axis)) + s.radius * d.norm();
    }
    case ShapeType::ConvexHull: {
      const Vec3 local = xf.rotateInverse(d);
      float most = -std::numeric_limits<float>::infinity();
      for (const Vec3& v : s.hull->vertices) most = std::max(most, local.dot(v));
      return d.dot(xf.p) + most;
    }
    case ShapeType::Compound: {
      float most = -std::numeric_limits<float>::infinity();
      for (const CompoundShape::Part& part : s.compound->parts) {
        const Transform at{xf.apply(part.local.p), xf.q * part.local.q};
        most = std::max(most, supportAlong(part.shape, at, d));
      }
      return most;
    }
    case ShapeType::TriangleMesh:
    case ShapeType::Plane:
    default: return std::numeric_limits<float>::infinity();
  }
}

}  // namespace haif
