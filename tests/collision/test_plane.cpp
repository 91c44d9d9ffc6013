// Known-answer tests: box, capsule, hull against a static plane; static-static pairs give nothing.
#include "collision/convex_hull.h"
#include "collision/triangle_mesh.h"
#include "collision_test_util.h"

namespace haif {
namespace {

using test::axisAngle;
using test::expectAll;
using test::expectVecNear;
using test::findPoint;
using test::xf;

const Shape kGround = Shape::plane(Vec3::UnitY(), 0.0f);

TEST(PlaneBox, RestingFourCorners) {
  Manifold m;
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), Shape::box(Vec3(0.5f, 0.5f, 0.5f)), xf(Vec3(1, 0.48f, 2)), 0.0f, m), 4);
  expectAll(m, Vec3::UnitY(), 0.02f, 1e-5f);
  for (float x : {0.5f, 1.5f})
    for (float z : {1.5f, 2.5f}) EXPECT_GE(findPoint(m, Vec3(x, -0.01f, z), 1e-5f), 0);
  // Reversed order: normal from box down to the plane.
  ASSERT_EQ(collide(Shape::box(Vec3(0.5f, 0.5f, 0.5f)), xf(Vec3(1, 0.48f, 2)), kGround, xf(Vec3::Zero()), 0.0f, m), 4);
  expectAll(m, -Vec3::UnitY(), 0.02f, 1e-5f);
}

TEST(PlaneBox, TiltedBoxOneCornerAndMargin) {
  // Box rotated 30 degrees about z: its lowest edge (two corners) touches; margin picks up nothing else.
  const Quat q = axisAngle(Vec3::UnitZ(), kPi / 6);
  const Shape box = Shape::box(Vec3(0.5f, 0.5f, 0.5f));
  const float low = 0.5f * (std::cos(kPi / 6) + std::sin(kPi / 6));
  Manifold m;
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), box, xf(Vec3(0, low - 0.03f, 0), q), 0.01f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.03f, 1e-5f);
  EXPECT_NE(m.points[0].id, m.points[1].id);
  // Lifted so the edge is 0.05 above the plane: speculative with margin 0.1, nothing with 0.04.
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), box, xf(Vec3(0, low + 0.05f, 0), q), 0.1f, m), 2);
  expectAll(m, Vec3::UnitY(), -0.05f, 1e-5f);
  EXPECT_EQ(collide(kGround, xf(Vec3::Zero()), box, xf(Vec3(0, low + 0.05f, 0), q), 0.04f, m), 0);
}

TEST(PlaneBox, InclinedPlane) {
  // Plane through the origin with normal (1,1,0)/sqrt2; unit box resting on it with matching rotation.
  const Vec3 n = Vec3(1, 1, 0).normalized();
  const Shape plane = Shape::plane(n, 0.0f);
  const Quat q = Quat::FromTwoVectors(Vec3::UnitY(), n);
  Manifold m;
  ASSERT_EQ(collide(plane, xf(Vec3::Zero()), Shape::box(Vec3::Constant(0.5f)), xf(0.45f * n, q), 0.0f, m), 4);
  expectAll(m, n, 0.05f, 1e-5f);
}

// A box (or hull) thinner than the margin has all its corners in reach of the plane: the manifold
// is its four bottom corners, never a top corner above one of them (which is as far across the
// contact but 1.5 cm farther away, and left a Jenga block standing on three points).
TEST(PlaneBox, ThinnerThanTheMarginKeepsItsBottomFace) {
  const Vec3 he(0.0375f, 0.0075f, 0.0125f);
  for (const float yaw : {0.0f, 0.3f, 1.2f}) {
    const Transform at = xf(Vec3(0.2f, he.y(), -0.1f), axisAngle(Vec3::UnitY(), yaw));
    Manifold m;
    ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), Shape::box(he), at, 0.02f, m), 4) << yaw;
    expectAll(m, Vec3::UnitY(), 0.0f, 1e-5f);
    for (float x : {-he.x(), he.x()})
      for (float z : {-he.z(), he.z()}) EXPECT_GE(findPoint(m, at.apply(Vec3(x, -he.y(), z)), 1e-5f), 0) << yaw;
  }
  std::string err;
  std::vector<Vec3> plate;
  for (float y : {-0.005f, 0.005f})
    for (float x : {-0.5f, 0.5f})
      for (float z : {-0.5f, 0.5f}) plate.push_back(Vec3(x, y, z));
  auto hull = buildConvexHull(plate, &err);
  ASSERT_TRUE(hull) << err;
  Manifold m;
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), Shape::convexHull(hull), xf(Vec3(0, 0.004f, 0)), 0.02f, m), 4);
  expectAll(m, Vec3::UnitY(), 0.001f, 1e-5f);
}

TEST(PlaneCapsule, LyingGivesTwoPoints) {
  const Shape cap = Shape::capsule(0.25f, 1.0f);
  Manifold m;
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), cap, xf(Vec3(0, 0.2f, 0), axisAngle(Vec3::UnitZ(), kPi / 2)), 0.0f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.05f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(1, -0.025f, 0), 1e-5f), 0);
  EXPECT_GE(findPoint(m, Vec3(-1, -0.025f, 0), 1e-5f), 0);
  // Standing upright: only the lower end.
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), cap, xf(Vec3(0, 1.2f, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
}

TEST(PlaneHull, TetrahedronOnPlane) {
  std::string err;
  auto hull = buildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)}, &err);
  ASSERT_TRUE(hull) << err;
  // Centroid of this tetrahedron is (0.25, 0.25, 0.25): base at local y = -0.25.
  Manifold m;
  ASSERT_EQ(collide(kGround, xf(Vec3::Zero()), Shape::convexHull(hull), xf(Vec3(0, 0.24f, 0)), 0.0f, m), 3);
  expectAll(m, Vec3::UnitY(), 0.01f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(0.75f, -0.005f, -0.25f), 1e-5f), 0);
}

TEST(StaticPairs, GiveNothing) {
  std::string err;
  auto mesh = buildTriangleMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)}, {0, 2, 1}, &err);
  ASSERT_TRUE(mesh) << err;
  const Shape ms = Shape::triangleMesh(mesh);
  Manifold m;
  m.count = 3;
  EXPECT_EQ(collide(kGround, xf(Vec3::Zero()), kGround, xf(Vec3::Zero()), 1.0f, m), 0);
  EXPECT_EQ(m.count, 0);
  EXPECT_EQ(collide(ms, xf(Vec3::Zero()), ms, xf(Vec3::Zero()), 1.0f, m), 0);
  EXPECT_EQ(collide(ms, xf(Vec3::Zero()), kGround, xf(Vec3::Zero()), 1.0f, m), 0);
  EXPECT_EQ(collide(kGround, xf(Vec3::Zero()), ms, xf(Vec3::Zero()), 1.0f, m), 0);
}

}  // namespace
}  // namespace haif
