// Known-answer tests of the box-box narrow phase.
#include "collision_test_util.h"

#include <random>
#include <set>

namespace haif {
namespace {

using test::axisAngle;
using test::collideBoth;
using test::expectAll;
using test::findPoint;
using test::xf;

const Shape kUnit = Shape::box(Vec3::Constant(0.5f));

TEST(BoxBox, RestingGivesFourCorners) {
  Manifold m;
  ASSERT_EQ(collideBoth(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 1, 0)), 0.0f, m), 4);
  expectAll(m, Vec3::UnitY(), 0.0f);
  for (float x : {-0.5f, 0.5f})
    for (float z : {-0.5f, 0.5f}) EXPECT_GE(findPoint(m, Vec3(x, 0.5f, z), 1e-5f), 0) << x << " " << z;
}

TEST(BoxBox, PenetratingDepthAndMidpoints) {
  Manifold m;
  ASSERT_EQ(collideBoth(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 0.9f, 0)), 0.0f, m), 4);
  expectAll(m, Vec3::UnitY(), 0.1f);
  // Midway between the two surfaces (y = 0.5 and y = 0.4).
  for (float x : {-0.5f, 0.5f})
    for (float z : {-0.5f, 0.5f}) EXPECT_GE(findPoint(m, Vec3(x, 0.45f, z), 1e-5f), 0);
}

TEST(BoxBox, BelowGivesDownwardNormal) {
  Manifold m;
  ASSERT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0.2f, -0.95f, 0)), 0.0f, m), 4);
  expectAll(m, -Vec3::UnitY(), 0.05f);
  EXPECT_GE(findPoint(m, Vec3(0.5f, -0.475f, 0.5f), 1e-5f), 0);   // A's corner, clipped
  EXPECT_GE(findPoint(m, Vec3(-0.3f, -0.475f, -0.5f), 1e-5f), 0); // B's corner
}

TEST(BoxBox, SmallOnLargeUsesSmallCorners) {
  const Shape ground = Shape::box(Vec3(10, 1, 10));
  Manifold m;
  ASSERT_EQ(collideBoth(ground, xf(Vec3(0, -1, 0)), kUnit, xf(Vec3(3, 0.49f, -2)), 0.0f, m), 4);
  expectAll(m, Vec3::UnitY(), 0.01f);
  for (float x : {2.5f, 3.5f})
    for (float z : {-2.5f, -1.5f}) EXPECT_GE(findPoint(m, Vec3(x, -0.005f, z), 1e-4f), 0);
}

TEST(BoxBox, SeparatedBeyondMarginGivesNothing) {
  Manifold m;
  EXPECT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 1.2f, 0)), 0.1f, m), 0);
  EXPECT_EQ(m.count, 0);
  EXPECT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(1.5f, 0.0f, 1.5f), axisAngle(Vec3(1, 2, 3), 0.7f)), 0.1f, m), 0);
}

TEST(BoxBox, SpeculativeWithinMargin) {
  Manifold m;
  ASSERT_EQ(collideBoth(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 1.05f, 0)), 0.1f, m), 4);
  expectAll(m, Vec3::UnitY(), -0.05f);
  EXPECT_GE(findPoint(m, Vec3(0.5f, 0.525f, 0.5f), 1e-5f), 0);
  EXPECT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 1.05f, 0)), 0.04f, m), 0);
}

TEST(BoxBox, RotatedAboutNormalClipsToOctagon) {
  // B turned 45 degrees about y: clipping gives 8 points, reduced to 4 of them.
  Manifold m;
  ASSERT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 0.98f, 0), axisAngle(Vec3::UnitY(), kPi / 4)), 0.0f, m),
            4);
  expectAll(m, Vec3::UnitY(), 0.02f);
  for (int i = 0; i < m.count; ++i) {
    const Vec3 p = m.points[i].position;
    EXPECT_NEAR(p.y(), 0.49f, 1e-5f);
    EXPECT_LE(std::fabs(p.x()), 0.5f + 1e-5f);
    EXPECT_LE(std::fabs(p.z()), 0.5f + 1e-5f);
    EXPECT_LE(std::fabs(p.x()) + std::fabs(p.z()), 0.5f * std::sqrt(2.0f) + 1e-4f);  // inside B's square
  }
}

