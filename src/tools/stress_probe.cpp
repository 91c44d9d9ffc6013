#include "tools/stress_probe.h"

#include <algorithm>
#include <cmath>

namespace haif {

Eigen::Vector3d totalAngularMomentum(const World& world) {
  const BodyStore& b = world.bodies();
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < b.size(); ++i) {
    if (b.kind[i] != BodyKind::Dynamic) continue;
    const Mat3 R = b.xf[i].q.toRotationMatrix();
    const Vec3 spin = R * (b.inertiaLocal[i] * (R.transpose() * b.w[i]));
    const Vec3 orbit = b.mass[i] * b.xf[i].p.cross(b.v[i]);
    L += (spin + orbit).cast<double>();
  }
  return L;
}

double currentMaxPenetration(const World& world) {
  double m = 0.0;
  for (const Contact& c : world.contacts()) {
    if (!c.touching()) continue;
    m = std::max(m, double(c.manifold.deepest()));
  }
  return m;
}

void StressProbe::begin(const World& world, const std::vector<StressCheck>& checks) {
  *this = StressProbe{};
  e0_ = world.kineticEnergy() + world.potentialEnergy();
  l0_ = totalAngularMomentum(world).norm();
  const BodyStore& b = world.bodies();
  for (const StressCheck& c : checks) {
    Follow f;
    f.kind = c.kind;
    f.body = c.body;
    f.axis = c.axis;
    f.offset = c.offset;
    if (f.body >= 0) f.startY = b.xf[size_t(f.body)].p.y();
    if (f.kind == StressCheckKind::NoTunnel && f.body >= 0) {
      const float d = f.axis.dot(b.xf[size_t(f.body)].p) - f.offset;
      f.side = d < 0.0f ? -1.0f : 1.0f;
      f.value = std::fabs(d);
    }
    follow_.push_back(f);
  }
  observe(world);  // initial speeds count: a body thrown at 50 m/s has that peak speed
}

void StressProbe::afterStep(const World& world) {
  speedLimited_ += world.lastStats().speedLimited;
  observe(world);
}

void StressProbe::observe(const World& world) {
  const BodyStore& b = world.bodies();
  for (size_t i = 0; i < b.size(); ++i)
    if (b.kind[i] == BodyKind::Dynamic) peakSpeed_ = std::max(peakSpeed_, double(b.v[i].norm()));
  const double e = world.kineticEnergy() + world.potentialEnergy();
  const double eScale = std::fabs(e0_) > 0.0 ? std::fabs(e0_) : 1.0;
  energyGain_ = std::max(energyGain_, (e - e0_) / eScale);
  const double l = totalAngularMomentum(world).norm();
  lDrift_ = std::max(lDrift_, std::fabs(l - l0_) / (l0_ > 0.0 ? l0_ : 1.0));

  for (Follow& f : follow_) {
    if (f.body < 0) continue;
    const size_t i = size_t(f.body);
    switch (f.kind) {
      case StressCheckKind::MaxDrop:
      case StressCheckKind::MinDrop: f.value = f.startY - double(b.xf[i].p.y()); break;  // the last one counts
      case StressCheckKind::PeakSpeed: f.value = std::max(f.value, double(b.v[i].norm())); break;
      case StressCheckKind::NoTunnel:
        f.value = std::min(f.value, double(f.side * (f.axis.dot(b.xf[i].p) - f.offset)));
        break;
      case StressCheckKind::IntermediateAxisFlip: {
        // The body's own angular momentum (about its centre) is fixed in space in free flight; the
        // intermediate axis is unstable, so it swings from along L to against L and back.
        const Mat3 R = b.xf[i].q.toRotationMatrix();
        const Vec3 L = R * (b.inertiaLocal[i] * (R.transpose() * b.w[i]));
        if (!(L.norm() > 0.0f)) break;
        const float s = (R * f.axis).dot(L.normalized());
        const int sign = s > 0.5f ? 1 : s < -0.5f ? -1 : 0;  // hysteresis: wobbles near 0 are no flip
        if (sign != 0 && f.state != 0 && sign != f.state) f.value += 1.0;
        if (sign != 0) f.state = sign;
        break;
      }
      default: break;
    }
  }
}

}  // namespace haif
