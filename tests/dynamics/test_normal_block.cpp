// The normal rows of a manifold are solved as one block: exactly (one product with the block's
// pseudo-inverse) while every point stays loaded, by projected passes otherwise.
#include "dynamics/contact_solver.h"
#include "tilted_patch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace haif {
namespace {

// A 1 m unit-mass cube (body 1) resting on a static ground (body 0), touching at its four bottom
// corners, with the given velocities; friction off so only the normal block acts.
struct BoxOnGround {
  BodyStore bodies;
  Contact contact;
  BoxOnGround(const Vec3& v, const Vec3& w, int points = 4) {
    bodies.add(BodyKind::Static, Transform{}, 0.0f, Mat3::Zero());
    Transform t;
    t.p = Vec3(0.0f, 0.5f, 0.0f);
    bodies.add(BodyKind::Dynamic, t, 1.0f, Mat3::Identity() * (1.0f / 6.0f));
    bodies.v[1] = v;
    bodies.w[1] = w;
    contact.a = 0;
    contact.b = 1;
    contact.friction = 0.0f;
    const float corners[4][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
    contact.manifold.count = points;
    for (int i = 0; i < points; ++i) {
      ContactPoint& p = contact.manifold.points[i];
      p.position = Vec3(corners[i][0], 0.0f, corners[i][1]);
      p.normal = Vec3::UnitY();
      p.depth = 0.0f;
      p.id = uint32_t(i);
    }
  }
  // Relative normal velocity of point i plus its bias: 0 when the row is satisfied.
  float rowError(const ContactConstraint& c, int i) const {
    return rowVelocity(c, i, bodies.v[0], bodies.w[0], bodies.v[1], bodies.w[1]) + c.bias[i];
  }
};

SolverParams params() {
  SolverParams sp;
  sp.warmStart = false;
  return sp;
}

TEST(NormalBlock, SharedNormalManifoldGetsAnExactBlock) {
  BoxOnGround s(Vec3(0.0f, -1.0f, 0.0f), Vec3::Zero());
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  EXPECT_TRUE(c.blockExact);
}

TEST(NormalBlock, OneSweepStopsATiltedImpactExactly) {
  // Falling and rotating about two axes: the four points need four different impulses. Passes
  // alone leave a residual after one sweep; the exact block leaves none.
  BoxOnGround s(Vec3(0.1f, -2.0f, 0.0f), Vec3(0.7f, 0.0f, -0.4f));
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact);
  solveIteration(s.bodies, &c, 1, 1.0f, true);
  float lo = 1e9f, hi = 0.0f;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(s.rowError(c, i), 0.0f, 1e-5f) << "point " << i;
    lo = std::min(lo, c.normalImpulse[i]);
    hi = std::max(hi, c.normalImpulse[i]);
  }
  EXPECT_GT(lo, 0.0f);
  EXPECT_GT(hi - lo, 0.05f);  // the split is genuinely uneven: the rotation was taken out too
  // The box's fall and both tilting rotations stop.
  EXPECT_NEAR(s.bodies.v[1].y(), 0.0f, 1e-5f);
  EXPECT_NEAR(s.bodies.w[1].x(), 0.0f, 1e-5f);
  EXPECT_NEAR(s.bodies.w[1].z(), 0.0f, 1e-5f);
}

TEST(NormalBlock, ExactSplitOfASymmetricLoadIsEven) {
  BoxOnGround s(Vec3(0.0f, -1.0f, 0.0f), Vec3::Zero());
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  solveIteration(s.bodies, &c, 1, 1.0f, true);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c.normalImpulse[i], 0.25f, 1e-6f) << "point " << i;
}

TEST(NormalBlock, LiftingCornerFallsBackToProjectedPasses) {
  // Spinning hard enough that one edge lifts: the unconstrained block would pull on the lifting
  // points (λ < 0), so the passes solve it with those points at zero, never negative.
  BoxOnGround s(Vec3(0.0f, -0.1f, 0.0f), Vec3(0.0f, 0.0f, 3.0f));
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  solveIteration(s.bodies, &c, 1, 1.0f, true);
  int zero = 0;
  for (int i = 0; i < 4; ++i) {
    EXPECT_GE(c.normalImpulse[i], 0.0f);
    if (c.normalImpulse[i] == 0.0f) {
      ++zero;
      EXPECT_GE(s.rowError(c, i), -1e-5f) << "a point at zero impulse must not be approaching";
    }
  }
  EXPECT_EQ(zero, 2);
}