TEST(BoxBox, TiltedCornerDown) {
  // B rotated so one corner points down: single deepest vertex on A's top face.
  const Quat q = axisAngle(Vec3(1, 0, 0), std::atan(std::sqrt(0.5f))) * axisAngle(Vec3::UnitY(), kPi / 4);
  const Quat qc = Quat::FromTwoVectors(q * Vec3(1, 1, 1).normalized(), Vec3::UnitY());
  const float h = 0.5f * std::sqrt(3.0f);  // centre height of a cube standing on a corner
  Manifold m;
  ASSERT_GE(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0, 0.5f + h - 0.02f, 0), qc * q), 0.0f, m), 1);
  EXPECT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, 0.02f, 1e-4f);
  test::expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-4f);
  test::expectVecNear(m.points[0].position, Vec3(0, 0.49f, 0), 1e-3f);
}

TEST(BoxBox, ReferenceFaceOnSecondBox) {
  // A is tilted corner-down over the large B: B's top face is the reference, the normal still runs
  // from A to B (downwards) and the single point sits at A's corner.
  const Shape ground = Shape::box(Vec3(5, 0.5f, 5));
  const Quat q = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitY());
  const float h = 0.5f * std::sqrt(3.0f);
  Manifold m;
  ASSERT_EQ(collide(kUnit, xf(Vec3(1, 0.5f + h - 0.03f, 2), q), ground, xf(Vec3::Zero()), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.03f, 1e-4f);
  test::expectVecNear(m.points[0].normal, -Vec3::UnitY(), 1e-4f);
  test::expectVecNear(m.points[0].position, Vec3(1, 0.485f, 2), 1e-3f);
  EXPECT_NE(m.points[0].id & 0x80000000u, 0u);  // reference face belongs to B
}

TEST(BoxBox, EdgeEdgeContact) {
  // A rotated 45 deg about z (edge up along z), B rotated 45 deg about x (edge down along x).
  const float r2 = std::sqrt(2.0f);
  const Transform ta = xf(Vec3(0, 0, 0), axisAngle(Vec3::UnitZ(), kPi / 4));
  const Transform tb = xf(Vec3(0, r2 - 0.1f, 0), axisAngle(Vec3::UnitX(), kPi / 4));
  Manifold m;
  ASSERT_EQ(collideBoth(kUnit, ta, kUnit, tb, 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-4f);
  test::expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-4f);
  test::expectVecNear(m.points[0].position, Vec3(0, 0.5f * r2 - 0.05f, 0), 1e-4f);
  EXPECT_NE(m.points[0].id & 0x40000000u, 0u);  // edge feature
  // Tiny perturbation keeps the id.
  Manifold m2;
  ASSERT_EQ(collide(kUnit, ta, kUnit, xf(tb.p + Vec3(1e-3f, -1e-3f, 2e-3f), tb.q * axisAngle(Vec3(0, 1, 1), 1e-3f)), 0.0f, m2), 1);
  EXPECT_EQ(m2.points[0].id, m.points[0].id);
  // Separated edges within the margin: negative depth.
  ASSERT_EQ(collide(kUnit, ta, kUnit, xf(Vec3(0, r2 + 0.05f, 0), tb.q), 0.1f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-4f);
}

TEST(BoxBox, FeatureIdsStableUnderPerturbation) {
  Manifold m1, m2;
  ASSERT_EQ(collide(kUnit, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(0.1f, 0.99f, 0.05f)), 0.01f, m1), 4);
  const Transform tb2 = xf(Vec3(0.1003f, 0.9898f, 0.0502f), axisAngle(Vec3(0.3f, 1.0f, -0.2f), 0.002f));
  const Transform ta2 = xf(Vec3(0.0001f, 0.0f, -0.0002f), axisAngle(Vec3(1.0f, 0.0f, 0.5f), 0.001f));
  ASSERT_EQ(collide(kUnit, ta2, kUnit, tb2, 0.01f, m2), 4);
  std::set<uint32_t> a, b;
  for (int i = 0; i < 4; ++i) { a.insert(m1.points[i].id); b.insert(m2.points[i].id); }
  EXPECT_EQ(a.size(), 4u);  // ids are distinct within a manifold
  EXPECT_EQ(a, b);
  // Same id refers to the same corner.
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (m1.points[i].id == m2.points[j].id) {
        EXPECT_LT((m1.points[i].position - m2.points[j].position).norm(), 0.01f);
      }
}

