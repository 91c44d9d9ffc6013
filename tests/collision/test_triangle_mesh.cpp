// Triangle mesh construction (BVH, errors) and convex shapes against a mesh.
#include "collision/convex_hull.h"
#include "collision/triangle_mesh.h"
#include "collision_test_util.h"

#include <functional>
#include <limits>
#include <set>

namespace haif {
namespace {

using test::axisAngle;
using test::collideBoth;
using test::expectAll;
using test::expectVecNear;
using test::findPoint;
using test::xf;

// Square floor y = 0 from -s to s, two triangles, front facing +y.
std::shared_ptr<TriangleMesh> floorMesh(float s) {
  std::string err;
  auto m = buildTriangleMesh({Vec3(-s, 0, -s), Vec3(s, 0, -s), Vec3(s, 0, s), Vec3(-s, 0, s)}, {0, 2, 1, 0, 3, 2}, &err);
  EXPECT_TRUE(m) << err;
  return m;
}

// n x n grid of quads (2 triangles each) over [-s, s]^2 at y = 0.
std::shared_ptr<TriangleMesh> gridMesh(int n, float s) {
  std::vector<Vec3> v;
  std::vector<uint32_t> idx;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(Vec3(-s + 2 * s * i / n, 0, -s + 2 * s * j / n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      idx.insert(idx.end(), {a, c, b, b, c, d});
    }
  std::string err;
  auto m = buildTriangleMesh(v, idx, &err);
  EXPECT_TRUE(m) << err;
  return m;
}

TEST(TriangleMeshBuild, BvhCoversEveryTriangleOnce) {
  auto mesh = gridMesh(16, 8.0f);
  ASSERT_TRUE(mesh);
  const size_t tris = mesh->indices.size() / 3;
  ASSERT_EQ(tris, 512u);
  std::vector<int> seen(tris, 0);
  std::function<int(int)> walk = [&](int i) -> int {
    const auto& n = mesh->nodes[size_t(i)];
    if (n.left < 0) {
      EXPECT_LE(n.triCount, kMeshLeafTriangles);
      EXPECT_GE(n.triCount, 1u);
      for (uint32_t k = 0; k < n.triCount; ++k) {
        const uint32_t t = mesh->triIndex[n.firstTri + k];
        ++seen[t];
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(n.box.expanded(1e-6f).contains(Aabb{mesh->vertices[mesh->indices[3 * t + uint32_t(c)]], mesh->vertices[mesh->indices[3 * t + uint32_t(c)]]}));
      }
      return 1;
    }
    EXPECT_TRUE(n.box.contains(mesh->nodes[size_t(n.left)].box));
    EXPECT_TRUE(n.box.contains(mesh->nodes[size_t(n.right)].box));
    return 1 + std::max(walk(n.left), walk(n.right));
  };
  const int depth = walk(0);
  for (int s : seen) EXPECT_EQ(s, 1);
  EXPECT_LE(depth, 10);  // balanced: log2(512 / 4) + 1 = 8
  // Query: a small box touches only nearby triangles.
  std::set<uint32_t> hit;
  queryMeshTriangles(*mesh, Aabb{Vec3(0.1f, -0.1f, 0.1f), Vec3(0.2f, 0.1f, 0.2f)}, [&](uint32_t t) { hit.insert(t); });
  EXPECT_GE(hit.size(), 2u);
  EXPECT_LE(hit.size(), 8u);
}

TEST(TriangleMeshBuild, BadInputGivesClearErrors) {
  std::string err;
  EXPECT_EQ(buildTriangleMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {}, &err), nullptr);
  EXPECT_NE(err.find("no triangles"), std::string::npos) << err;
  EXPECT_EQ(buildTriangleMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {0, 1}, &err), nullptr);
  EXPECT_NE(err.find("multiple of 3"), std::string::npos) << err;
  EXPECT_EQ(buildTriangleMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {0, 1, 3}, &err), nullptr);
  EXPECT_NE(err.find("out of range"), std::string::npos) << err;
  EXPECT_EQ(buildTriangleMesh({Vec3(0, 0, 0), Vec3(1, std::numeric_limits<float>::infinity(), 0), Vec3(0, 1, 0)}, {0, 1, 2}, &err), nullptr);
  EXPECT_NE(err.find("vertex 1"), std::string::npos) << err;
}

TEST(MeshCollision, SphereOnTwoTriangleFloor) {
  const Shape floor = Shape::triangleMesh(floorMesh(5.0f));
  Manifold m;
  ASSERT_EQ(collideBoth(floor, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(1.0f, 0.9f, -2.0f)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  expectVecNear(m.points[0].position, Vec3(1.0f, -0.05f, -2.0f), 1e-5f);
  // Right above the shared diagonal: still one point, straight up.
  ASSERT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(1.0f, 0.95f, 1.0f)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  // Margin and separation.
  ASSERT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(0, 1.05f, 0.3f)), 0.1f, m), 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-5f);
  EXPECT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(0, 1.2f, 0.3f)), 0.1f, m), 0);
  // Beyond the floor's edge: nothing.
  EXPECT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(1.0f), xf(Vec3(7, 0.5f, 0)), 0.1f, m), 0);
}

