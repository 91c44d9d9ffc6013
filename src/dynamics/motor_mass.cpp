#include "dynamics/motor_mass.h"

#include <cmath>

namespace haif {

namespace {

using Vec3d = Eigen::Vector3d;

/// Below this fraction of its own two bodies' K the axis is held by the tree (a loop, a merged
/// joint): the mass would be large and rest on the tree's rounding, so the row keeps its own.
constexpr double kHeldAxis = 1e-3;

/// Each such motor costs a tree solve per sweep (the tree answers it before the next motor): past
/// this many motor-joints of work a step (32 servos along a 32-link arm) motors keep their own mass.
constexpr uint64_t kMotorTreeWork = 1024;

Vec3d toDouble(const Vec3& v) { return v.cast<double>(); }

}  // namespace

void motorMassesThroughTree(JointConstraint* js, uint32_t n, JointTree& tree) {
  if (tree.size() == 0) return;
  uint32_t motors = 0;
  for (uint32_t m = 0; m < n; ++m) motors += js[m].motor ? 1u : 0u;
  if (motors == 0 || uint64_t(motors) * tree.size() > kMotorTreeWork) return;
  for (uint32_t m = 0; m < n; ++m) {
    JointConstraint& motor = js[m];
    if (!motor.motor || !(motor.extraMass[0] > 0.0f)) continue;
    const JointRow& row = motor.extra[0];
    // M⁻¹ Jᵀ of a unit push on the motor row, at its two bodies.
    const Vec3d dvA = motor.dynA ? Vec3d(-double(motor.invMassA) * toDouble(row.lin)) : Vec3d::Zero();
    const Vec3d dwA = motor.dynA ? Vec3d(-toDouble(row.iAngA)) : Vec3d::Zero();
    const Vec3d dvB = motor.dynB ? Vec3d(double(motor.invMassB) * toDouble(row.lin)) : Vec3d::Zero();
    const Vec3d dwB = motor.dynB ? Vec3d(toDouble(row.iAngB)) : Vec3d::Zero();
    auto pushAt = [&](uint32_t body, bool dynamic, Vec3d& v, Vec3d& w) {
      v.setZero();
      w.setZero();
      if (!dynamic) return;
      if (motor.dynA && body == motor.a) v += dvA, w += dwA;
      if (motor.dynB && body == motor.b) v += dvB, w += dwB;
    };
    // g: each tree row's velocity under the push; x = A⁻¹ g in the tree's factors; K −= g · x.
    double coupled = 0.0;
    for (uint32_t e = 0; e < tree.size(); ++e) {
      const JointConstraint& jc = js[tree.jointAt(e)];
      double* g = tree.rowsOf(e);
      Vec3d va, wa, vb, wb;
      pushAt(jc.a, jc.dynA, va, wa);
      pushAt(jc.b, jc.dynB, vb, wb);
      for (int i = 0; i < jc.blockRows; ++i) {
        const JointRow& r = jc.block[i];
        g[i] = toDouble(r.lin).dot(vb - va) + toDouble(r.angB).dot(wb) - toDouble(r.angA).dot(wa);
      }
    }
    tree.solveRows();  // x replaces g in place: g is made again, row by row, for g · x
    for (uint32_t e = 0; e < tree.size(); ++e) {
      const JointConstraint& jc = js[tree.jointAt(e)];
      const double* x = tree.rowsOf(e);
      Vec3d va, wa, vb, wb;
      pushAt(jc.a, jc.dynA, va, wa);
      pushAt(jc.b, jc.dynB, vb, wb);
      for (int i = 0; i < jc.blockRows; ++i) {
        const JointRow& r = jc.block[i];
        const double g = toDouble(r.lin).dot(vb - va) + toDouble(r.angB).dot(wb) - toDouble(r.angA).dot(wa);
        coupled += g * x[i];
      }
    }
    const double own = 1.0 / double(motor.extraMass[0]);
    const double through = own - coupled;
    if (through > kHeldAxis * own && through <= own * (1.0 + 1e-6)) {
      motor.extraMass[0] = float(1.0 / through);
      motor.motorThroughTree = true;
    }
  }
}

}  // namespace haif
