#include "bullet/bullet_shapes.h"

#include "collision/compound.h"

#include <btBulletCollisionCommon.h>
#include <LinearMath/btGeometryUtil.h>

#include <algorithm>

namespace haif {

namespace {

btVector3 toBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }

// A convex hull the size of HAIF's: Bullet puts its margin outside a hull's points, so the hull's
// face planes move inwards by the margin and the hull is rebuilt from them.
std::unique_ptr<btCollisionShape> hullShape(const ConvexHull& hull, const Quat& frame, std::string& error) {
  const Quat toShape = frame.conjugate();
  float extent = 1e30f;
  for (const auto& f : hull.faces) {
    float lo = 1e30f;
    for (const Vec3& v : hull.vertices) lo = std::min(lo, f.normal.dot(v));
    extent = std::min(extent, f.offset - lo);
  }
  const float margin = std::min(0.04f, 0.1f * extent);
  btAlignedObjectArray<btVector3> planes, points;
  for (const auto& f : hull.faces) {
    btVector3 n = toBt(toShape * f.normal);
    n[3] = -(f.offset - margin);  // Bullet's plane: n·x + w = 0
    planes.push_back(n);
  }
  btGeometryUtil::getVerticesFromPlaneEquations(planes, points);
  if (points.size() < 4) {
    error = "convex hull too thin for Bullet's collision margin";
    return nullptr;
  }
  auto shape = std::make_unique<btConvexHullShape>(&points[0].x(), points.size(), int(sizeof(btVector3)));
  shape->setMargin(margin);
  return shape;
}

}  // namespace

BulletShapeStore::BulletShapeStore() = default;
BulletShapeStore::~BulletShapeStore() = default;

btCollisionShape* BulletShapeStore::add(const Shape& s, const Quat& frame, std::string& error) {
  std::unique_ptr<btCollisionShape> shape;
  switch (s.type) {
    case ShapeType::Sphere:
      shape = std::make_unique<btSphereShape>(s.radius);  // the margin is the radius: no growth
      break;
    case ShapeType::Box:
      // btBoxShape keeps its margin inside the half extents it is given (a box stays its size).
      // Boxes have diagonal inertia, so `frame` is the identity here.
      shape = std::make_unique<btBoxShape>(toBt(s.halfExtents));
      break;
    case ShapeType::Capsule:
      shape = std::make_unique<btCapsuleShape>(s.radius, 2.0f * s.halfHeight);  // along y, as HAIF's
      break;
    case ShapeType::ConvexHull:
      if (!s.hull) break;
      shape = hullShape(*s.hull, frame, error);
      if (!shape) return nullptr;
      break;
    case ShapeType::TriangleMesh: {
      if (!s.mesh) break;
      auto mesh = std::make_unique<btTriangleMesh>();
      const auto& v = s.mesh->vertices;
      const auto& ix = s.mesh->indices;
      for (size_t t = 0; t + 2 < ix.size(); t += 3)
        mesh->addTriangle(toBt(v[ix[t]]), toBt(v[ix[t + 1]]), toBt(v[ix[t + 2]]));
      shape = std::make_unique<btBvhTriangleMeshShape>(mesh.get(), true);
      meshes_.push_back(std::move(mesh));
      break;
    }
    case ShapeType::Plane:
      shape = std::make_unique<btStaticPlaneShape>(toBt(s.planeNormal), s.planeOffset);
      break;
    case ShapeType::Compound: {
      if (!s.compound) break;
      // Bullet's body frame is the principal frame `frame` of the HAIF body frame: each part's pose is
      // turned into it; the parts themselves are expressed in their own frames.
      auto compound = std::make_unique<btCompoundShape>(true, int(s.compound->parts.size()));
      const Quat toShape = frame.conjugate();
      for (const CompoundShape::Part& part : s.compound->parts) {
        btCollisionShape* child = add(part.shape, Quat::Identity(), error);
        if (!child) return nullptr;
        const Quat q = toShape * part.local.q;
        compound->addChildShape(btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), toBt(toShape * part.local.p)), child);
      }
      shape = std::move(compound);
      break;
    }
    default:
      break;
  }
  if (!shape) {
    error = std::string("shape '") + shapeTypeName(s.type) + "' cannot be expressed in Bullet";
    return nullptr;
  }
  shapes_.push_back(std::move(shape));
  return shapes_.back().get();
}

}  // namespace haif
