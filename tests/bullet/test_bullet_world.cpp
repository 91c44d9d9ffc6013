// The Bullet baseline reproduces the scene it is given: free fall at g with the same integrator
// order, boxes, spheres, capsules and hulls resting at their true size (Bullet's margin must not
// inflate them), HAIF's friction and restitution combine, Coulomb sliding at μg, kinematic motion,
// principal-axis frames that read back as the scene's pose, and a clear error for what it lacks.
#include "bullet/bullet_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace haif {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kG = 9.81f;

SceneDesc emptyScene() {
  SceneDesc s;
  s.name = "test";
  s.sourcePath = "mem/test.json";
  s.materials.push_back(MaterialDesc{});
  return s;
}

BodyDesc groundBox() {
  BodyDesc b;
  b.name = "ground";
  b.where = "bodies[ground]";
  b.motion = MotionType::Static;
  b.shape.type = ShapeType::Box;
  b.shape.halfExtents = Vec3(50.0f, 1.0f, 50.0f);
  b.position = Vec3(0.0f, -1.0f, 0.0f);
  return b;
}

BodyDesc box(const Vec3& p, float half = 0.5f, float mass = 1.0f) {
  BodyDesc b;
  b.where = "bodies[box]";
  b.shape.type = ShapeType::Box;
  b.shape.halfExtents = Vec3::Constant(half);
  b.position = p;
  b.mass = mass;
  return b;
}

void build(BulletWorld& w, const SceneDesc& s, int iterations = 10) {
  std::string error;
  ASSERT_TRUE(w.build(s, iterations, error)) << error;
}

void steps(BulletWorld& w, int n) {
  for (int i = 0; i < n; ++i) w.step();
}

TEST(BulletWorld, FreeFallFollowsSemiImplicitEuler) {
  SceneDesc s = emptyScene();
  s.bodies.push_back(box(Vec3(0.0f, 100.0f, 0.0f)));
  BulletWorld w;
  build(w, s);
  const int n = 60;
  steps(w, n);
  // v_n = -g n dt, y_n = y_0 - g dt² n(n+1)/2: velocity first, then position, as HAIF integrates.
  EXPECT_NEAR(w.linearVelocity(0).y(), -kG * n * kDt, 1e-3f);
  EXPECT_NEAR(w.pose(0).p.y(), 100.0f - kG * kDt * kDt * n * (n + 1) / 2.0f, 2e-3f);
  EXPECT_NEAR(w.pose(0).p.x(), 0.0f, 1e-6f);
}

TEST(BulletWorld, BoxRestsOnGroundAtItsTrueSize) {
  SceneDesc s = emptyScene();
  s.bodies.push_back(groundBox());
  s.bodies.push_back(box(Vec3(0.2f, 0.5f, -0.3f)));
  BulletWorld w;
  build(w, s);
  steps(w, 120);
  const Transform xf = w.pose(1);
  // A margin added outside the box would hold it at 0.54; penetration is held near the slop.
  EXPECT_NEAR(xf.p.y(), 0.5f, 0.01f);
  EXPECT_NEAR(xf.p.x(), 0.2f, 1e-3f);
  EXPECT_NEAR(xf.p.z(), -0.3f, 1e-3f);
  EXPECT_LT(w.linearVelocity(1).norm(), 0.02f);
  EXPECT_GT(std::fabs(xf.q.w()), 0.9999f);
  std::vector<BulletContactPoint> points;
  w.readContactPoints(points);
  ASSERT_GE(points.size(), 4u);
  for (const BulletContactPoint& p : points) {
    EXPECT_TRUE((p.a == 0 && p.b == 1) || (p.a == 1 && p.b == 0));
    EXPECT_LT(std::fabs(p.depth), 0.02f);
  }
  EXPECT_EQ(w.smallestExtent(1), 1.0f);
}

