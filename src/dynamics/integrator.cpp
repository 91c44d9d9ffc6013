#include "dynamics/integrator.h"

namespace haif {

void integrateVelocities(BodyStore& b, uint32_t begin, uint32_t end, const Vec3& gravity, float dt) {
  for (uint32_t i = begin; i < end; ++i) {
    if (b.kind[i] != BodyKind::Dynamic || b.asleep[i]) continue;
    b.v[i] += dt * (gravity + b.invMass[i] * b.force[i]);
    b.w[i] += dt * (b.invInertiaWorld[i] * b.torque[i]);
    // Implicit damping: stable for any damping coefficient and time step.
    if (b.linearDamping[i] > 0.0f) b.v[i] *= 1.0f / (1.0f + dt * b.linearDamping[i]);
    if (b.angularDamping[i] > 0.0f) b.w[i] *= 1.0f / (1.0f + dt * b.angularDamping[i]);
    b.force[i].setZero();
    b.torque[i].setZero();
  }
}

void integratePositions(BodyStore& b, uint32_t begin, uint32_t end, float dt, float sleepLinear,
                        float sleepAngular) {
  const float lin2 = sleepLinear * sleepLinear, ang2 = sleepAngular * sleepAngular;
  for (uint32_t i = begin; i < end; ++i) {
    const BodyKind k = b.kind[i];
    if (k == BodyKind::Static || b.asleep[i]) continue;
    Transform& xf = b.xf[i];
    xf.p += dt * b.v[i];
    const Vec3 w = b.w[i];
    const Quat qOld = xf.q;
    if (w.squaredNorm() > 0.0f) {
      const Quat dq(0.0f, 0.5f * dt * w.x(), 0.5f * dt * w.y(), 0.5f * dt * w.z());
      Quat q = qOld;
      q.coeffs() += (dq * qOld).coeffs();
      xf.q = q.normalized();
    }
    if (k != BodyKind::Dynamic) continue;
    if (w.squaredNorm() > 0.0f && b.implicitGyro[i]) {
      // Solve I (ω' - ω) + dt ω' × I ω' = 0 in the body frame by one Newton step from ω.
      const Mat3& I = b.inertiaLocal[i];
      const Vec3 wb = xf.q.conjugate() * w;
      const Vec3 Iw = I * wb;
      auto skew = [](const Vec3& a) {
        Mat3 m;
        m << 0.0f, -a.z(), a.y(), a.z(), 0.0f, -a.x(), -a.y(), a.x(), 0.0f;
        return m;
      };
      const Mat3 J = I + dt * (skew(wb) * I - skew(Iw));
      b.w[i] = xf.q * (wb - J.inverse() * (dt * wb.cross(Iw)));
    } else if (w.squaredNorm() > 0.0f) {
      // Angular momentum in world space is unchanged by a pure rotation of the body.
      const Vec3 L = qOld * (b.inertiaLocal[i] * (qOld.conjugate() * w));
      b.w[i] = xf.q * (b.invInertiaLocal[i] * (xf.q.conjugate() * L));
    }
    b.updateWorldInertia(i);
    const bool slow = b.v[i].squaredNorm() < lin2 && b.w[i].squaredNorm() < ang2;
    b.restTime[i] = slow ? b.restTime[i] + dt : 0.0f;
  }
}

}  // namespace haif
