// The rows prepareContact builds, checked against the contact's Jacobians formed here from scratch
// (in double): the friction rows at the manifold's centre and their coupling, which the sweep uses
// as solved (the 2x2 tangent block, the twist mass and the twist-tangent couplings).
#include "dynamics/contact_solver.h"
#include "tilted_patch.h"

#include <gtest/gtest.h>

#include <cmath>

namespace haif {
namespace {

using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;

// One row of a contact: J v = lin·(vB − vA) + angB·wB − angA·wA.
struct Row {
  Vec3d lin, angA, angB;
};

// J_r M⁻¹ J_sᵀ of two rows of the patch's contact, from its bodies' masses and world inertias.
struct TiltedPatch : test::TiltedPatch {
  double coupling(const Row& r, const Row& s) const {
    const double mSum = double(bodies.invMass[0]) + double(bodies.invMass[1]);
    const Mat3d iA = bodies.invInertiaWorld[0].cast<double>(), iB = bodies.invInertiaWorld[1].cast<double>();
    return mSum * r.lin.dot(s.lin) + r.angA.dot(iA * s.angA) + r.angB.dot(iB * s.angB);
  }
};

Vec3d rowOf(const RowVectors& rows, int i) { return rows.row(i).cast<double>(); }

TEST(ContactRows, FrictionRowsAndTheirCouplingMatchTheJacobians) {
  TiltedPatch s;
  SolverParams sp;
  sp.warmStart = false;
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, sp, c);
  ASSERT_EQ(c.count, 4);

  // The frame: the mean normal and two tangents, orthonormal.
  Vec3d centre = Vec3d::Zero();
  for (int i = 0; i < 4; ++i) centre += s.contact.manifold.points[i].position.cast<double>() / 4.0;
  const Vec3d n = s.contact.manifold.points[0].normal.cast<double>();
  const Vec3d t1 = c.tangent1().cast<double>(), t2 = c.tangent2().cast<double>();
  EXPECT_NEAR(t1.norm(), 1.0, 1e-6);
  EXPECT_NEAR(t2.norm(), 1.0, 1e-6);
  EXPECT_NEAR(t1.dot(t2), 0.0, 1e-6);
  EXPECT_NEAR(t1.dot(n), 0.0, 1e-6);
  EXPECT_NEAR(t2.dot(n), 0.0, 1e-6);
  EXPECT_NEAR((c.twistAxis().cast<double>() - n).norm(), 0.0, 1e-6);

  // The three rows at the centre, formed here.
  const Vec3d rA = centre - s.bodies.xf[0].p.cast<double>(), rB = centre - s.bodies.xf[1].p.cast<double>();
  const Row rows[3] = {{t1, rA.cross(t1), rB.cross(t1)}, {t2, rA.cross(t2), rB.cross(t2)}, {Vec3d::Zero(), n, n}};
  const Mat3d iA = s.bodies.invInertiaWorld[0].cast<double>(), iB = s.bodies.invInertiaWorld[1].cast<double>();
  for (int r = 0; r < 3; ++r) {
    EXPECT_LT((rowOf(c.frictionLinear, r) - rows[r].lin).norm(), 1e-5) << "row " << r;
    EXPECT_LT((rowOf(c.frictionAngularA, r) - rows[r].angA).norm(), 1e-5) << "row " << r;
    EXPECT_LT((rowOf(c.frictionAngularB, r) - rows[r].angB).norm(), 1e-5) << "row " << r;
    EXPECT_LT((rowOf(c.frictionInverseA, r) - iA * rows[r].angA).norm(), 1e-5) << "row " << r;
    EXPECT_LT((rowOf(c.frictionInverseB, r) - iB * rows[r].angB).norm(), 1e-5) << "row " << r;
  }
  EXPECT_EQ(rowOf(c.frictionLinear, 3).norm(), 0.0);  // the unused fourth row
  EXPECT_EQ(rowOf(c.frictionInverseA, 3).norm(), 0.0);

  // The tangent block's inverse, the twist mass and the twist's coupling with each tangent.
  Eigen::Matrix2d Kt;
  Kt << s.coupling(rows[0], rows[0]), s.coupling(rows[0], rows[1]), s.coupling(rows[1], rows[0]),
      s.coupling(rows[1], rows[1]);
  const Eigen::Matrix2d Mt = Kt.inverse();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_NEAR(c.tangentMass[i][j], Mt(i, j), 1e-4 * std::abs(Mt(i, i))) << i << j;
  EXPECT_NEAR(c.twistMass, 1.0 / s.coupling(rows[2], rows[2]), 1e-4 * c.twistMass);
  for (int i = 0; i < 2; ++i) {
    const double k = s.coupling(rows[i], rows[2]);
    EXPECT_NEAR(c.twistCoupling[i], k, 1e-5 + 1e-4 * std::abs(k)) << "tangent " << i;
  }

  // The twist lever: the mean distance from the centre of the patch the 4 points bound, taken as
  // 0.541 times their RMS distance in the contact plane (exact for a square: (√2 + ln(1 + √2)) / 3 / √2).
  // The points stand 1 cm apart along the normal; that is no width of the patch.
  double meanSquare = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Vec3d d = s.contact.manifold.points[i].position.cast<double>() - centre;
    meanSquare += (d.dot(t1) * d.dot(t1) + d.dot(t2) * d.dot(t2)) / 4.0;
  }
  EXPECT_NEAR(c.twistRadius, 0.541 * std::sqrt(meanSquare), 1e-5);
}

TEST(ContactRows, FrictionActsWherePointsTouch) {
  // Two of the four points are 5 cm apart from the nearest (a top's speculative rim, a box landing on
  // an edge): the friction rows act at the middle of the two that touch, and the twist's lever is
  // that segment's. The normal rows keep all four.
  TiltedPatch s;
  const Vec3 n = s.contact.manifold.points[0].normal;
  for (int i = 2; i < 4; ++i) {
    s.contact.manifold.points[i].depth = -0.05f;
    s.contact.manifold.points[i].position -= 0.05f * n;
  }
  SolverParams sp;
  sp.warmStart = false;
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, sp, c);
  ASSERT_EQ(c.count, 4);
  const Vec3d p0 = s.contact.manifold.points[0].position.cast<double>(), p1 = s.contact.manifold.points[1].position.cast<double>();
  const Vec3d centre = 0.5 * (p0 + p1);
  const Vec3d t1 = c.tangent1().cast<double>();
  const Vec3d rA = centre - s.bodies.xf[0].p.cast<double>();
  EXPECT_LT((rowOf(c.frictionAngularA, 0) - rA.cross(t1)).norm(), 1e-5) << "friction at the touching pair's middle";
  const Vec3d d = p1 - p0;
  const double inPlane = std::sqrt(d.squaredNorm() - d.dot(n.cast<double>()) * d.dot(n.cast<double>()));
  EXPECT_NEAR(c.twistRadius, 0.5 * 0.5 * inPlane, 1e-5) << "a segment's mean distance from its middle: a quarter";
  for (int i = 0; i < 4; ++i) EXPECT_GT(c.normalMass[i], 0.0f) << "point " << i << " keeps its normal row";
}

}  // namespace
}  // namespace haif