TEST(BulletWorld, SphereCapsuleAndHullRestAtTheirTrueSize) {
  SceneDesc s = emptyScene();
  BodyDesc plane;
  plane.where = "bodies[plane]";
  plane.motion = MotionType::Static;
  plane.shape.type = ShapeType::Plane;
  plane.shape.planeNormal = Vec3::UnitY();
  s.bodies.push_back(plane);
  BodyDesc sphere;
  sphere.shape.type = ShapeType::Sphere;
  sphere.shape.radius = 0.3f;
  sphere.position = Vec3(0.0f, 0.3f, 0.0f);
  s.bodies.push_back(sphere);
  BodyDesc capsule;
  capsule.shape.type = ShapeType::Capsule;
  capsule.shape.radius = 0.25f;
  capsule.shape.halfHeight = 0.5f;
  capsule.position = Vec3(3.0f, 0.25f, 0.0f);  // lying on its side
  capsule.orientation = Quat(Eigen::AngleAxisf(0.5f * kPi, Vec3::UnitZ()));
  s.bodies.push_back(capsule);
  BodyDesc hull;
  hull.shape.type = ShapeType::ConvexHull;
  for (int k = 0; k < 8; ++k)
    hull.shape.points.push_back(Vec3(k & 1 ? 0.6f : -0.6f, k & 2 ? 0.4f : -0.4f, k & 4 ? 0.5f : -0.5f));
  hull.position = Vec3(-3.0f, 0.4f, 0.0f);
  s.bodies.push_back(hull);
  BulletWorld w;
  build(w, s);
  steps(w, 90);
  EXPECT_NEAR(w.pose(1).p.y(), 0.3f, 0.01f);
  EXPECT_NEAR(w.pose(2).p.y(), 0.25f, 0.01f);
  EXPECT_NEAR(w.pose(3).p.y(), 0.4f, 0.01f);  // the margin was taken off the hull's faces
  for (uint32_t i = 1; i <= 3; ++i) EXPECT_LT(w.linearVelocity(i).norm(), 0.05f) << "body " << i;
}

TEST(BulletWorld, FrictionAndRestitutionCombineAsHaifDoes) {
  SceneDesc s = emptyScene();
  MaterialDesc rough;
  rough.name = "rough";
  rough.friction = 0.9f;
  rough.restitution = 0.2f;
  MaterialDesc smooth;
  smooth.name = "smooth";
  smooth.friction = 0.4f;
  smooth.restitution = 0.7f;
  s.materials.push_back(rough);
  s.materials.push_back(smooth);
  BodyDesc g = groundBox();
  g.material = 1;
  s.bodies.push_back(g);
  BodyDesc b = box(Vec3(0.0f, 0.5f, 0.0f));
  b.material = 2;
  s.bodies.push_back(b);
  BulletWorld w;
  build(w, s);
  EXPECT_TRUE(std::isnan(w.combinedFriction(0, 1)));  // no collision pass yet
  steps(w, 2);
  // HAIF: friction √(μa·μb), restitution max(ea, eb).
  EXPECT_NEAR(w.combinedFriction(0, 1), std::sqrt(0.9f * 0.4f), 1e-6f);
  EXPECT_NEAR(w.combinedFriction(1, 0), 0.6f, 1e-6f);
  EXPECT_NEAR(w.combinedRestitution(0, 1), 0.7f, 1e-6f);
}

TEST(BulletWorld, SlidingBoxDeceleratesAtMuG) {
  SceneDesc s = emptyScene();
  MaterialDesc m;
  m.name = "m";
  m.friction = 0.3f;
  s.materials.push_back(m);
  BodyDesc g = groundBox();
  g.material = 1;
  s.bodies.push_back(g);
  BodyDesc b = box(Vec3(0.0f, 0.5f, 0.0f));
  b.material = 1;
  b.linearVelocity = Vec3(3.0f, 0.0f, 2.0f);  // not along an axis: needs both friction rows
  s.bodies.push_back(b);
  BulletWorld w;
  build(w, s);
  const int n = 30;
  steps(w, n);
  const Vec3 v = w.linearVelocity(1);
  const float speed0 = std::sqrt(13.0f);
  const float expected = speed0 - 0.3f * kG * n * kDt;
  EXPECT_NEAR(Vec3(v.x(), 0.0f, v.z()).norm(), expected, 0.05f * speed0);
  // Friction opposes the motion, so the direction is kept, to a few degrees: Bullet's friction rows
  // act point by point and give the sliding box a slow yaw.
  const float cosTurned = Vec3(v.x(), 0.0f, v.z()).normalized().dot(Vec3(3.0f, 0.0f, 2.0f).normalized());
  const float turned = std::acos(std::clamp(cosTurned, -1.0f, 1.0f));
  EXPECT_LT(turned, 6.0f * kPi / 180.0f);
}

TEST(BulletWorld, KinematicBodyMovesAtItsVelocityAndCarriesABox) {
  SceneDesc s = emptyScene();
  BodyDesc platform;
  platform.motion = MotionType::Kinematic;
  platform.shape.type = ShapeType::Box;
  platform.shape.halfExtents = Vec3(2.0f, 0.25f, 2.0f);
  platform.position = Vec3(0.0f, 1.0f, 0.0f);
  platform.linearVelocity = Vec3(0.5f, 0.0f, 0.0f);
  s.bodies.push_back(platform);
  s.bodies.push_back(box(Vec3(0.0f, 1.75f, 0.0f)));
  BulletWorld w;
  build(w, s);
  steps(w, 120);
  EXPECT_NEAR(w.pose(0).p.x(), 0.5f * 120 * kDt, 1e-3f);
  EXPECT_NEAR(w.pose(0).p.y(), 1.0f, 1e-6f);
  EXPECT_FALSE(w.isDynamic(0));
  EXPECT_TRUE(w.isDynamic(1));
  // Friction makes the box ride along.
  EXPECT_NEAR(w.linearVelocity(1).x(), 0.5f, 0.05f);
  EXPECT_NEAR(w.pose(1).p.y(), 1.75f, 0.02f);
}

