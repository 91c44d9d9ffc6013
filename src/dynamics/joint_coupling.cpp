#include "dynamics/joint_coupling.h"

#include "dynamics/mass_ratio.h"
#include "dynamics/pair_push.h"

#include <algorithm>
#include <cmath>

namespace haif {

namespace {

using Vec3d = Eigen::Vector3d;

/// The joints' answer to a push counts as holding them when it leaves their rows moving at most this
/// fraction of what the push alone gives them (the tree's own rounding leaves ~1e-9).
constexpr double kJointHoldTolerance = 1e-4;
/// A motor's system through the contacts keeps at least this fraction of its own through the tree
/// (solveMotorsThroughContacts): held still, its row asks its force bound, not rounding's answer.
constexpr double kContactHeldMotor = 1e-3;
/// A contact row that moves less than this fraction as much through the joints as on its own bodies
/// is held by them (its force goes into a joint); an island with one is swept.
constexpr double kJointHeldRow = 1e-3;

Vec3d toDouble(const Vec3& v) { return v.cast<double>(); }

// M⁻¹ R_rᵀ at one side of contact c (side 0: body A, 1: body B); zero for a body that does not move.
void freeResponse(const BodyStore& bodies, const ContactConstraint& c, const ChainLink& link, int r, int side,
                  Vec3d& dv, Vec3d& dw) {
  const bool dynamic = side == 0 ? c.dynA : c.dynB;
  if (!dynamic) {
    dv.setZero();
    dw.setZero();
    return;
  }
  const uint32_t body = side == 0 ? c.a : c.b;
  const double sign = side == 0 ? -1.0 : 1.0;
  dv = sign * double(bodies.invMass[body]) * double(link.lin[r]) * toDouble(c.normal.row(0));
  dw = sign * (bodies.invInertiaWorld[body].cast<double>() * toDouble(side == 0 ? link.angA[r] : link.angB[r]));
}

// Row r of link `link` (contact c) read under its own push at one side only: that body's motion along it.
double ownMotion(const BodyStore& bodies, const ContactConstraint& c, const ChainLink& link, int r, int side) {
  Vec3d dv, dw;
  freeResponse(bodies, c, link, r, side, dv, dw);
  const double v = double(link.lin[r]) * toDouble(c.normal.row(0)).dot(dv) +
                   toDouble(side == 0 ? link.angA[r] : link.angB[r]).dot(dw);
  return side == 0 ? -v : v;
}

// A unit push on row r of contact c, as the joints' rows read it: only its own two bodies move.
PairPush contactPush(const BodyStore& bodies, const ContactConstraint& c, const ChainLink& link, int r) {
  PairPush push;
  push.a = c.a, push.b = c.b, push.dynA = c.dynA, push.dynB = c.dynB;
  freeResponse(bodies, c, link, r, 0, push.va, push.wa);
  freeResponse(bodies, c, link, r, 1, push.vb, push.wb);
  return push;
}

// Adds −M⁻¹ Jᵀ x to coupling.dv/dw: what the joints' impulses x (the tree's rows, kJointBlockRows a
// joint in elimination order) take back.
void takeBackThroughJoints(const BodyStore& bodies, const JointCoupling& coupling, const double* xs) {
  const JointTree& tree = *coupling.tree;
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const JointConstraint& jc = coupling.joints[tree.jointAt(e)];
    const double* x = xs + kJointBlockRows * e;
    Vec3d P = Vec3d::Zero(), angA = Vec3d::Zero(), angB = Vec3d::Zero();
    for (int i = 0; i < jc.blockRows; ++i) {
      P += x[i] * toDouble(jc.block[i].lin);
      angA += x[i] * toDouble(jc.block[i].angA);
      angB += x[i] * toDouble(jc.block[i].angB);
    }
    if (jc.dynA) {
      coupling.dv[jc.a] += double(bodies.invMass[jc.a]) * P;
      coupling.dw[jc.a] += bodies.invInertiaWorld[jc.a].cast<double>() * angA;
    }
    if (jc.dynB) {
      coupling.dv[jc.b] -= double(bodies.invMass[jc.b]) * P;
      coupling.dw[jc.b] -= bodies.invInertiaWorld[jc.b].cast<double>() * angB;
    }
  }
}

}  // namespace

