// Known-answer tests: sphere against sphere, box, capsule and plane.
#include "collision_test_util.h"

namespace haif {
namespace {

using test::axisAngle;
using test::collideBoth;
using test::expectVecNear;
using test::xf;

TEST(SphereSphere, Penetrating) {
  Manifold m;
  ASSERT_EQ(collideBoth(Shape::sphere(1.0f), xf(Vec3(0, 0, 0)), Shape::sphere(0.5f), xf(Vec3(1.4f, 0, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitX(), 1e-6f);
  expectVecNear(m.points[0].position, Vec3(0.95f, 0, 0), 1e-5f);
}

TEST(SphereSphere, SeparatedAndSpeculative) {
  Manifold m;
  EXPECT_EQ(collide(Shape::sphere(1.0f), xf(Vec3(0, 0, 0)), Shape::sphere(1.0f), xf(Vec3(0, 2.3f, 0)), 0.2f, m), 0);
  ASSERT_EQ(collide(Shape::sphere(1.0f), xf(Vec3(0, 0, 0)), Shape::sphere(1.0f), xf(Vec3(0, 2.1f, 0)), 0.2f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.1f, 1e-5f);
  expectVecNear(m.points[0].position, Vec3(0, 1.05f, 0), 1e-5f);
}

TEST(SphereSphere, CoincidentCentresStillGiveUnitNormal) {
  Manifold m;
  ASSERT_EQ(collide(Shape::sphere(1.0f), xf(Vec3(1, 1, 1)), Shape::sphere(1.0f), xf(Vec3(1, 1, 1)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].normal.norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(m.points[0].depth, 2.0f, 1e-6f);
}

TEST(SpherePlane, KnownAnswerFromBrief) {
  // Sphere r = 1 at y = 0.9 on the plane y = 0: depth 0.1.
  const Shape plane = Shape::plane(Vec3::UnitY(), 0.0f);
  Manifold m;
  ASSERT_EQ(collide(plane, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(2, 0.9f, -1)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-6f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-6f);  // from plane (a) to sphere (b)
  expectVecNear(m.points[0].position, Vec3(2, -0.05f, -1), 1e-6f);
  ASSERT_EQ(collide(Shape::sphere(1.0f), xf(Vec3(2, 0.9f, -1)), plane, xf(Vec3::Zero()), 0.0f, m), 1);
  expectVecNear(m.points[0].normal, -Vec3::UnitY(), 1e-6f);  // from sphere (a) to plane (b)
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-6f);
}

TEST(SpherePlane, TransformedPlaneAndMargin) {
  // Plane body rotated so its local +y normal points along +x, offset 1 in its frame, body at x = 2:
  // world plane x = 3.
  const Shape plane = Shape::plane(Vec3::UnitY(), 1.0f);
  const Transform tp = xf(Vec3(2, 0, 0), axisAngle(Vec3::UnitZ(), -kPi / 2));
  Manifold m;
  ASSERT_EQ(collide(plane, tp, Shape::sphere(0.5f), xf(Vec3(3.55f, 4, 0)), 0.1f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitX(), 1e-5f);
  EXPECT_EQ(collide(plane, tp, Shape::sphere(0.5f), xf(Vec3(3.65f, 4, 0)), 0.1f, m), 0);
}

TEST(SphereBox, FaceEdgeCorner) {
  const Shape box = Shape::box(Vec3(1, 0.5f, 2));
  const Shape s = Shape::sphere(0.5f);
  Manifold m;
  // Face (+y).
  ASSERT_EQ(collideBoth(box, xf(Vec3::Zero()), s, xf(Vec3(0.3f, 0.9f, 1.0f)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  expectVecNear(m.points[0].position, Vec3(0.3f, 0.45f, 1.0f), 1e-5f);
  // Edge (+x, +y).
  const float d = 0.4f / std::sqrt(2.0f);
  ASSERT_EQ(collideBoth(box, xf(Vec3::Zero()), s, xf(Vec3(1 + d, 0.5f + d, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3(1, 1, 0).normalized(), 1e-5f);
  // Corner, separated within margin.
  const Vec3 dir = Vec3(1, 1, 1).normalized();
  ASSERT_EQ(collide(box, xf(Vec3::Zero()), s, xf(Vec3(1, 0.5f, 2) + 0.55f * dir), 0.1f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, dir, 1e-5f);
  EXPECT_EQ(collide(box, xf(Vec3::Zero()), s, xf(Vec3(1, 0.5f, 2) + 0.65f * dir), 0.1f, m), 0);
}

TEST(SphereBox, CentreInsideLeavesThroughNearestFace) {
  const Shape box = Shape::box(Vec3(1, 1, 1));
  Manifold m;
  ASSERT_EQ(collide(Shape::sphere(0.25f), xf(Vec3(0.2f, 0.1f, -0.8f)), box, xf(Vec3::Zero()), 0.0f, m), 1);
  // Nearest face is -z (0.2 away): sphere (a) to box (b) normal is +z, depth 0.2 + 0.25.
  expectVecNear(m.points[0].normal, Vec3::UnitZ(), 1e-5f);
  EXPECT_NEAR(m.points[0].depth, 0.45f, 1e-5f);
}

TEST(SphereBox, RotatedBox) {
  const Shape box = Shape::box(Vec3(0.5f, 0.5f, 0.5f));
  const Quat q = axisAngle(Vec3::UnitZ(), kPi / 4);  // edge up
  const float top = 0.5f * std::sqrt(2.0f);
  Manifold m;
  ASSERT_EQ(collide(box, xf(Vec3::Zero(), q), Shape::sphere(0.5f), xf(Vec3(0, top + 0.45f, 0.2f)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
}

TEST(SphereCapsule, SideAndEnd) {
  const Shape cap = Shape::capsule(0.5f, 1.0f);
  Manifold m;
  ASSERT_EQ(collideBoth(Shape::sphere(0.5f), xf(Vec3(0.9f, 0.3f, 0)), cap, xf(Vec3::Zero()), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, -Vec3::UnitX(), 1e-5f);
  expectVecNear(m.points[0].position, Vec3(0.45f, 0.3f, 0), 1e-5f);
  // Beyond the top cap.
  ASSERT_EQ(collide(cap, xf(Vec3::Zero()), Shape::sphere(0.5f), xf(Vec3(0, 2.05f, 0)), 0.1f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  // Rotated capsule lying along x.
  ASSERT_EQ(collide(cap, xf(Vec3::Zero(), axisAngle(Vec3::UnitZ(), kPi / 2)), Shape::sphere(0.5f),
                    xf(Vec3(0.7f, 0.95f, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  EXPECT_EQ(collide(cap, xf(Vec3::Zero()), Shape::sphere(0.5f), xf(Vec3(1.2f, 0, 0)), 0.1f, m), 0);
}

}  // namespace
}  // namespace haif
