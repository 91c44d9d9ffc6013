#include "haif/speed_bound.h"

#include <algorithm>
#include <cmath>

namespace haif {

void SpeedBound::addBody(const Shape& shape) {
  const Aabb box = computeAabb(shape, Transform());
  // The farthest corner from the centre of mass (a hull's or compound's box is not centred on it).
  const Vec3 far = box.lo.cwiseAbs().cwiseMax(box.hi.cwiseAbs());
  // Planes and meshes are static: their reach never enters a speed.
  reach_.push_back(shape.type == ShapeType::Plane || shape.type == ShapeType::TriangleMesh ? 0.0f : far.norm());
}

void SpeedBound::update(const BodyStore& bodies, const Vec3& gravity, float dt, float waterLift, float floor) {
  const uint32_t n = static_cast<uint32_t>(bodies.size());
  const float g = gravity.norm();
  const Vec3 up = g > 0.0f ? Vec3(-gravity / g) : Vec3::UnitY();
  for (uint32_t i = seen_; i < n; ++i) {
    if (bodies.kind[i] != BodyKind::Dynamic) continue;
    fastestStart_ = std::max(fastestStart_, bodies.v[i].norm() + bodies.w[i].norm() * reach_[i]);
    const float h = up.dot(bodies.xf[i].p);
    highestStart_ = std::max(highestStart_, h + reach_[i]);
    lowest_ = std::min(lowest_, h - reach_[i]);
  }
  seen_ = n;
  float kinematic = 0.0f, pushed = 0.0f;
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies.kind[i] == BodyKind::Kinematic) {
      kinematic = std::max(kinematic, bodies.v[i].norm() + bodies.w[i].norm() * reach_[i]);
    } else if (bodies.kind[i] == BodyKind::Dynamic) {
      const float f = bodies.force[i].squaredNorm(), t = bodies.torque[i].squaredNorm();
      if (f > 0.0f || t > 0.0f) {
        // |Δv| + |Δω| r of this step's user force and torque, bounded by the body's inverse inertia.
        const float invI = bodies.invInertiaLocal[i].norm();
        pushed = std::max(pushed, dt * (bodies.invMass[i] * std::sqrt(f) + invI * std::sqrt(t) * reach_[i]));
      }
    }
  }
  forceAllowance_ += pushed;
  up_ = up;
  floor_ = std::isfinite(floor) ? floor : -1e30f;
  const float lowest = std::isfinite(floor) ? std::max(lowest_, floor) : lowest_;
  const float fall = std::max(0.0f, highestStart_ - lowest);
  const float freeFall = std::sqrt(2.0f * g * (1.0f + waterLift) * fall);
  base_ = fastestStart_ + freeFall + 2.0f * kinematic + forceAllowance_;
  setLimit();
}

void SpeedBound::setMotorSurface(float speed) {
  motorSurface_ = speed;
  setLimit();
}

void SpeedBound::setLimit() {
  limit_ = settings.factor > 0.0f ? settings.factor * (base_ + 2.0f * motorSurface_) + settings.floor : 1e30f;
}

uint32_t SpeedBound::apply(BodyStore& bodies, uint32_t begin, uint32_t end) const {
  if (settings.factor <= 0.0f) return 0;
  uint32_t slowed = 0;
  for (uint32_t i = begin; i < end; ++i) {
    if (!bodies.isAwakeDynamic(i) || up_.dot(bodies.xf[i].p) + reach_[i] < floor_) continue;
    const float speed = bodies.v[i].norm() + bodies.w[i].norm() * reach_[i];
    if (speed <= limit_) continue;  // false for NaN too
    if (std::isfinite(speed)) {
      const float s = limit_ / speed;
      bodies.v[i] *= s;
      bodies.w[i] *= s;
    } else {
      bodies.v[i].setZero();
      bodies.w[i].setZero();
    }
    ++slowed;
  }
  return slowed;
}

void SpeedBound::noteLowest(const BodyStore& bodies, const Vec3& up) {
  const uint32_t n = static_cast<uint32_t>(bodies.size());
  for (uint32_t i = 0; i < n; ++i)
    if (bodies.isAwakeDynamic(i)) lowest_ = std::min(lowest_, up.dot(bodies.xf[i].p) - reach_[i]);
}

}  // namespace haif
