// The separating-axis test of polyhedra tries only the edge pairs whose Gauss-map arcs cross
// (PolyView::edgeFaces), or else one edge per direction (PolyView::numAxisEdges). Either must find
// what testing every edge pair over all vertices finds.
#include "collision/convex_hull.h"
#include "collision/polytope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
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
      fullA.edgeFaces = fullB.edgeFaces = nullptr;  // every edge pair, measured over all vertices
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

TEST(AxisEdges, PrunedEdgePairsOfRandomHullsFindWhatEveryPairFinds) {
  // Two irregular hulls of 12-30 points in 300 random poses each, overlapping, touching or apart:
  // the same contacts whether the edge pairs are pruned on the Gauss map or all measured.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int compared = 0, touching = 0;
  for (int shapes = 0; shapes < 6; ++shapes) {
    std::shared_ptr<ConvexHull> hulls[2];
    for (auto& h : hulls) {
      std::vector<Vec3> pts;
      const int n = 12 + int(rng() % 19);
      for (int i = 0; i < n; ++i) pts.emplace_back(0.5f * u(rng), 0.35f * u(rng), 0.4f * u(rng));
      h = buildConvexHull(pts, nullptr);
      ASSERT_TRUE(h);
      ASSERT_EQ(h->edgeFaces.size(), h->edges.size()) << "every hull edge has its two faces";
    }
    for (int trial = 0; trial < 300; ++trial) {
      Transform xa, xb;
      xa.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      xb.p = 0.7f * Vec3(u(rng), u(rng), u(rng));
      xb.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      const PolyView A = hullView(*hulls[0]), B = hullView(*hulls[1]);
      ASSERT_TRUE(A.edgeFaces && B.edgeFaces);
      PolyView fullA = A, fullB = B;
      fullA.numAxisEdges = fullA.numEdges;
      fullB.numAxisEdges = fullB.numEdges;
      fullA.edgeFaces = fullB.edgeFaces = nullptr;
      Manifold fast, full;
      collidePolyPoly(A, xa, B, xb, 0.02f, fast);
      collidePolyPoly(fullA, xa, fullB, xb, 0.02f, full);
      ASSERT_EQ(fast.count, full.count) << "hulls " << shapes << ", trial " << trial;
      float deepestFast = -1e30f, deepestFull = -1e30f;
      for (int k = 0; k < fast.count; ++k) {
        deepestFast = std::max(deepestFast, fast.points[k].depth);
        deepestFull = std::max(deepestFull, full.points[k].depth);
      }
      if (deepestFull >= 0.0f) {
        // Overlapping: the deepest axis is a face or a Minkowski-face edge pair, which both find.
        for (int k = 0; k < fast.count; ++k) {
          EXPECT_NEAR(fast.points[k].depth, full.points[k].depth, 1e-4f) << "hulls " << shapes << ", trial " << trial;
          EXPECT_LT((fast.points[k].normal - full.points[k].normal).norm(), 1e-3f) << "hulls " << shapes << ", trial " << trial;
        }
      } else if (fast.count > 0) {
        // Apart within the margin: every axis only bounds the gap from below, and the full test
        // tries more of them, so the pruned one may see a smaller gap (its contact acts sooner),
        // never a larger one.
        EXPECT_GE(deepestFast, deepestFull - 1e-5f) << "hulls " << shapes << ", trial " << trial;
      }
      ++compared;
      touching += fast.count > 0;
    }
  }
  EXPECT_EQ(compared, 1800);
  EXPECT_GT(touching, 600) << "test set-up: many trials must touch";
}

}  // namespace
}  // namespace detail
}  // namespace haif