bool jointResponse(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint& c,
                   const ChainLink& link, int r) {
  JointTree& tree = *coupling.tree;
  const PairPush push = contactPush(bodies, c, link, r);
  // The rows' velocity with the joints' answer `withJoints` added (dv, dw), or without it.
  auto rowVelocity = [&](const JointConstraint& jc, int i, bool withJoints) {
    return withJoints ? push.rowVelocity(jc, jc.block[i], coupling.dv, coupling.dw) : push.rowVelocity(jc, jc.block[i]);
  };
  // g = J M⁻¹ R_rᵀ, then x = K⁻¹ g in the tree's own factors.
  double largest = 0.0;
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const JointConstraint& jc = coupling.joints[tree.jointAt(e)];
    double* g = tree.rowsOf(e);
    for (int i = 0; i < jc.blockRows; ++i) {
      g[i] = rowVelocity(jc, i, false);
      largest = std::max(largest, std::fabs(g[i]));
    }
  }
  tree.solveRows();
  takeBackThroughJoints(bodies, coupling, tree.rowsOf(0));
  // The answer holds the joints when the tree's factor is sound. Where it kept nearly redundant
  // rows, or let go of rows that were not quite redundant (a bridge hinged to a post at each end, a
  // ragdoll's limbs), it leaves the rows moving as fast as the push itself, and the joints' answer
  // to the rounds' impulses (solved in float) is far from the factored one.
  double moving = 0.0;
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const JointConstraint& jc = coupling.joints[tree.jointAt(e)];
    const double* x = tree.rowsOf(e);  // a soft row holds when J v = compliance * x (the impulse is -x)
    for (int i = 0; i < jc.blockRows; ++i)
      moving = std::max(moving, std::fabs(rowVelocity(jc, i, true) - double(jc.blockCompliance[i]) * x[i]));
  }
  return moving <= kJointHoldTolerance * largest;
}

double rowAtResponse(const JointCoupling& coupling, const ContactConstraint& c, const ChainLink& link, int q) {
  const Vec3d n = toDouble(c.normal.row(0));
  double v = 0.0;
  if (c.dynA) v -= double(link.lin[q]) * n.dot(coupling.dv[c.a]) + toDouble(link.angA[q]).dot(coupling.dw[c.a]);
  if (c.dynB) v += double(link.lin[q]) * n.dot(coupling.dv[c.b]) + toDouble(link.angB[q]).dot(coupling.dw[c.b]);
  return v;
}

double motorsAtResponse(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint& c,
                        const ChainLink& link, int r) {
  if (!coupling.motors || coupling.motors->count == 0) return 0.0;
  const TreeMotors& motors = *coupling.motors;
  const PairPush push = contactPush(bodies, c, link, r);
  double g[kMaxTreeMotors];
  for (uint32_t a = 0; a < motors.count; ++a) {
    const JointConstraint& m = coupling.joints[motors.joint[a]];
    g[a] = push.rowVelocity(m, m.extra[0], coupling.dv, coupling.dw);
  }
  return motorsTakeBack(motors, g);
}