TEST(BulletWorld, PrincipalFrameReadsBackAsTheScenePose) {
  // An irregular hull has a non-diagonal inertia tensor: Bullet's body frame is rotated to its
  // principal axes, which must not show in the pose it reports.
  SceneDesc s = emptyScene();
  s.settings.world.gravity = Vec3::Zero();
  BodyDesc hull;
  hull.shape.type = ShapeType::ConvexHull;
  hull.shape.points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.5f), Vec3(1, 1, 0.5f)};
  hull.position = Vec3(1.0f, 2.0f, 3.0f);
  hull.orientation = Quat(Eigen::AngleAxisf(0.7f, Vec3(1, 2, 3).normalized()));
  hull.angularVelocity = Vec3(0.0f, 1.0f, 0.0f);
  s.bodies.push_back(hull);
  BulletWorld w;
  build(w, s);
  const Transform start = w.pose(0);
  EXPECT_LT(start.q.angularDistance(hull.orientation), 1e-5f);
  // The centre of mass (not the hull's origin) is the body's position, as in HAIF.
  EXPECT_GT((start.p - hull.position).norm(), 0.1f);
  steps(w, 30);
  // A free body keeps its centre of mass where it is and keeps spinning.
  EXPECT_NEAR((w.pose(0).p - start.p).norm(), 0.0f, 1e-5f);
  EXPECT_GT(w.angularVelocity(0).norm(), 0.5f);
}

TEST(BulletWorld, AnAsymmetricCompoundRestsOnItsPartsWhereHaifPutsIt) {
  // An L of a long bar and a heavy block at one end, tilted: Bullet gets a btCompoundShape in the
  // principal frame (the tensor is not diagonal), its pose reads back as HAIF's, and it comes to
  // rest lying on both parts with its centre of mass at the height the parts give it.
  SceneDesc s = emptyScene();
  s.bodies.push_back(groundBox());
  BodyDesc l;
  l.where = "bodies[l]";
  l.shape.type = ShapeType::Compound;
  CompoundPartDesc bar, block;
  bar.shape.type = ShapeType::Box;
  bar.shape.halfExtents = Vec3(0.6f, 0.1f, 0.1f);
  block.shape.type = ShapeType::Box;
  block.shape.halfExtents = Vec3(0.1f, 0.1f, 0.3f);
  block.position = Vec3(0.7f, 0.0f, 0.2f);
  l.shape.parts = {bar, block};
  l.position = Vec3(0.0f, 0.6f, 0.0f);
  l.orientation = Quat(Eigen::AngleAxisf(0.2f, Vec3(1, 0, 1).normalized()));
  s.bodies.push_back(l);
  BulletWorld w;
  build(w, s);
  EXPECT_LT(w.pose(1).q.angularDistance(l.orientation), 1e-5f);
  steps(w, 240);
  // Both parts are 0.1 high at the centre: lying flat, the centre of mass sits 0.1 m up.
  EXPECT_NEAR(w.pose(1).p.y(), 0.1f, 0.02f);
  EXPECT_LT(std::abs((w.pose(1).q * Vec3::UnitY()).dot(Vec3::UnitY()) - 1.0f), 1e-3f) << "not lying flat";
  EXPECT_LT(w.linearVelocity(1).norm(), 0.05f);
}

TEST(BulletWorld, WaterIsRefusedWithAClearError) {
  SceneDesc s = emptyScene();
  s.bodies.push_back(box(Vec3(0.0f, 1.0f, 0.0f)));
  s.water.push_back(WaterDesc{});
  BulletWorld w;
  std::string error;
  EXPECT_FALSE(w.build(s, 10, error));
  EXPECT_NE(error.find("mem/test.json"), std::string::npos) << error;
  EXPECT_NE(error.find("water"), std::string::npos) << error;
}

TEST(BulletWorld, IterationCountComesFromTheCallerOrTheScene) {
  SceneDesc s = emptyScene();
  s.settings.world.iterations = 7;
  s.bodies.push_back(box(Vec3::Zero()));
  BulletWorld a, b;
  build(a, s, 0);
  build(b, s, 25);
  EXPECT_EQ(a.iterations(), 7);
  EXPECT_EQ(b.iterations(), 25);
}

}  // namespace
}  // namespace haif
