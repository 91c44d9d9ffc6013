#include "dynamics/integrator.h"

namespace haif {

namespace {

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0.0f, -a.z(), a.y(), a.z(), 0.0f, -a.x(), -a.y(), a.x(), 0.0f;
  return m;
}

// Newton iterations for the midpoint angular velocity; it converges quadratically from the predictor,
// so two or three suffice; the stop is relative to |w|.
constexpr int kMidpointIterations = 4;
constexpr float kMidpointTolerance2 = 1e-12f;
// When the predictor changes w by less than this (relative), its own error (second order in that change,
// ~1e-8) is below float rounding and Newton is skipped: bodies at rest or turning slowly.
constexpr float kPredictorExact2 = 1e-8f;
// w along a principal axis to within 1e-6 rad (always so for cubes and spheres): nothing turns L away
// from w, so the body turns by w and keeps it (the cheapest path, no change of frame).
constexpr float kPrincipal2 = 1e-12f;

// q' = normalize((1, dt/2 w) q): the Cayley rotation of dt w (world frame).
Quat cayleyTurn(const Quat& q, const Vec3& w, float dt) {
  const Quat dq(0.0f, 0.5f * dt * w.x(), 0.5f * dt * w.y(), 0.5f * dt * w.z());
  Quat r = q;
  r.coeffs() += (dq * q).coeffs();
  return r.normalized();
}

// Implicit midpoint rule on Euler's equations in the body frame, dL/dt = L x w with L0 = I wb:
// L1 = L0 + dt Lm x wm, Lm = (L0 + L1) / 2 = I wm. Returns wm, found by Newton on
// f(wm) = I wm - (dt/2) (I wm) x wm - L0 = 0. The rule keeps |L|^2 and the energy L.I^-1 L exactly (both
// invariants are quadratic), so a free body neither spins up nor loses energy, and its polhode, hence
// the intermediate-axis flip, is the true one.
Vec3 midpointBodyAngularVelocity(const Mat3& I, const Mat3& invI, const Vec3& wb, const Vec3& L0, float dt) {
  const float h = 0.5f * dt;
  const Vec3 predict = h * (invI * L0.cross(wb));  // explicit half step as the starting guess
  Vec3 wm = wb + predict;
  if (predict.squaredNorm() <= kPredictorExact2 * wb.squaredNorm()) return wm;
  for (int k = 0; k < kMidpointIterations; ++k) {
    const Vec3 Lm = I * wm;
    const Vec3 r = Lm - h * Lm.cross(wm) - L0;
    const Mat3 J = I + h * (skew(wm) * I - skew(Lm));
    const Vec3 step = J.inverse() * r;
    wm -= step;
    if (step.squaredNorm() <= kMidpointTolerance2 * wm.squaredNorm()) break;
  }
  return wm;
}

// The implicit midpoint rule's turn of a body free to turn (inertia I in its frame, angular velocity
// wb and momentum L0 there): q turns by the Cayley rotation of dt w_mid, and the returned world w reads
// the unchanged world L in the new frame, so |L| and the energy are kept. w = I⁻¹ L is taken in the
// body frame, not through the world inverse inertia: for a thin body that matrix mixes 1/I of very
// different sizes in every entry, and its rounding turned L by ~1e-7 a step (a thin capsule's |L|
// drifted by 6e-5 in 600 steps at -O3 and 1.8e-4 at -O2; now 2e-5 at both).
Vec3 turnFreely(Quat& q, const Mat3& I, const Mat3& invI, const Vec3& wb, const Vec3& L0, float dt) {
  const Quat qOld = q;
  const Vec3 wm = midpointBodyAngularVelocity(I, invI, wb, L0, dt);
  q = (qOld * Quat(1.0f, 0.5f * dt * wm.x(), 0.5f * dt * wm.y(), 0.5f * dt * wm.z())).normalized();
  return q * (invI * (q.conjugate() * (qOld * L0)));
}

// The rest timer sleeping reads: how long the body has been slower than both thresholds (squared).
void noteRest(BodyStore& b, uint32_t i, float dt, float lin2, float ang2) {
  const bool slow = b.v[i].squaredNorm() < lin2 && b.w[i].squaredNorm() < ang2;
  b.restTime[i] = slow ? b.restTime[i] + dt : 0.0f;
}

}  // namespace

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
    if (k == BodyKind::Static || b.asleep[i] || b.pinned[i]) continue;
    Transform& xf = b.xf[i];
    xf.p += dt * b.v[i];
    const Vec3 w = b.w[i];
    const bool spinning = w.squaredNorm() > 0.0f;
    const bool freeBody = k == BodyKind::Dynamic && !b.implicitGyro[i];
    const Vec3 u = b.invInertiaWorld[i] * w;
    if (spinning && freeBody && u.cross(w).squaredNorm() > kPrincipal2 * u.squaredNorm() * w.squaredNorm()) {
      // Free body: the exact midpoint rule (turnFreely).
      const Mat3& I = b.inertiaLocal[i];
      const Vec3 wb = xf.q.conjugate() * w;
      b.w[i] = turnFreely(xf.q, I, b.invInertiaLocal[i], wb, I * wb, dt);
      b.updateWorldInertia(i);
    } else {
      // Kinematic, jointed, or free and spinning about a principal axis (w kept).
      if (spinning) xf.q = cayleyTurn(xf.q, w, dt);
      if (k != BodyKind::Dynamic) continue;
      if (spinning && !freeBody) {
        // Jointed body: solve I (ω' - ω) + dt ω' × I ω' = 0 in the body frame by one Newton step from ω.
        const Mat3& I = b.inertiaLocal[i];
        const Vec3 wb = xf.q.conjugate() * w;
        const Vec3 Iw = I * wb;
        const Mat3 J = I + dt * (skew(wb) * I - skew(Iw));
        b.w[i] = xf.q * (wb - J.inverse() * (dt * wb.cross(Iw)));
      }
      b.updateWorldInertia(i);
    }
    noteRest(b, i, dt, lin2, ang2);
  }
}

