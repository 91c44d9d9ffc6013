#include "dynamics/motor_mass.h"

#include "dynamics/pair_push.h"

#include <algorithm>
#include <cmath>

namespace haif {

namespace {

/// A motor whose S diagonal is below this fraction of its own two bodies' (the tree locks its axis:
/// a loop, a merged joint) would ask large impulses of the tree's rounding: the island keeps the sweep.
constexpr double kHeldAxis = 1e-3;
/// Projected Gauss-Seidel passes over S when a motor meets its force bound.
constexpr int kBoundPasses = 32;

// In-place Cholesky of an SPD matrix (row-major, lower triangle); false when not positive definite.
bool cholesky(double* s, uint32_t m) {
  for (uint32_t j = 0; j < m; ++j) {
    double d = s[j * m + j];
    for (uint32_t k = 0; k < j; ++k) d -= s[j * m + k] * s[j * m + k];
    if (!(d > 0.0)) return false;
    d = std::sqrt(d);
    s[j * m + j] = d;
    for (uint32_t i = j + 1; i < m; ++i) {
      double v = s[i * m + j];
      for (uint32_t k = 0; k < j; ++k) v -= s[i * m + k] * s[j * m + k];
      s[i * m + j] = v / d;
    }
  }
  return true;
}

}  // namespace

void prepareTreeMotors(JointConstraint* js, uint32_t n, JointTree& tree, TreeMotors& motors) {
  motors.count = 0;
  if (tree.size() == 0) return;
  uint32_t m = 0;
  for (uint32_t j = 0; j < n; ++j) m += js[j].motor ? 1u : 0u;
  if (m == 0 || m > kMaxTreeMotors) return;
  const uint32_t rows = kJointBlockRows * tree.size();
  motors.joint.resize(m);
  motors.push.resize(size_t(m) * rows);
  motors.answer.resize(size_t(m) * rows);
  motors.system.resize(size_t(m) * m * 2);  // S, then its Cholesky factor
  for (uint32_t j = 0, a = 0; j < n; ++j)
    if (js[j].motor) motors.joint[a++] = j;
  // G and A⁻¹ G per motor, from the tree's own factors.
  PairPush pushes[kMaxTreeMotors];
  for (uint32_t a = 0; a < m; ++a) {
    const JointConstraint& motor = js[motors.joint[a]];
    const PairPush& push = pushes[a] = PairPush::onJointRow(motor, motor.extra[0]);
    double* g = &motors.push[size_t(a) * rows];
    for (uint32_t e = 0; e < tree.size(); ++e) {
      const JointConstraint& jc = js[tree.jointAt(e)];
      double* slot = tree.rowsOf(e);
      for (int i = 0; i < kJointBlockRows; ++i) {
        slot[i] = i < jc.blockRows ? push.rowVelocity(jc, jc.block[i]) : 0.0;
        g[kJointBlockRows * e + i] = slot[i];
      }
    }
    tree.solveRows();
    double* x = &motors.answer[size_t(a) * rows];
    for (uint32_t e = 0; e < tree.size(); ++e) std::copy_n(tree.rowsOf(e), kJointBlockRows, x + kJointBlockRows * e);
  }
  // S = J M⁻¹ Jᵀ (motors sharing a body) − G · A⁻¹ G.
  double* S = motors.system.data();
  for (uint32_t a = 0; a < m; ++a) {
    const JointConstraint& ma = js[motors.joint[a]];
    for (uint32_t b = 0; b < m; ++b) {
      double s = pushes[b].rowVelocity(ma, ma.extra[0]);
      const double* g = &motors.push[size_t(a) * rows];
      const double* x = &motors.answer[size_t(b) * rows];
      for (uint32_t r = 0; r < rows; ++r) s -= g[r] * x[r];
      S[a * m + b] = s;
    }
  }
  for (uint32_t a = 0; a < m; ++a)  // symmetric up to the tree's rounding
    for (uint32_t b = 0; b < a; ++b) S[a * m + b] = S[b * m + a] = 0.5 * (S[a * m + b] + S[b * m + a]);
  for (uint32_t a = 0; a < m; ++a) {
    const double own = 1.0 / double(js[motors.joint[a]].extraMass[0]);
    if (!(S[a * m + a] > kHeldAxis * own)) return;
  }
  double* L = S + size_t(m) * m;
  std::copy_n(S, size_t(m) * m, L);
  if (!cholesky(L, m)) return;
  motors.count = m;
  for (uint32_t a = 0; a < m; ++a) js[motors.joint[a]].motorThroughTree = true;
}

double motorsTakeBack(const TreeMotors& motors, const double* rowVelocity) {
  // gᵀ S⁻¹ g = |L⁻¹ g|², forward substitution through S's Cholesky factor.
  const uint32_t m = motors.count;
  const double* L = motors.system.data() + size_t(m) * m;
  double y[kMaxTreeMotors], taken = 0.0;
  for (uint32_t a = 0; a < m; ++a) {
    double v = rowVelocity[a];
    for (uint32_t k = 0; k < a; ++k) v -= L[a * m + k] * y[k];
    y[a] = v / L[a * m + a];
    taken += y[a] * y[a];
  }
  return taken;
}

void motorChanges(const BodyStore& bodies, const JointConstraint* js, const TreeMotors& motors, const double* S,
                  const double* L, bool useBias, double* d) {
  const uint32_t m = motors.count;
  double rhs[kMaxTreeMotors];
  auto velocity = [&](uint32_t body, bool angular) -> Vec3 {
    if (body == kWorldBody) return Vec3::Zero();
    return angular ? bodies.w[body] : bodies.v[body];
  };
  for (uint32_t a = 0; a < m; ++a) {
    const JointConstraint& c = js[motors.joint[a]];
    const JointRow& r = c.extra[0];
    const float cdot = r.lin.dot(velocity(c.b, false) - velocity(c.a, false)) + r.angB.dot(velocity(c.b, true)) -
                       r.angA.dot(velocity(c.a, true));
    rhs[a] = -(double(cdot) + double(useBias ? c.extraBias[0] : c.extraRelaxBias[0]));
  }
  // Unbounded: S d = rhs by the factor.
  for (uint32_t a = 0; a < m; ++a) {
    double v = rhs[a];
    for (uint32_t k = 0; k < a; ++k) v -= L[a * m + k] * d[k];
    d[a] = v / L[a * m + a];
  }
  for (uint32_t a = m; a-- > 0;) {
    double v = d[a];
    for (uint32_t k = a + 1; k < m; ++k) v -= L[k * m + a] * d[k];
    d[a] = v / L[a * m + a];
  }
  // A motor past its force: clamped, and the others solved again against it (projected Gauss-Seidel).
  auto bounded = [&](uint32_t a, double change) {
    const JointConstraint& c = js[motors.joint[a]];
    const double lambda = std::clamp(double(c.extraImpulse[0]) + change, double(c.extraLo[0]), double(c.extraHi[0]));
    return lambda - double(c.extraImpulse[0]);
  };
  bool clamped = false;
  for (uint32_t a = 0; a < m; ++a) {
    const double b = bounded(a, d[a]);
    clamped |= b != d[a];
    d[a] = b;
  }
  for (int pass = 0; clamped && pass < kBoundPasses; ++pass)
    for (uint32_t a = 0; a < m; ++a) {
      double v = rhs[a];
      for (uint32_t b = 0; b < m; ++b) v -= S[a * m + b] * d[b];
      d[a] = bounded(a, d[a] + v / S[a * m + a]);
    }
}

float applyMotorChanges(BodyStore& bodies, JointConstraint* js, const TreeMotors& motors, const double* S,
                        const double* d) {
  const uint32_t m = motors.count;
  float largest = 0.0f;
  for (uint32_t a = 0; a < m; ++a) {
    JointConstraint& c = js[motors.joint[a]];
    const float l = float(d[a]);
    c.extraImpulse[0] += l;
    const JointRow& r = c.extra[0];
    if (c.dynA) {
      bodies.v[c.a] -= (c.invMassA * l) * r.lin;
      bodies.w[c.a] -= l * r.iAngA;
    }
    if (c.dynB) {
      bodies.v[c.b] += (c.invMassB * l) * r.lin;
      bodies.w[c.b] += l * r.iAngB;
    }
    largest = std::max(largest, float(std::fabs(d[a]) * S[a * m + a]));
  }
  return largest;
}

float solveTreeMotors(BodyStore& bodies, JointConstraint* js, const TreeMotors& motors, bool useBias) {
  const uint32_t m = motors.count;
  if (m == 0) return 0.0f;
  const double* S = motors.system.data();
  const double* L = S + size_t(m) * m;
  double d[kMaxTreeMotors];
  motorChanges(bodies, js, motors, S, L, useBias, d);
  return applyMotorChanges(bodies, js, motors, S, d);
}

bool choleskyFactor(double* s, uint32_t m) { return cholesky(s, m); }

}  // namespace haif
