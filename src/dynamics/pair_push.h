// A push on one row (a contact's or a joint's): the velocity change it gives each of the row's two
// bodies, and how the rows of joints read it. The joint tree's answer to a push is made from what its
// joints' rows read (joint_coupling.h for a contact row's push, motor_mass.h for a motor's).
#pragma once

#include "dynamics/joint_solver.h"

#include <Eigen/Core>

#include <cstdint>

namespace haif {

struct PairPush {
  uint32_t a = 0, b = 0;
  bool dynA = false, dynB = false;
  Eigen::Vector3d va = Eigen::Vector3d::Zero(), wa = Eigen::Vector3d::Zero();
  Eigen::Vector3d vb = Eigen::Vector3d::Zero(), wb = Eigen::Vector3d::Zero();

  /// A unit push on joint c's row r.
  static PairPush onJointRow(const JointConstraint& c, const JointRow& r) {
    PairPush p;
    p.a = c.a, p.b = c.b, p.dynA = c.dynA, p.dynB = c.dynB;
    if (c.dynA) p.va = -double(c.invMassA) * r.lin.cast<double>(), p.wa = -r.iAngA.cast<double>();
    if (c.dynB) p.vb = double(c.invMassB) * r.lin.cast<double>(), p.wb = r.iAngB.cast<double>();
    return p;
  }

  /// The change it gives `body` (none unless the body is one of its two and moves).
  void at(uint32_t body, bool dynamic, Eigen::Vector3d& v, Eigen::Vector3d& w) const {
    v.setZero();
    w.setZero();
    if (!dynamic) return;
    if (dynA && body == a) v += va, w += wa;
    if (dynB && body == b) v += vb, w += wb;
  }

  /// Row r of joint c read under the push, with a per-body velocity `addV` / `addW` added to its
  /// bodies where given (the joints' own answer).
  double rowVelocity(const JointConstraint& c, const JointRow& r, const Eigen::Vector3d* addV = nullptr,
                     const Eigen::Vector3d* addW = nullptr) const {
    Eigen::Vector3d v1, w1, v2, w2;
    at(c.a, c.dynA, v1, w1);
    at(c.b, c.dynB, v2, w2);
    if (addV && c.dynA) v1 += addV[c.a], w1 += addW[c.a];
    if (addV && c.dynB) v2 += addV[c.b], w2 += addW[c.b];
    return r.lin.cast<double>().dot(v2 - v1) + r.angB.cast<double>().dot(w2) - r.angA.cast<double>().dot(w1);
  }
};

}  // namespace haif
