// The separating-axis test of polyhedra tries only the edge pairs whose Gauss-map arcs cross
// (PolyView::edgeFaces), or else one edge per direction (PolyView::numAxisEdges). Either must find
// what testing every edge pair over all vertices finds.
#include "collision_test_util.h"
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

// A hull of fewest to fewest + spread - 1 points drawn within ±half (null if it could not be built).
std::shared_ptr<ConvexHull> randomHull(std::mt19937& rng, std::uniform_real_distribution<float>& u, int fewest,
                                       int spread, const Vec3& half) {
  std::vector<Vec3> pts;
  const int n = fewest + int(rng() % uint32_t(spread));
  for (int i = 0; i < n; ++i) pts.emplace_back(half.x() * u(rng), half.y() * u(rng), half.z() * u(rng));
  return buildConvexHull(pts, nullptr);
}

// The same polyhedron, its separating-axis test made over every edge pair and all vertices.
PolyView everyEdgePair(PolyView P) {
  P.numAxisEdges = P.numEdges;
  P.edgeFaces = nullptr;
  return P;
}

// The points of two manifolds of one overlapping pair agree in depth and normal (hulls pair
// `shapes`, pose `trial`, for the message).
void expectSamePoints(const Manifold& fast, const Manifold& full, int shapes, int trial) {
  for (int k = 0; k < fast.count; ++k) {
    EXPECT_NEAR(fast.points[k].depth, full.points[k].depth, 1e-4f) << "hulls " << shapes << ", trial " << trial;
    EXPECT_LT((fast.points[k].normal - full.points[k].normal).norm(), 1e-3f) << "hulls " << shapes << ", trial " << trial;
  }
}

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
      const PolyView fullA = everyEdgePair(A), fullB = everyEdgePair(B);
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

// Hull a at a random turn and b at a random pose near it, `trials` times: the same contacts whether
// the edge pairs are pruned on the Gauss map or all measured. Returns how many poses touched.
int expectPrunedFindsWhatEveryPairFinds(const ConvexHull& a, const ConvexHull& b, std::mt19937& rng,
                                        std::uniform_real_distribution<float>& u, int trials, int shapes) {
  const PolyView A = hullView(a), B = hullView(b);
  EXPECT_TRUE(A.edgeFaces && B.edgeFaces);
  const PolyView fullA = everyEdgePair(A), fullB = everyEdgePair(B);
  int touching = 0;
  for (int trial = 0; trial < trials; ++trial) {
    Transform xa, xb;
    xa.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    xb.p = 0.7f * Vec3(u(rng), u(rng), u(rng));
    xb.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    Manifold fast, full;
    collidePolyPoly(A, xa, B, xb, 0.02f, fast);
    collidePolyPoly(fullA, xa, fullB, xb, 0.02f, full);
    EXPECT_EQ(fast.count, full.count) << "hulls " << shapes << ", trial " << trial;
    if (fast.count != full.count) continue;
    float deepestFast = -1e30f, deepestFull = -1e30f;
    for (int k = 0; k < fast.count; ++k) {
      deepestFast = std::max(deepestFast, fast.points[k].depth);
      deepestFull = std::max(deepestFull, full.points[k].depth);
    }
    if (deepestFull >= 0.0f) {
      // Overlapping: the deepest axis is a face or a Minkowski-face edge pair, which both find.
      expectSamePoints(fast, full, shapes, trial);
    } else if (fast.count > 0) {
      // Apart within the margin: every axis only bounds the gap from below, and the full test
      // tries more of them, so the pruned one may see a smaller gap (its contact acts sooner),
      // never a larger one.
      EXPECT_GE(deepestFast, deepestFull - 1e-5f) << "hulls " << shapes << ", trial " << trial;
    }
    touching += fast.count > 0;
  }
  return touching;
}

TEST(AxisEdges, PrunedEdgePairsOfRandomHullsFindWhatEveryPairFinds) {
  // Two irregular hulls of 12-30 points in 300 random poses each, overlapping, touching or apart.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int touching = 0;
  for (int shapes = 0; shapes < 6; ++shapes) {
    std::shared_ptr<ConvexHull> hulls[2];
    for (auto& h : hulls) {
      h = randomHull(rng, u, 12, 19, Vec3(0.5f, 0.35f, 0.4f));
      ASSERT_TRUE(h);
      ASSERT_EQ(h->edgeFaces.size(), h->edges.size()) << "every hull edge has its two faces";
    }
    touching += expectPrunedFindsWhatEveryPairFinds(*hulls[0], *hulls[1], rng, u, 300, shapes);
  }
  EXPECT_GT(touching, 600) << "test set-up: many trials must touch";
}

