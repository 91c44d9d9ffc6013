// The separating-axis test of polyhedra uses one edge per direction (PolyView::numAxisEdges). It
// must find exactly what testing every edge pair finds.
#include "collision/convex_hull.h"
#include "collision/polytope.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace haif {
namespace detail {
namespace {

TEST(AxisEdges, BoxesAndBoxLikeHullsKeepOneEdgePerDirection) {
  const BoxPoly box(Vec3(0.3f, 0.2f, 0.1f));
  EXPECT_EQ(box.view().numAxisEdges, 3);
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back((i & 1) ? 0.4f : -0.4f, (i & 2) ? 0.2f : -0.2f, (i & 4) ? 0.3f : -0.3f);
  corners.emplace_back(0.0f, 0.5f, 0.0f);  // a roof: 4 more directions
  const auto hull = buildConvexHull(corners, nullptr);
  ASSERT_TRUE(hull);
  EXPECT_EQ(hull->axisEdges, 3u + 4u);
  EXPECT_EQ(hull->edges.size(), 8u + 4u + 4u);  // 8 cuboid edges left below the roof, 4 at the eaves, 4 roof edges
}

TEST(AxisEdges, SameContactsAsEveryEdgePair) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back((i & 1) ? 0.3f : -0.3f, (i & 2) ? 0.25f : -0.25f, (i & 4) ? 0.2f : -0.2f);
  for (int i = 0; i < 6; ++i) pts.emplace_back(0.35f * u(rng), 0.3f + 0.1f * std::fabs(u(rng)), 0.25f * u(rng));
  const auto hull = buildConvexHull(pts, nullptr);
  ASSERT_TRUE(hull);
  ASSERT_LT(int(hull->axisEdges), int(hull->edges.size())) << "test set-up: the hull must have parallel edges";
  const BoxPoly box(Vec3(0.25f, 0.2f, 0.3f));
  int touching = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Transform xa, xb;
    xa.p = Vec3::Zero();
    xa.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    xb.p = 0.55f * Vec3(u(rng), u(rng), u(rng));
    xb.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    for (int pair = 0; pair < 2; ++pair) {
      PolyView A = pair == 0 ? box.view() : hullView(*hull), B = hullView(*hull);
      PolyView fullA = A, fullB = B;
      fullA.numAxisEdges = fullA.numEdges;
      fullB.numAxisEdges = fullB.numEdges;
      Manifold fast, full;
      collidePolyPoly(A, xa, B, xb, 0.02f, fast);
      collidePolyPoly(fullA, xa, fullB, xb, 0.02f, full);
      ASSERT_EQ(fast.count, full.count) << "trial " << trial << " pair " << pair;
      for (int k = 0; k < fast.count; ++k) {
        EXPECT_NEAR(fast.points[k].depth, full.points[k].depth, 1e-5f);
        EXPECT_LT((fast.points[k].normal - full.points[k].normal).norm(), 1e-4f);
        EXPECT_LT((fast.points[k].position - full.points[k].position).norm(), 1e-4f);
      }
      touching += fast.count > 0;
    }
  }
  EXPECT_GT(touching, 100) << "test set-up: most trials must touch";
}

}  // namespace
}  // namespace detail
}  // namespace haif