namespace {

// Zeroes a per-body pair of scratch arrays at the joints' moving bodies.
void zeroAtJoints(const JointCoupling& coupling, Vec3d* v, Vec3d* w) {
  for (uint32_t j = 0; j < coupling.jointCount; ++j) {
    const JointConstraint& jc = coupling.joints[j];
    if (jc.dynA) v[jc.a].setZero(), w[jc.a].setZero();
    if (jc.dynB) v[jc.b].setZero(), w[jc.b].setZero();
  }
}

// Zeroes the noted change of every body that can have one: the joints' and the contacts' bodies.
void clearChange(const JointCoupling& coupling) {
  zeroAtJoints(coupling, coupling.changeV, coupling.changeW);
  for (uint32_t j = 0; j < coupling.contactCount; ++j) {
    const ContactConstraint& c = coupling.contacts[j];
    if (c.dynA) coupling.changeV[c.a].setZero(), coupling.changeW[c.a].setZero();
    if (c.dynB) coupling.changeV[c.b].setZero(), coupling.changeW[c.b].setZero();
  }
}

}  // namespace

void clearJointResponse(const JointCoupling& coupling) { zeroAtJoints(coupling, coupling.dv, coupling.dw); }

void addContactChange(const JointCoupling& coupling, const ContactConstraint& c, const float* applied) {
  Vec3d P = Vec3d::Zero(), turnA = Vec3d::Zero(), turnB = Vec3d::Zero();
  for (int i = 0; i < c.count; ++i) {
    P += double(applied[i]) * toDouble(c.normal.row(i));
    turnA += double(applied[i]) * toDouble(c.iAn.row(i));
    turnB += double(applied[i]) * toDouble(c.iBn.row(i));
  }
  if (c.dynA) {
    coupling.changeV[c.a] -= double(c.invMassA) * P;
    coupling.changeW[c.a] -= turnA;
  }
  if (c.dynB) {
    coupling.changeV[c.b] += double(c.invMassB) * P;
    coupling.changeW[c.b] += turnB;
  }
}

void addBodyChange(const JointCoupling& coupling, uint32_t body, const Vec3& dv, const Vec3& dw) {
  coupling.changeV[body] += toDouble(dv);
  coupling.changeW[body] += toDouble(dw);
}

void holdJointChange(BodyStore& bodies, const JointCoupling& coupling) {
  JointTree& tree = *coupling.tree;
  auto change = [&](uint32_t body, bool dynamic, bool angular) -> Vec3d {
    if (!dynamic) return Vec3d::Zero();
    return angular ? coupling.changeW[body] : coupling.changeV[body];
  };
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const JointConstraint& jc = coupling.joints[tree.jointAt(e)];
    const Vec3d va = change(jc.a, jc.dynA, false), wa = change(jc.a, jc.dynA, true);
    const Vec3d vb = change(jc.b, jc.dynB, false), wb = change(jc.b, jc.dynB, true);
    double* g = tree.rowsOf(e);
    for (int i = 0; i < jc.blockRows; ++i) {
      const JointRow& row = jc.block[i];
      g[i] = -(toDouble(row.lin).dot(vb - va) + toDouble(row.angB).dot(wb) - toDouble(row.angA).dot(wa));
    }
  }
  tree.solveRows();
  tree.applyRows(bodies, coupling.joints);
  clearChange(coupling);
}