TEST(NormalBlock, CollinearPointsUseALineBlock) {
  // Two points on an edge: rank 2, still exact.
  BoxOnGround s(Vec3(0.0f, -1.0f, 0.0f), Vec3(0.5f, 0.0f, 0.5f), 2);
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact);
  solveIteration(s.bodies, &c, 1, 1.0f, true);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(s.rowError(c, i), 0.0f, 1e-5f) << "point " << i;
}

TEST(NormalBlock, DifferentNormalsAreLeftToThePasses) {
  BoxOnGround s(Vec3(0.0f, -1.0f, 0.0f), Vec3::Zero());
  s.contact.manifold.points[2].normal = Vec3(0.0f, 0.8f, 0.6f);
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  EXPECT_FALSE(c.blockExact);
}

TEST(NormalBlock, PlaneBlockIsThePseudoInverseOfTheCouplingOnItsRange) {
  // Two dynamic bodies with unequal, turned inertias, a tilted contact plane and an irregular
  // quadrilateral of points at different depths: G must satisfy K G K = K and G K G = G, and
  // solve any loaded right-hand side exactly (K G b = b for b in K's range).
  const test::TiltedPatch s;
  ContactConstraint c;
  prepareContact(s.bodies, s.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact);
  float coupling[4][4];
  normalCoupling(c, coupling);
  Eigen::Matrix4d K, G;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      K(i, j) = coupling[i][j];
      G(i, j) = c.blockInverse[i][j];
    }
  EXPECT_LT((K * G * K - K).norm(), 1e-4 * K.norm());
  EXPECT_LT((G * K * G - G).norm(), 1e-4 * G.norm());
  const Eigen::Vector4d b = K * Eigen::Vector4d(1.0, -2.0, 0.5, 3.0);
  EXPECT_LT((K * (G * b) - b).norm(), 1e-4 * b.norm());
}

// Two 250 kg bricks (1 x 0.5 x 0.5 m) of a resting bed, diagonal neighbours in adjacent layers whose
// faces 2 cm apart overlap in a sliver 0.3 x 0.1 mm at a corner: the narrow phase's four points of
// that speculative contact, as a minute run of a 20 t ball on a three-layer bed made them (step 629).
struct BrickSliver {
  BodyStore bodies;
  Contact contact;
  // A rectangle `across` wide in x and `width` high in y (a quarter of `across` unless given).
  explicit BrickSliver(float across, float width = -1.0f) {
    if (width < 0.0f) width = 0.25f * across;
    const float m = 250.0f;
    const Vec3 h(0.5f, 0.25f, 0.25f);
    const Mat3 inertia = Vec3(m / 3.0f * (h.y() * h.y() + h.z() * h.z()), m / 3.0f * (h.x() * h.x() + h.z() * h.z()),
                              m / 3.0f * (h.x() * h.x() + h.y() * h.y()))
                             .asDiagonal();
    Transform a, b;
    a.p = Vec3(-2.06f, 0.74995f, 0.78f);
    b.p = Vec3(-1.06024826f, 1.24902797f, 0.260529935f);
    b.q = Quat(0.999999702f, 2.65423641e-05f, -0.000324512104f, -0.000722464581f);
    bodies.add(BodyKind::Dynamic, a, m, inertia);
    bodies.add(BodyKind::Dynamic, b, m, inertia);
    contact.a = 0;
    contact.b = 1;
    // At the corner of the overlap.
    const Vec3 corner(-1.56055f, 0.99989f, 0.5201f);
    const Vec3 offsets[4] = {{0.0f, 0.0f, 0.0f}, {0.0f, -width, 0.0f}, {across, -width, 0.0f}, {across, 0.0f, 0.0f}};
    contact.manifold.count = 4;
    for (int i = 0; i < 4; ++i) {
      ContactPoint& p = contact.manifold.points[i];
      p.position = corner + offsets[i];
      p.normal = -Vec3::UnitZ();
      p.depth = -0.0198f;
      p.id = uint32_t(i);
    }
  }
};

