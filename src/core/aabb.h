// Axis-aligned bounding box.
#pragma once

#include "core/math.h"

namespace haif {

struct Aabb {
  Vec3 lo = Vec3::Constant(1e30f);
  Vec3 hi = Vec3::Constant(-1e30f);

  bool overlaps(const Aabb& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y() &&
           lo.z() <= o.hi.z() && o.lo.z() <= hi.z();
  }
  bool contains(const Aabb& o) const {
    return lo.x() <= o.lo.x() && lo.y() <= o.lo.y() && lo.z() <= o.lo.z() && o.hi.x() <= hi.x() &&
           o.hi.y() <= hi.y() && o.hi.z() <= hi.z();
  }
  Aabb merged(const Aabb& o) const { return {lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)}; }
  Aabb expanded(float m) const { return {lo - Vec3::Constant(m), hi + Vec3::Constant(m)}; }
  /// What the box covers moving by d: itself merged with itself moved.
  Aabb swept(const Vec3& d) const { return merged({lo + d, hi + d}); }
  void include(const Vec3& p) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  Vec3 center() const { return 0.5f * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
  /// Half the surface area: the cost measure of the AABB tree.
  float perimeter() const {
    const Vec3 d = hi - lo;
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
};

}  // namespace haif