void integratePinned(BodyStore& b, const PinnedBody& pin, const Vec3& gravity, float dt, float sleepLinear,
                     float sleepAngular) {
  const uint32_t i = pin.body;
  if (b.asleep[i]) return;
  Transform& xf = b.xf[i];
  const Vec3& a = pin.anchor;
  // Inertia about the held point (parallel axes), body frame. Inverted in double: for a small bob on
  // a long arm it is ill-conditioned (1.001 across the arm, 0.001 along it for a 5 cm ball 1 m out),
  // and a float inverse's error across the arm, read back next step as momentum through I, took
  // 3e-6 of the swing's momentum every step (0.04 % of its energy a swing at 60°).
  const Eigen::Matrix3d I = (b.inertiaLocal[i] + b.mass[i] * (a.squaredNorm() * Mat3::Identity() - a * a.transpose())).cast<double>();
  const Eigen::Matrix3d invI = I.inverse();
  const Quat qOld = xf.q;
  // Angular momentum about the point (world), from both velocities: what the solve left of the motion
  // that the joint does not hold (a contact's push) keeps its moment about the point.
  const Vec3 weight = b.mass[i] * gravity;
  const Vec3 L0 = qOld * (b.inertiaLocal[i] * (qOld.conjugate() * b.w[i])) + b.mass[i] * (xf.p - pin.point).cross(b.v[i]);
  // Gravity's turning impulse came whole from the step start's pose (integrateVelocities); half of it
  // is taken back before the turn and the half from the end pose given after it: the Störmer-Verlet
  // kick. The whole kick first is symplectic Euler, whose energy reads ±ω dt / 2 off the swing's
  // (±2.5 % at 60 Hz for a 1 m pendulum, at any amplitude); split, the error is second order.
  const Vec3 half = L0 - 0.5f * dt * (xf.p - pin.point).cross(weight);
  const Vec3 halfBody = qOld.conjugate() * half;
  const Vec3 wb = (invI * halfBody.cast<double>()).cast<float>();
  turnFreely(xf.q, I.cast<float>(), invI.cast<float>(), wb, halfBody, dt);
  xf.p = pin.point - xf.q * a;
  const Vec3 L1 = half + 0.5f * dt * (xf.p - pin.point).cross(weight);
  b.w[i] = xf.q * (invI * (xf.q.conjugate() * L1).cast<double>()).cast<float>();
  b.v[i] = b.w[i].cross(xf.p - pin.point);
  b.updateWorldInertia(i);
  noteRest(b, i, dt, sleepLinear * sleepLinear, sleepAngular * sleepAngular);
}

}  // namespace haif