// The block's inverse reads how the coupling K varies across the points, by ~|I⁻¹| times their
// spread; float holds K to ~1e-7 of its size. Across 0.33 mm on 1 m bricks that variation is
// rounding, and the inverse came out at 7.6e12 (a row's mass is 25): velocity rounding of 1e-7 m/s
// made impulses of 1e6 N s, and whenever they happened to be all pushing they were kept: the
// bed's 119 bricks, at rest, left at 24 m/s in one step. Such a sliver is one place; a patch of
// a few centimetres on the same bricks keeps its exact block.
TEST(NormalBlock, APatchTooSmallForFloatToReadIsOnePlace) {
  BrickSliver sliver(0.00033f);
  ContactConstraint c;
  prepareContact(sliver.bodies, sliver.contact, 0, params(), c);
  EXPECT_FALSE(c.blockExact) << "a 0.33 mm patch on 1 m bricks solved as a block";
  BrickSliver patch(0.03f);
  prepareContact(patch.bodies, patch.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact) << "a 3 cm patch lost its exact block";
  float largest = 0.0f;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) largest = std::max(largest, std::fabs(c.blockInverse[i][j]));
  EXPECT_LT(largest, 1e5f) << "the 3 cm patch's inverse reads rounding too";
}

// The largest gain of a block over its rows' own masses: max G_ii K_ii (1 for a row alone).
float blockGain(const ContactConstraint& c) {
  float K[kMaxManifoldPoints][kMaxManifoldPoints];
  normalCoupling(c, K);
  float gain = 0.0f;
  for (int i = 0; i < c.count; ++i) gain = std::max(gain, c.blockInverse[i][i] * K[i][i]);
  return gain;
}

// The same rule across a patch as over it: a patch 6 mm long and 0.1 mm wide on these bricks (the
// points of a 3-layer bed's speculative contacts) was a patch of rank 3, its turn about the line's own
// axis read from rounding across 0.1 mm: gains of 1e5-1e9 over a row's mass, about four in a
// thousand blocks of that bed. Its width is no direction; it is a line, whose block stays well within float.
TEST(NormalBlock, ASliverAlongALineIsALine) {
  BrickSliver line(0.006f, 0.0001f);
  ContactConstraint c;
  prepareContact(line.bodies, line.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact) << "a 6 mm line on 1 m bricks lost its block";
  EXPECT_LT(blockGain(c), 1e5f) << "the line's width was read as a direction";
  // A patch 6 mm by 3 mm keeps its third direction (and a gain float can read).
  BrickSliver patch(0.006f, 0.003f);
  prepareContact(patch.bodies, patch.contact, 0, params(), c);
  ASSERT_TRUE(c.blockExact);
  EXPECT_LT(blockGain(c), 1e5f);
}

// spreadRank reads each principal direction, whatever the axes the points are given in.
TEST(NormalBlock, APatchsRankDoesNotDependOnItsAxes) {
  const double single = 1e-6;
  for (const double angle : {0.0, 0.3, 0.7854, 1.2, 2.5}) {
    const double c = std::cos(angle), s = std::sin(angle);
    // Points at (±a, ±b) in the patch's own axes, turned by `angle`.
    auto rank = [&](double a, double b, double* along) {
      double css = 0.0, ctt = 0.0, cst = 0.0;
      for (const double u : {-a, a})
        for (const double v : {-b, b}) {
          const double x = c * u - s * v, y = s * u + c * v;
          css += x * x, ctt += y * y, cst += x * y;
        }
      return spreadRank(css, ctt, cst, 4, single, along);
    };
    double along[2];
    EXPECT_EQ(rank(0.1, 0.05, along), 3) << angle;
    EXPECT_EQ(rank(0.1, 0.0001, along), 2) << angle;  // 0.2 mm wide: under the single place's spread
    EXPECT_NEAR(std::fabs(along[0] * c + along[1] * s), 1.0, 1e-9) << angle;  // along the line
    EXPECT_EQ(rank(0.0002, 0.0002, along), 1) << angle;
  }
}

}  // namespace
}  // namespace haif