TEST(MeshCollision, TransformedMesh) {
  // Floor mesh body lifted to y = 2 and turned about y: same answer shifted.
  const Shape floor = Shape::triangleMesh(floorMesh(5.0f));
  Manifold m;
  ASSERT_EQ(collide(floor, xf(Vec3(0, 2, 0), axisAngle(Vec3::UnitY(), 0.7f)), Shape::sphere(0.5f), xf(Vec3(1, 2.4f, 1)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
}

TEST(MeshCollision, BoxOnFloorGivesFourCorners) {
  const Shape floor = Shape::triangleMesh(floorMesh(5.0f));
  const Shape box = Shape::box(Vec3::Constant(0.5f));
  Manifold m;
  // Inside one triangle, then straddling the diagonal x = z.
  for (const Vec3& c : {Vec3(2.0f, 0.49f, -2.5f), Vec3(0.3f, 0.49f, 0.1f)}) {
    ASSERT_EQ(collideBoth(floor, xf(Vec3::Zero()), box, xf(c), 0.0f, m), 4) << c.transpose();
    expectAll(m, Vec3::UnitY(), 0.01f, 1e-5f);
    for (float x : {-0.5f, 0.5f})
      for (float z : {-0.5f, 0.5f})
        EXPECT_GE(findPoint(m, Vec3(c.x() + x, -0.005f, c.z() + z), 1e-4f), 0) << c.transpose() << " " << x << " " << z;
  }
}

TEST(MeshCollision, BoxOnGridStableIds) {
  const Shape grid = Shape::triangleMesh(gridMesh(8, 4.0f));
  const Shape box = Shape::box(Vec3(0.7f, 0.5f, 0.7f));
  Manifold m1, m2;
  ASSERT_EQ(collide(grid, xf(Vec3::Zero()), box, xf(Vec3(0.2f, 0.49f, 0.15f)), 0.01f, m1), 4);
  ASSERT_EQ(collide(grid, xf(Vec3::Zero()), box, xf(Vec3(0.2003f, 0.4898f, 0.1499f), axisAngle(Vec3(0.2f, 1, 0.1f), 1e-3f)), 0.01f, m2), 4);
  expectAll(m1, Vec3::UnitY(), 0.01f, 1e-5f);
  std::set<uint32_t> a, b;
  for (int i = 0; i < 4; ++i) { a.insert(m1.points[i].id); b.insert(m2.points[i].id); }
  EXPECT_EQ(a.size(), 4u);
  EXPECT_EQ(a, b);
}

TEST(MeshCollision, CapsuleAndHullOnFloor) {
  const Shape floor = Shape::triangleMesh(floorMesh(5.0f));
  Manifold m;
  // The capsule crosses the diagonal: both ends are contacts (a third, redundant point may sit where
  // the axis crosses the shared edge).
  const int n = collideBoth(floor, xf(Vec3::Zero()), Shape::capsule(0.25f, 1.0f), xf(Vec3(0.5f, 0.2f, 0.2f), axisAngle(Vec3::UnitZ(), kPi / 2)), 0.0f, m);
  EXPECT_GE(n, 2);
  EXPECT_LE(n, 3);
  expectAll(m, Vec3::UnitY(), 0.05f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(1.5f, -0.025f, 0.2f), 1e-4f), 0);
  EXPECT_GE(findPoint(m, Vec3(-0.5f, -0.025f, 0.2f), 1e-4f), 0);

  std::string err;
  auto h = buildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)}, &err);
  ASSERT_TRUE(h) << err;
  ASSERT_EQ(collideBoth(floor, xf(Vec3::Zero()), Shape::convexHull(h), xf(Vec3(-2, 0.23f, 2)), 0.0f, m), 3);
  expectAll(m, Vec3::UnitY(), 0.02f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(-2.25f, -0.01f, 2.75f), 1e-4f), 0);
}

TEST(MeshCollision, SpeculativeBoxAboveFloor) {
  const Shape floor = Shape::triangleMesh(floorMesh(5.0f));
  const Shape box = Shape::box(Vec3::Constant(0.5f));
  Manifold m;
  ASSERT_EQ(collide(box, xf(Vec3(1, 0.53f, 1.5f)), floor, xf(Vec3::Zero()), 0.05f, m), 4);
  expectAll(m, -Vec3::UnitY(), -0.03f, 1e-5f);
  EXPECT_EQ(collide(box, xf(Vec3(1, 0.53f, 1.5f)), floor, xf(Vec3::Zero()), 0.02f, m), 0);
}

TEST(MeshCollision, BackSideAndEdgeOfMesh) {
  const Shape floor = Shape::triangleMesh(floorMesh(1.0f));
  Manifold m;
  // Below the one-sided floor: nothing pushes it up through the surface.
  EXPECT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(0.5f), xf(Vec3(0, -0.4f, 0)), 0.0f, m), 0);
  // Beside the outer edge x = 1 at floor height: pushed out sideways by the edge.
  ASSERT_EQ(collide(floor, xf(Vec3::Zero()), Shape::sphere(0.5f), xf(Vec3(1.4f, 0.0f, 0.0f)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitX(), 1e-5f);
}

}  // namespace
}  // namespace haif