bool jointsCarryContacts(const BodyStore& bodies, const JointCoupling& coupling, const ContactConstraint* cs,
                         const ChainLink* links, uint32_t n, float ratio) {
  // How much row r of link j moves through the joints, as a share of what it moves on its own
  // bodies; negative: the tree's factor cannot carry the contacts' rows. `withMotors`: the island's
  // motors hold their axes too (a servo pressing its hand on a stack of crates carries their push
  // as a joint would, up to its force).
  auto share = [&](uint32_t j, int r, bool withMotors) {
    const double free = links[j].diag[r][r];
    const bool holds = jointResponse(bodies, coupling, cs[j], links[j], r);
    double through = free + rowAtResponse(coupling, cs[j], links[j], r);
    const double taken = withMotors ? motorsAtResponse(bodies, coupling, cs[j], links[j], r) : 0.0;
    if (taken > 0.0) through = std::max(0.0, through - taken);  // held to rounding: not carried less
    clearJointResponse(coupling);
    return holds && free > 0.0 ? through / free : -1.0;
  };
  auto jointed = [&](uint32_t body) {
    for (uint32_t i = 0; i < coupling.jointCount; ++i) {
      const JointConstraint& jc = coupling.joints[i];
      if ((jc.dynA && jc.a == body) || (jc.dynB && jc.b == body)) return true;
    }
    return false;
  };
  // A light body pressed by a heavy one: sweeps pass the heavy one's push through it a sliver at a
  // time, as through a light box under a heavy one (the small-island solve's case without joints).
  // In an island with motors, a jointed body is as heavy as the joints and motors make it along the
  // row (`share`: the row's motion through them): robot_arm's 2 kg hand, held by its servos, moves
  // 1/11 as much as the 3 kg crate it presses, and sweeps pushed the crate 24 cm into the one below.
  // Not without motors: rope_bridge's planks, held by the bridge, read 8 times heavier than the
  // crates on them, and the coupled solve every step took 5 times the sweeps' time at 4 iterations
  // for 5 mm less depth.
  const bool motorsHold = coupling.motors && coupling.motors->count > 0;
  auto pressesLight = [&](uint32_t j, double rowShare) {
    const ContactConstraint& c = cs[j];
    if (!(c.dynA && c.dynB)) return false;
    if (massesDiffer(c.invMassA, c.invMassB, ratio)) return true;
    if (!motorsHold) return false;
    const bool jointedA = jointed(c.a);
    if (jointedA == jointed(c.b)) return false;
    const double own = ownMotion(bodies, c, links[j], 0, jointedA ? 1 : 0);  // the free body's
    const double held = std::max(0.0, rowShare * links[j].diag[0][0] - own);  // the jointed body's
    return massesDiffer(float(held), float(own), ratio);
  };
  // First whether any force row is carried (most islands with joints have none: one solve a link).
  bool carried = false;
  for (uint32_t j = 0; j < n && !carried; ++j) {
    const double s = share(j, 0, true);
    if (s < 0.0) return false;
    carried = s * double(ratio) <= 1.0 || pressesLight(j, s);
  }
  if (!carried) return false;
  // Then that no row is held by the joints (almost) still: it shares its load with them in any
  // proportion (a plank resting on a fulcrum right under its hinge). Solved together, the split's
  // impulses grew to thousands of N s a step, warm started, and locked the plank or threw its load.
  for (uint32_t j = 0; j < n; ++j)
    for (int r = 0; r < links[j].rank; ++r) {
      const double s = share(j, r, false);  // the rows are solved through the tree alone
      if (!(s > kJointHeldRow)) return false;
    }
  return true;
}