TEST(AxisEdges, AHullWithEdgesPastOneChunkFindsWhatEveryPairFinds) {
  // A's near edges are gathered 64 at a time (collide_polytope.cpp): a round hull of 48 points on a
  // sphere has 138 edges, so the pairs that touch lie in every chunk.
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Vec3> pts;
  while (pts.size() < 48) {
    const Vec3 d(u(rng), u(rng), u(rng));
    if (d.squaredNorm() > 0.04f && d.squaredNorm() < 1.0f) pts.push_back(0.45f * d.normalized());
  }
  const std::shared_ptr<ConvexHull> round = buildConvexHull(pts, nullptr);
  ASSERT_TRUE(round);
  ASSERT_GT(round->edges.size(), 128u) << "test set-up: edges in three chunks";
  int touching = 0;
  for (int shapes = 0; shapes < 4; ++shapes) {
    const std::shared_ptr<ConvexHull> other = randomHull(rng, u, 12, 19, Vec3(0.5f, 0.35f, 0.4f));
    ASSERT_TRUE(other);
    touching += expectPrunedFindsWhatEveryPairFinds(*round, *other, rng, u, 300, shapes);
  }
  EXPECT_GT(touching, 400) << "test set-up: many trials must touch";
}

TEST(AxisEdges, HullsJustTouchingGetWhatEveryEdgePairGives) {
  // In a pile most hull pairs touch by a few millimetres, and only the edges near the other hull
  // are tried (the reach of collidePolyPoly). Random hulls moved along a random direction to where
  // they start to touch, then from 3 cm apart to 3 cm deep: the same contacts as every edge pair
  // measured over all vertices when they overlap, and a contact whenever that finds one.
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int compared = 0, overlapping = 0;
  for (int shapes = 0; shapes < 6; ++shapes) {
    std::shared_ptr<ConvexHull> hulls[2];
    for (auto& h : hulls) {
      h = randomHull(rng, u, 12, 19, Vec3(0.3f, 0.2f, 0.25f));
      ASSERT_TRUE(h);
    }
    const PolyView A = hullView(*hulls[0]), B = hullView(*hulls[1]);
    const PolyView fullA = everyEdgePair(A), fullB = everyEdgePair(B);
    for (int trial = 0; trial < 200; ++trial) {
      Transform xa, xb;
      xa.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      xb.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      // Where along dir they start to touch: the full test at margin 0 says overlap or not.
      float in = 0.0f, out = 2.0f;
      for (int k = 0; k < 30; ++k) {
        xb.p = 0.5f * (in + out) * dir;
        Manifold m;
        (collidePolyPoly(fullA, xa, fullB, xb, 0.0f, m) > 0 ? in : out) = 0.5f * (in + out);
      }
      xb.p = (out + 0.03f * u(rng)) * dir;
      Manifold fast, full;
      collidePolyPoly(A, xa, B, xb, 0.02f, fast);
      collidePolyPoly(fullA, xa, fullB, xb, 0.02f, full);
      if (full.count > 0 && full.deepest() > 0.0f) {
        ASSERT_EQ(fast.count, full.count) << "hulls " << shapes << ", trial " << trial;
        expectSamePoints(fast, full, shapes, trial);
        ++overlapping;
      } else if (full.count > 0) {
        // Apart within the margin: as above, the pruned test may see a smaller gap, never a larger.
        ASSERT_GT(fast.count, 0) << "hulls " << shapes << ", trial " << trial;
        float deepestFast = -1e30f, deepestFull = -1e30f;
        for (int k = 0; k < fast.count; ++k) deepestFast = std::max(deepestFast, fast.points[k].depth);
        for (int k = 0; k < full.count; ++k) deepestFull = std::max(deepestFull, full.points[k].depth);
        EXPECT_GE(deepestFast, deepestFull - 1e-5f) << "hulls " << shapes << ", trial " << trial;
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 1200);
  EXPECT_GT(overlapping, 400) << "test set-up: many trials must overlap";
}


TEST(AxisEdges, AWiderMarginNeverLosesAnOverlapOfRandomHulls) {
  // A fast pair's wide margin makes a face preferred over an edge while they are apart (the face's
  // points take a landing on several points). Once the edges overlap, the face's clipped points can
  // lie where nothing touches and read the overlap as a gap: the same pairs at margin 0 and at the
  // margins of 8, 15 and 30 m/s must all report an overlap.
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int overlapping = 0;
  for (int shapes = 0; shapes < 6; ++shapes) {
    std::shared_ptr<ConvexHull> hulls[2];
    for (auto& h : hulls) {
      h = randomHull(rng, u, 8, 12, Vec3(0.3f, 0.25f, 0.3f));
      ASSERT_TRUE(h);
    }
    const PolyView A = hullView(*hulls[0]), B = hullView(*hulls[1]);
    for (int trial = 0; trial < 2000; ++trial) {
      Transform xa, xb;
      xa.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      xb.p = 0.4f * Vec3(u(rng), u(rng), u(rng));
      xb.q = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
      bool deep = false;
      ASSERT_TRUE(test::overlapKeptAtWideMargins(
          [&](float margin, Manifold& m) { return collidePolyPoly(A, xa, B, xb, margin, m); }, {0.15f, 0.25f, 0.5f},
          deep))
          << "hulls " << shapes << ", trial " << trial;
      overlapping += deep;
    }
  }
  EXPECT_GT(overlapping, 1000) << "test set-up: many trials must overlap";
}

TEST(AxisEdges, AHullLyingFlatOnAWideGroundBoxTouchesWhereItLies) {
  // A hull resting on a face on a 1000 m ground box, one bottom edge within a degree of the
  // ground's rim edges, tilted by float noise. Its face's negated normal and the ground's top normal
  // are one point of the Gauss map, so whether the arcs of that edge and a rim edge "cross" is
  // rounding; and the cross product of two nearly parallel edges turns a 1e-7 tilt into a 1e-5 one,
  // which over the 500 m to the rim made the two edge lines 6 mm apart. Taken for the shapes'
  // separation, that edge pair beat the face: a hull resting on the ground got one contact point
  // 250 m away (in a pit of 1200 bodies one was pushed through the floor at 37 m/s). Every point
  // must lie under the hull, level with the ground's top.
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const BoxPoly ground(Vec3(500.0f, 1.0f, 500.0f));
  Transform xg;
  xg.p = Vec3(0.0f, -1.0f, 0.0f);
  const Vec3 corners[4] = {Vec3(0.0f, 0.0f, 0.0f), Vec3(0.28f, 0.0f, 0.0f), Vec3(0.1f, 0.0f, 0.2f), Vec3(0.1f, 0.2f, 0.07f)};
  int poses = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // The hull is built turned by a random rotation and laid back flat by its inverse, so its face
    // normals and edges are level only to rounding, as in a simulated pile; then yawed to within
    // 1.2 degrees of a rim direction (x or z).
    const Quat turn = Quat(Eigen::AngleAxisf(3.0f * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    std::vector<Vec3> pts;
    for (const Vec3& c : corners) pts.push_back(turn * c);
    const auto hull = buildConvexHull(pts, nullptr);
    ASSERT_TRUE(hull);
    const PolyView H = hullView(*hull);
    const float yaw = 0.5f * float(M_PI) * float(trial % 4) + 0.02f * u(rng);
    Transform xh;
    xh.q = Quat(Eigen::AngleAxisf(yaw, Vec3::UnitY())) * turn.conjugate();
    xh.q.normalize();
    const float gap = 0.004f * std::fabs(u(rng));
    float lowest = 1e30f;
    for (const Vec3& v : hull->vertices) lowest = std::min(lowest, (xh.q * v).y());
    xh.p = Vec3(10.0f * u(rng), gap - lowest, 10.0f * u(rng));
    Manifold m;
    collidePolyPoly(ground.view(), xg, H, xh, 0.02f, m);
    ++poses;
    ASSERT_GT(m.count, 0) << "trial " << trial << ": resting " << gap << " m above the ground";
    for (int k = 0; k < m.count; ++k) {
      const Vec3& p = m.points[k].position;
      EXPECT_LT(Vec3(p.x() - xh.p.x(), 0.0f, p.z() - xh.p.z()).norm(), 0.3f)
          << "trial " << trial << ": a point far from where the hull lies, at " << p.transpose();
      EXPECT_NEAR(m.points[k].depth, -gap, 1e-3f) << "trial " << trial;
      EXPECT_GT(m.points[k].normal.y(), 0.999f) << "trial " << trial;
    }
  }
  EXPECT_EQ(poses, 400);
}

}  // namespace
}  // namespace detail
}  // namespace haif