TEST(BoxBox, RotatedFrameKnownAnswer) {
  // The resting pair rotated and translated as a whole: same answer in the rotated frame.
  const Quat q = axisAngle(Vec3(0.2f, 0.9f, -0.4f), 1.1f);
  const Vec3 o(3, -2, 5);
  Manifold m;
  ASSERT_EQ(collideBoth(kUnit, xf(o, q), kUnit, xf(o + q * Vec3(0.25f, 0.95f, 0), q), 0.0f, m), 4);
  expectAll(m, q * Vec3::UnitY(), 0.05f, 1e-4f);
  for (float x : {-0.25f, 0.5f})
    for (float z : {-0.5f, 0.5f}) EXPECT_GE(findPoint(m, o + q * Vec3(x, 0.475f, z), 1e-4f), 0);
}

TEST(BoxBox, DeepOverlapPicksShallowestAxis) {
  Manifold m;
  const Shape wide = Shape::box(Vec3(2, 0.5f, 2));
  // Overlap along x is 2.5 - 1.6 = 0.9, along y 1.0 - 0.6 = 0.4: y is the axis to push along.
  ASSERT_GE(collide(wide, xf(Vec3(0, 0, 0)), kUnit, xf(Vec3(1.6f, 0.6f, 0)), 0.0f, m), 1);
  expectAll(m, Vec3::UnitY(), 0.4f);
}

TEST(BoxBox, AWiderMarginNeverLosesAnOverlap) {
  // A pair closing fast gets a wide speculative margin, and with it a preference for a face over an
  // edge (axis_preference.h). Where the boxes meet at edges beyond the face, the face clipped to
  // nothing: a box falling at 13 m/s (margin 0.24 m) onto another, 4.3 cm deep at their edges, got
  // no point and sank 0.27 m into it. The case from that pour, then random pairs of pour-sized boxes.
  {
    const Shape a = Shape::box(Vec3(0.195841f, 0.217016f, 0.17999f));
    const Shape b = Shape::box(Vec3(0.189172f, 0.194957f, 0.201427f));
    const Transform xa = xf(Vec3(-1.08417463f, 0.808601677f, -1.90989602f),
                            Quat(0.820176065f, 0.40220052f, 0.235038906f, 0.332118422f).normalized());
    const Transform xb = xf(Vec3(-1.03651607f, 1.34579122f, -1.96732461f),
                            Quat(0.248318419f, -0.150120392f, 0.948880076f, 0.124211587f).normalized());
    for (float margin : {0.0f, 0.1f, 0.25f, 0.5f}) {
      Manifold m;
      ASSERT_GE(collideBoth(a, xa, b, xb, margin, m), 1) << "margin " << margin;
      EXPECT_NEAR(m.deepest(), 0.043f, 2e-3f) << "margin " << margin;
    }
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> size(0.1f, 0.3f), unit(-1.0f, 1.0f);
  auto quat = [&] { return Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized(); };
  int overlaps = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Shape a = Shape::box(Vec3(size(rng), size(rng), size(rng)));
    const Shape b = Shape::box(Vec3(size(rng), size(rng), size(rng)));
    const Transform xa = xf(Vec3::Zero(), quat());
    const Transform xb = xf(0.55f * Vec3(unit(rng), unit(rng), unit(rng)), quat());
    bool overlapping = false;
    ASSERT_TRUE(test::overlapKeptAtWideMargins(
        [&](float margin, Manifold& m) { return collide(a, xa, b, xb, margin, m); }, {0.1f, 0.25f, 0.5f}, overlapping))
        << "trial " << trial;
    overlaps += overlapping;
  }
  EXPECT_GT(overlaps, 2000);  // the poses do overlap often enough to mean something
}

}  // namespace
}  // namespace haif
