// Reused manifolds (collision/manifold_cache.h): moved with the bodies, a kept manifold must give the
// points and depths a fresh collide() gives, and must be refused once the bodies slide, turn or part.
#include "collision/manifold_cache.h"
#include "collision_test_util.h"

namespace haif {
namespace {

using test::axisAngle;
using test::expectVecNear;
using test::findPoint;
using test::xf;

const Shape kBox = Shape::box(Vec3(0.5f, 0.25f, 0.4f));
constexpr float kMargin = 0.02f;

// Box B resting 3 mm deep on box A, a little off centre and turned about the normal.
struct Pair {
  Transform a = xf(Vec3(0.0f, 0.0f, 0.0f));
  Transform b = xf(Vec3(0.15f, 0.497f, -0.1f), axisAngle(Vec3::UnitY(), 0.3f));
  Manifold m;
  ManifoldCache cache;
  Pair() {
    EXPECT_GT(collide(kBox, a, kBox, b, kMargin, m), 0);
    rememberManifold(m, a, b, cache);
  }
};

// Every point of `kept` is at a point of a fresh manifold, with its normal and depth.
void expectSameAsFresh(const Manifold& kept, const Transform& a, const Transform& b) {
  Manifold fresh;
  ASSERT_EQ(collide(kBox, a, kBox, b, kMargin, fresh), kept.count);
  for (int i = 0; i < kept.count; ++i) {
    const int k = findPoint(fresh, kept.points[i].position, 2e-5f);
    ASSERT_GE(k, 0) << "point " << i << " of the kept manifold is not a point of a fresh one";
    expectVecNear(kept.points[i].normal, fresh.points[k].normal, 1e-5f);
    EXPECT_NEAR(kept.points[i].depth, fresh.points[k].depth, 2e-6f);
  }
}

TEST(ManifoldCache, MovesWithBothBodies) {
  Pair p;
  // The pair carried along together: 2 m across and turned 40 degrees about a slanted axis.
  Transform carry = xf(Vec3(2.0f, -0.5f, 1.0f), axisAngle(Vec3(1.0f, 2.0f, 0.5f), 0.7f));
  const Transform a = Transform{carry.apply(p.a.p), carry.q * p.a.q}, b = Transform{carry.apply(p.b.p), carry.q * p.b.q};
  Manifold kept = p.m;
  ASSERT_TRUE(refreshManifold(p.cache, a, b, ManifoldReuseLimits{}, kept));
  expectSameAsFresh(kept, a, b);
  for (int i = 0; i < kept.count; ++i) EXPECT_EQ(kept.points[i].id, p.m.points[i].id);  // warm starts stay matched
}

TEST(ManifoldCache, DepthFollowsMotionAlongTheNormal) {
  Pair p;
  for (float dy : {-0.002f, 0.004f, -0.015f}) {  // 2 mm deeper, 4 mm apart (speculative), 15 mm deeper
    Transform b = p.b;
    b.p.y() += dy;
    Manifold kept = p.m;
    ASSERT_TRUE(refreshManifold(p.cache, p.a, b, ManifoldReuseLimits{}, kept)) << dy;
    for (int i = 0; i < kept.count; ++i) EXPECT_NEAR(kept.points[i].depth, p.m.points[i].depth - dy, 1e-6f);
    expectSameAsFresh(kept, p.a, b);
  }
}

TEST(ManifoldCache, RefusedWhenTheBodiesSlideTurnOrPart) {
  Pair p;
  const ManifoldReuseLimits limits;
  auto refused = [&](const Transform& b) {
    Manifold kept = p.m;
    const bool ok = refreshManifold(p.cache, p.a, b, limits, kept);
    for (int i = 0; i < kept.count; ++i) EXPECT_EQ(kept.points[i].depth, p.m.points[i].depth);  // untouched
    return !ok;
  };
  Transform slid = p.b, turned = p.b, tilted = p.b, parted = p.b;
  slid.p.x() += 2.0f * limits.slide;
  turned.q = axisAngle(Vec3::UnitY(), 0.02f) * turned.q;  // about the normal: the points slide on the patch
  tilted.q = axisAngle(Vec3::UnitX(), 0.02f) * tilted.q;   // the normal turns: a corner may lift or land
  parted.p.y() += limits.margin + 0.01f;
  EXPECT_TRUE(refused(slid));
  EXPECT_TRUE(refused(turned));
  EXPECT_TRUE(refused(tilted));
  EXPECT_TRUE(refused(parted));
  Transform still = p.b;
  still.p.x() += 0.5f * limits.slide;
  EXPECT_FALSE(refused(still));
}

TEST(ManifoldCache, NothingKeptForEmptyOrMixedNormals) {
  ManifoldCache cache;
  Manifold m;
  EXPECT_FALSE(refreshManifold(cache, xf(Vec3::Zero()), xf(Vec3::UnitY()), ManifoldReuseLimits{}, m));
  m.count = 2;
  m.points[0].normal = Vec3::UnitY();
  m.points[1].normal = Vec3(0.0f, 0.8f, 0.6f);  // a mesh contact across an edge
  rememberManifold(m, xf(Vec3::Zero()), xf(Vec3::UnitY()), cache);
  EXPECT_FALSE(cache.valid);
}

}  // namespace
}  // namespace haif
