// Known-answer tests: capsule against capsule and box.
#include "collision_test_util.h"

namespace haif {
namespace {

using test::axisAngle;
using test::collideBoth;
using test::expectAll;
using test::expectVecNear;
using test::findPoint;
using test::xf;

const Quat kAlongX = axisAngle(Vec3::UnitZ(), kPi / 2);  // capsule axis from y to x

TEST(CapsuleCapsule, CrossedGivesOnePoint) {
  const Shape cap = Shape::capsule(0.5f, 1.0f);
  Manifold m;
  ASSERT_EQ(collideBoth(cap, xf(Vec3::Zero(), kAlongX), cap, xf(Vec3(0.3f, 0.9f, 0.2f), axisAngle(Vec3::UnitX(), kPi / 2)),
                        0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  expectVecNear(m.points[0].position, Vec3(0.3f, 0.45f, 0.0f), 1e-5f);
}

TEST(CapsuleCapsule, ParallelGivesTwoPoints) {
  const Shape cap = Shape::capsule(0.5f, 1.0f);
  Manifold m;
  ASSERT_EQ(collideBoth(cap, xf(Vec3::Zero(), kAlongX), cap, xf(Vec3(0.5f, 0.95f, 0), kAlongX), 0.0f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.05f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(-0.5f, 0.475f, 0), 1e-4f), 0);
  EXPECT_GE(findPoint(m, Vec3(1.0f, 0.475f, 0), 1e-4f), 0);
}

TEST(CapsuleCapsule, EndToEndAndSeparated) {
  const Shape cap = Shape::capsule(0.25f, 0.5f);
  Manifold m;
  ASSERT_EQ(collide(cap, xf(Vec3::Zero()), cap, xf(Vec3(0, 1.45f, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  EXPECT_EQ(collide(cap, xf(Vec3::Zero()), cap, xf(Vec3(0.7f, 0, 0)), 0.1f, m), 0);
  ASSERT_EQ(collide(cap, xf(Vec3::Zero()), cap, xf(Vec3(0.55f, 0.2f, 0)), 0.1f, m), 2);
  expectAll(m, Vec3::UnitX(), -0.05f, 1e-5f);
}

TEST(CapsuleBox, LyingOnBoxGivesTwoPoints) {
  const Shape box = Shape::box(Vec3(2, 0.5f, 2));
  const Shape cap = Shape::capsule(0.25f, 0.75f);
  Manifold m;
  ASSERT_EQ(collideBoth(box, xf(Vec3::Zero()), cap, xf(Vec3(0.5f, 0.73f, 1.0f), kAlongX), 0.0f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.02f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(-0.25f, 0.49f, 1.0f), 1e-5f), 0);
  EXPECT_GE(findPoint(m, Vec3(1.25f, 0.49f, 1.0f), 1e-5f), 0);
  // Speculative: lying 0.05 above with margin 0.1.
  ASSERT_EQ(collide(cap, xf(Vec3(0.5f, 0.80f, 1.0f), kAlongX), box, xf(Vec3::Zero()), 0.1f, m), 2);
  expectAll(m, -Vec3::UnitY(), -0.05f, 1e-5f);
}

TEST(CapsuleBox, TiltedOverAFaceGetsAPointAtEachEndWithinTheMargin) {
  // A capsule (r 0.124, core 0.39 m) tilted 11 degrees, its low end 0.03 m into the ground and the
  // high end within the margin above it: both ends are points, each at its own depth, or the high
  // end swings into the ground unseen (0.27 m in a pour, where only a level capsule got two).
  const Shape ground = Shape::box(Vec3(50, 1, 50));
  const Shape cap = Shape::capsule(0.124f, 0.195f);
  const float tilt = 0.2f, r = 0.124f, hh = 0.195f;
  const Quat q = axisAngle(Vec3::UnitZ(), tilt) * kAlongX;  // axis along x, raised at +x
  const float lowEnd = -0.03f, rise = 2.0f * hh * std::sin(tilt);
  const Vec3 centre(0.3f, 1.0f + lowEnd + r + 0.5f * rise, 0.2f);  // ground top at y = 1
  Manifold m;
  ASSERT_EQ(collideBoth(ground, xf(Vec3::Zero()), cap, xf(centre, q), 0.1f, m), 2);
  for (int i = 0; i < 2; ++i) expectVecNear(m.points[i].normal, Vec3::UnitY(), 1e-5f);  // the face's
  float lo = 1e30f, hi = -1e30f;
  for (int i = 0; i < 2; ++i) {
    lo = std::min(lo, m.points[i].depth);
    hi = std::max(hi, m.points[i].depth);
  }
  EXPECT_NEAR(hi, -lowEnd, 1e-4f);
  EXPECT_NEAR(lo, -lowEnd - rise, 1e-4f);
  // Tilted so the high end is beyond the margin: only the low end.
  ASSERT_EQ(collide(ground, xf(Vec3::Zero()), cap, xf(centre, q), rise - 0.035f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -lowEnd, 1e-4f);
}

TEST(CapsuleBox, OverhangingTheEdgeClipsToTheFace) {
  const Shape box = Shape::box(Vec3(1, 0.5f, 1));
  const Shape cap = Shape::capsule(0.25f, 1.0f);
  Manifold m;
  ASSERT_EQ(collide(box, xf(Vec3::Zero()), cap, xf(Vec3(1.5f, 0.74f, 0), kAlongX), 0.0f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.01f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(0.5f, 0.495f, 0), 1e-5f), 0);
  EXPECT_GE(findPoint(m, Vec3(1.0f, 0.495f, 0), 1e-5f), 0);
}

TEST(CapsuleBox, UprightOnCornerRegion) {
  // Upright capsule beside the box's +x,+z vertical edge: one point, normal from the edge outwards.
  const Shape box = Shape::box(Vec3(0.5f, 0.5f, 0.5f));
  const Shape cap = Shape::capsule(0.3f, 0.5f);
  const float d = 0.25f / std::sqrt(2.0f);
  Manifold m;
  ASSERT_EQ(collide(box, xf(Vec3::Zero()), cap, xf(Vec3(0.5f + d, 0.2f, 0.5f + d)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3(1, 0, 1).normalized(), 1e-5f);
}

TEST(CapsuleBox, DeepPenetrationUsesCheapestExit) {
  // Core segment passes through the box top: exit upwards.
  const Shape box = Shape::box(Vec3(1, 0.5f, 1));
  const Shape cap = Shape::capsule(0.2f, 0.5f);
  Manifold m;
  ASSERT_GE(collide(box, xf(Vec3::Zero()), cap, xf(Vec3(0.1f, 0.7f, 0.0f)), 0.0f, m), 1);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  // Lower end at y = 0.2: 0.3 below the face plus the radius.
  EXPECT_NEAR(m.points[0].depth, 0.5f, 1e-5f);
}

// While the core stays outside the box, the depth is the radius less the core's distance to the box,
// whatever the pose: a capsule standing by a side face with its lower end past the face's edge got
// the face's points at the clipped segment's heights and no more, 0.089 m where it was 0.207 m deep
// (and a 1 mm move that turned the closest feature from the edge to the face dropped the depth of a
// capsule in a pile from 1.7 cm to 0.4 cm). Random poses about a box's corner, the exact distance
// by ternary search (a point's distance to a box is convex along a segment).
TEST(CapsuleBox, TheDeepestPointIsRadiusLessDistanceAtEveryShallowPose) {
  const Vec3 half(1.0f, 0.5f, 1.0f);
  const Shape box = Shape::box(half);
  auto distance = [&](const Vec3& p) { return (p - p.cwiseMax(-half).cwiseMin(half)).norm(); };
  uint32_t seed = 12345u;
  auto uniform = [&] {  // in [-1, 1)
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 23) - 1.0f;
  };
  int shallow = 0;
  float worst = 0.0f;
  for (int t = 0; t < 20000; ++t) {
    const float r = 0.1f + 0.2f * std::abs(uniform()), hh = 0.1f + 0.4f * std::abs(uniform());
    const Quat q = axisAngle(Vec3::UnitY(), 3.2f * uniform()) * axisAngle(Vec3::UnitZ(), 1.6f * uniform()) * kAlongX;
    const Vec3 centre(1.0f + 0.8f * uniform(), 0.5f + 0.8f * uniform(), 1.0f + 0.8f * uniform());
    const Vec3 e0 = centre + q * Vec3(0, hh, 0), e1 = centre - q * Vec3(0, hh, 0);
    float lo = 0.0f, hi = 1.0f;
    for (int k = 0; k < 60; ++k) {
      const float m1 = lo + (hi - lo) / 3.0f, m2 = hi - (hi - lo) / 3.0f;
      if (distance(e0 + m1 * (e1 - e0)) < distance(e0 + m2 * (e1 - e0))) hi = m2;
      else lo = m1;
    }
    const float gap = distance(e0 + 0.5f * (lo + hi) * (e1 - e0));
    if (gap < 1e-3f || gap > r - 1e-3f) continue;  // the core touches the box, or no overlap
    ++shallow;
    Manifold m;
    ASSERT_GT(collide(box, xf(Vec3::Zero()), Shape::capsule(r, hh), xf(centre, q), 0.0f, m), 0) << "pose " << t;
    worst = std::max(worst, std::abs(m.deepest() - (r - gap)));
  }
  EXPECT_GT(shallow, 2000);  // of the 20000 poses, those the test can say something about
  EXPECT_LT(worst, 2e-4f);
}

TEST(CapsuleBox, RotatedBoxKnownAnswer) {
  const Quat q = axisAngle(Vec3(0.3f, -1.0f, 0.4f), 0.8f);
  const Vec3 o(-2, 3, 1);
  const Shape box = Shape::box(Vec3(2, 0.5f, 2));
  const Shape cap = Shape::capsule(0.25f, 0.75f);
  Manifold m;
  ASSERT_EQ(collide(box, xf(o, q), cap, xf(o + q * Vec3(0.5f, 0.73f, 1.0f), q * kAlongX), 0.0f, m), 2);
  expectAll(m, q * Vec3::UnitY(), 0.02f, 1e-4f);
  EXPECT_GE(findPoint(m, o + q * Vec3(-0.25f, 0.49f, 1.0f), 1e-4f), 0);
}

}  // namespace
}  // namespace haif
