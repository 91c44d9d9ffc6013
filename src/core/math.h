// Vector, rotation and transform types used across HAIF.
// The engine works in single precision: it halves memory traffic in the solver and is what
// real-time engines ship with; positions stay well inside float range for the scenes we run.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace haif {

using Vec2 = Eigen::Vector2f;
using Vec3 = Eigen::Vector3f;
using Quat = Eigen::Quaternionf;
using Mat3 = Eigen::Matrix3f;

inline constexpr float kPi = 3.14159265358979323846f;

/// Rigid transform: world = q * local + p.
struct Transform {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();

  Vec3 apply(const Vec3& local) const { return q * local + p; }
  Vec3 applyInverse(const Vec3& world) const { return q.conjugate() * (world - p); }
  Vec3 rotate(const Vec3& v) const { return q * v; }
  Vec3 rotateInverse(const Vec3& v) const { return q.conjugate() * v; }
  /// this^-1 * other: `other` expressed in this transform's frame.
  Transform inverseTimes(const Transform& other) const {
    Transform t;
    t.q = q.conjugate() * other.q;
    t.p = q.conjugate() * (other.p - p);
    return t;
  }
};

/// Build an orthonormal basis (t1, t2) perpendicular to unit vector n (branch-free variant
/// of the Frisvad construction; stable for every direction).
inline void orthonormalBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float b = n.x() * n.y() * a;
  t1 = Vec3(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

inline bool isFinite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace haif
