#include "collision/compound.h"

namespace haif {

bool compoundPartType(ShapeType t) {
  return t == ShapeType::Sphere || t == ShapeType::Box || t == ShapeType::Capsule || t == ShapeType::ConvexHull;
}

std::string notAPartMessage(ShapeType t) {
  return std::string("a compound's part cannot be a ") + shapeTypeName(t) + "; use sphere, box, capsule or hull";
}

std::shared_ptr<CompoundShape> buildCompound(const std::vector<Shape>& shapes, const std::vector<Transform>& poses,
                                             std::string* error) {
  auto refuse = [&](const std::string& why) {
    if (error) *error = why;
    return std::shared_ptr<CompoundShape>();
  };
  if (shapes.empty()) return refuse("a compound needs at least one part");
  if (shapes.size() != poses.size()) return refuse("every part needs a pose");
  if (shapes.size() > kMaxCompoundParts)
    return refuse("a compound has at most " + std::to_string(kMaxCompoundParts) + " parts (got " +
                  std::to_string(shapes.size()) + ")");
  auto c = std::make_shared<CompoundShape>();
  c->parts.reserve(shapes.size());
  // Sums in double: the parallel-axis terms of parts far from the centre cancel against each other.
  double volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < shapes.size(); ++i) {
    const Shape& s = shapes[i];
    if (!compoundPartType(s.type))
      return refuse("parts[" + std::to_string(i) + "]: a " + shapeTypeName(s.type) +
                    " cannot be a part (use sphere, box, capsule or hull)");
    if (s.type == ShapeType::ConvexHull && !s.hull) return refuse("parts[" + std::to_string(i) + "]: hull without points");
    Transform local = poses[i];
    if (!isFinite(local.p) || !std::isfinite(local.q.norm()) || !(local.q.norm() > 1e-6f))
      return refuse("parts[" + std::to_string(i) + "]: the pose must be finite with a non-zero rotation");
    local.q.normalize();
    if (s.type == ShapeType::ConvexHull) local.p += local.q * s.hull->centroid;
    const float v = computeMassProperties(s, 1.0f).mass;
    volume += v;
    moment += double(v) * local.p.cast<double>();
    c->parts.push_back(CompoundShape::Part{s, local, Aabb{}});
    c->roundParts |= s.type == ShapeType::Sphere || s.type == ShapeType::Capsule;
  }
  if (!(volume > 0.0)) return refuse("the parts have no volume");
  const Eigen::Vector3d centre = moment / volume;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (CompoundShape::Part& p : c->parts) {
    const MassProperties mp = computeMassProperties(p.shape, 1.0f);
    const Eigen::Matrix3d R = p.local.q.toRotationMatrix().cast<double>();
    const Eigen::Vector3d d = p.local.p.cast<double>() - centre;
    // The part's own tensor turned into the body frame, plus its mass at its offset (parallel axes).
    inertia += R * mp.inertia.cast<double>() * R.transpose() +
               double(mp.mass) * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    p.local.p = d.cast<float>();
    p.box = computeAabb(p.shape, p.local);
  }
  c->centroid = centre.cast<float>();
  c->volume = float(volume);
  c->inertiaPerDensity = inertia.cast<float>();
  return c;
}

}  // namespace haif