bool solveMotorsThroughContacts(BodyStore& bodies, const JointCoupling& coupling, ContactConstraint* cs,
                                const ChainLink* links, const DenseNormalSystem& system, bool useBias, float& largest) {
  if (!coupling.motors || coupling.motors->count == 0 || system.rows == 0) return false;
  const TreeMotors& motors = *coupling.motors;
  const uint32_t m = motors.count;
  const int rows = system.rows;
  // C: each contact row's motion under each motor's unit push, the tree answering (rows × m).
  double C[DenseNormalSystem::kMaxRows * kMaxTreeMotors], X[DenseNormalSystem::kMaxRows * kMaxTreeMotors];
  const size_t treeRows = size_t(kJointBlockRows) * coupling.tree->size();
  for (uint32_t a = 0; a < m; ++a) {
    const JointConstraint& motor = coupling.joints[motors.joint[a]];
    const PairPush push = PairPush::onJointRow(motor, motor.extra[0]);
    takeBackThroughJoints(bodies, coupling, &motors.answer[a * treeRows]);
    if (motor.dynA) coupling.dv[motor.a] += push.va, coupling.dw[motor.a] += push.wa;
    if (motor.dynB) coupling.dv[motor.b] += push.vb, coupling.dw[motor.b] += push.wb;
    for (int i = 0; i < rows; ++i) {
      const uint32_t j = system.linkOf[i];
      C[i * m + a] = rowAtResponse(coupling, cs[j], links[j], system.partOf[i]);
    }
    clearJointResponse(coupling);
  }
  // X = A⁺ C, the contacts' answer to each push (least norm, as the rounds solve them).
  double b[DenseNormalSystem::kMaxRows], x[DenseNormalSystem::kMaxRows], scratch[DenseNormalSystem::kMaxRows];
  for (uint32_t a = 0; a < m; ++a) {
    for (int i = 0; i < rows; ++i) b[i] = C[i * m + a];
    solveFactored(system, b, x, scratch);
    for (int k = 0; k < rows; ++k) X[system.order[k] * m + a] = x[k];
  }
  // S' = S − Cᵀ X: the motors' system with the contacts answering, and its factor.
  double Sp[kMaxTreeMotors * kMaxTreeMotors], Lp[kMaxTreeMotors * kMaxTreeMotors];
  const double* S = motors.system.data();
  for (uint32_t a = 0; a < m; ++a)
    for (uint32_t c = 0; c < m; ++c) {
      double v = S[a * m + c];
      for (int i = 0; i < rows; ++i) v -= C[i * m + a] * X[i * m + c];
      Sp[a * m + c] = v;
    }
  for (uint32_t a = 0; a < m; ++a)
    for (uint32_t c = 0; c < a; ++c) Sp[a * m + c] = Sp[c * m + a] = 0.5 * (Sp[a * m + c] + Sp[c * m + a]);
  // A motor the contacts hold still (a hand pressing a crate on the ground) has S' ≈ 0 up to
  // rounding: kept positive, its change is large and its force bound takes it.
  for (uint32_t a = 0; a < m; ++a) Sp[a * m + a] += kContactHeldMotor * S[a * m + a];
  std::copy_n(Sp, size_t(m) * m, Lp);
  if (!choleskyFactor(Lp, m)) return false;
  double d[kMaxTreeMotors];
  motorChanges(bodies, coupling.joints, motors, Sp, Lp, useBias, d);
  // The contacts answer with −X d; read as holding, they may not pull: where a point would, the
  // motors are solved as before (the contacts let go, the motors see the bodies free).
  for (int i = 0; i < rows; ++i) {
    double v = 0.0;
    for (uint32_t a = 0; a < m; ++a) v -= X[i * m + a] * d[a];
    b[i] = v;
  }
  float applied[DenseNormalSystem::kMaxLinks][kMaxManifoldPoints] = {};
  for (uint32_t j = 0; j < coupling.contactCount; ++j) {
    const int first = system.rowOf[j];
    if (first < 0) continue;
    const ChainLink& link = links[j];
    for (int p = 0; p < cs[j].count; ++p) {
      if (!(link.points & (1u << p))) continue;
      double change = 0.0;
      for (int q = 0; q < link.rank; ++q) change += double(link.basis[p][q]) * b[first + q];
      if (double(cs[j].normalImpulse[p]) + change < 0.0) return false;
      applied[j][p] = float(change);
    }
  }
  // Both answers within the sweep: the motors' change and the contacts' to it (the tree's to both
  // follows in its solve), so that a sweep, the last one too, does not end with the motors driving
  // the bodies into the contacts.
  largest = applyMotorChanges(bodies, coupling.joints, motors, Sp, d);
  for (uint32_t j = 0; j < coupling.contactCount; ++j) {
    if (system.rowOf[j] < 0) continue;
    ContactConstraint& c = cs[j];
    for (int p = 0; p < c.count; ++p) c.normalImpulse[p] += applied[j][p];
    Vec3 va = bodies.v[c.a], wa = bodies.w[c.a], vb = bodies.v[c.b], wb = bodies.w[c.b];
    applyNormalChange(c, applied[j], va, wa, vb, wb);
    storeVelocities(bodies, c, va, wa, vb, wb);
  }
  return true;
}

}  // namespace haif
