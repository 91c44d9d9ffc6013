// Support functions (collision/support.h): each shape's reach along a direction, and the depth bound
// the turn projection leans on: no pair routine reports a point deeper than the overlap along any
// direction allows.
#include "collision/support.h"

#include "collision/compound.h"
#include "collision/convex_hull.h"
#include "collision_test_util.h"

#include <cmath>
#include <limits>
#include <random>

namespace haif::test {
namespace {

using test::randomTurn;

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  Vec3 v;
  do v = Vec3(g(rng), g(rng), g(rng));
  while (v.squaredNorm() < 1e-6f);
  return v.normalized();
}

std::shared_ptr<const ConvexHull> randomHull(std::mt19937& rng, int points, float size) {
  std::vector<Vec3> pts;
  for (int i = 0; i < points; ++i) pts.push_back(size * randomUnit(rng).cwiseProduct(Vec3(1.0f, 0.7f, 0.5f)));
  std::string why;
  auto h = buildConvexHull(pts, &why);
  EXPECT_TRUE(h) << why;
  return h;
}

// The shapes of the pair tests: every convex kind, hulls of two sizes, and a compound of a box and
// a capsule (its reach is its parts').
std::vector<Shape> convexShapes(std::mt19937& rng) {
  std::vector<Shape> shapes = {Shape::sphere(0.3f), Shape::box(Vec3(0.4f, 0.25f, 0.15f)), Shape::capsule(0.15f, 0.3f),
                               Shape::convexHull(randomHull(rng, 14, 0.35f)),
                               Shape::convexHull(randomHull(rng, 40, 0.5f))};
  std::string why;
  auto c = buildCompound({Shape::box(Vec3(0.3f, 0.1f, 0.1f)), Shape::capsule(0.1f, 0.2f)},
                         {xf(Vec3(0, 0, 0)), xf(Vec3(0.3f, 0.2f, 0), axisAngle(Vec3::UnitZ(), 0.5f))}, &why);
  EXPECT_TRUE(c) << why;
  shapes.push_back(Shape::compoundOf(c));
  return shapes;
}

// Points that lie on (or in) a shape, at its pose: every corner, end and vertex a support can take.
std::vector<Vec3> surfacePoints(const Shape& s, const Transform& at, std::mt19937& rng) {
  std::vector<Vec3> out;
  switch (s.type) {
    case ShapeType::Sphere:
      for (int i = 0; i < 200; ++i) out.push_back(at.apply(s.radius * randomUnit(rng)));
      break;
    case ShapeType::Box:
      for (int i = 0; i < 8; ++i)
        out.push_back(at.apply(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1).cwiseProduct(s.halfExtents)));
      break;
    case ShapeType::Capsule:
      for (int i = 0; i < 200; ++i)
        out.push_back(at.apply(Vec3(0, i % 2 ? s.halfHeight : -s.halfHeight, 0) + s.radius * randomUnit(rng)));
      break;
    case ShapeType::ConvexHull:
      for (const Vec3& v : s.hull->vertices) out.push_back(at.apply(v));
      break;
    case ShapeType::Compound:
      for (const CompoundShape::Part& p : s.compound->parts)
        for (const Vec3& v : surfacePoints(p.shape, Transform{at.apply(p.local.p), at.q * p.local.q}, rng))
          out.push_back(v);
      break;
    default: break;
  }
  return out;
}

// Along any direction, no point of a shape reaches past its support, and some point reaches it (the
// support is attained: exactly at a corner or vertex, within the sampling on a round shape).
TEST(Support, EveryShapeReachesItsSupportAndNoFurther) {
  std::mt19937 rng(7);
  const std::vector<Shape> shapes = convexShapes(rng);
  for (size_t k = 0; k < shapes.size(); ++k) {
    for (int trial = 0; trial < 50; ++trial) {
      const Transform at = xf(Vec3(1.0f, -2.0f, 0.5f) + randomUnit(rng), randomTurn(rng));
      const Vec3 d = randomUnit(rng);
      const float reach = supportAlong(shapes[k], at, d);
      float most = -std::numeric_limits<float>::infinity();
      for (const Vec3& p : surfacePoints(shapes[k], at, rng)) most = std::max(most, d.dot(p));
      const bool round = shapes[k].type == ShapeType::Sphere || shapes[k].type == ShapeType::Capsule ||
                         shapes[k].type == ShapeType::Compound;
      EXPECT_LE(most, reach + 1e-5f) << "shape " << k;
      EXPECT_GE(most, reach - (round ? 0.02f : 1e-5f)) << "shape " << k;
    }
  }
  // Twice the direction, twice the reach (the turn projection passes unit normals; others may not).
  const Transform at = xf(Vec3(0.2f, 0.1f, -0.3f), axisAngle(Vec3(1, 2, 3), 0.7f));
  for (const Shape& s : shapes) EXPECT_NEAR(supportAlong(s, at, Vec3(0, 2, 0)), 2.0f * supportAlong(s, at, Vec3::UnitY()), 1e-5f);
  EXPECT_EQ(supportAlong(Shape::plane(Vec3::UnitY(), 0.0f), at, Vec3::UnitY()), std::numeric_limits<float>::infinity());
}

// Every pair of convex shapes, 400 random poses each, overlapping by up to 12 cm along a random
// direction: the deepest point collide reports (margin 0) is never deeper than the bound from the
// overlap along its own normal, along the line between the centres, or along a random direction.
// Along its own normal the bound is also tight for single shapes (within the allowance and 1 mm, but
// where clipping left the deepest vertex out), which is what makes it useful: a pair that ends
// shallow is told so without a collision.
TEST(Support, NoPairRoutineReportsAPointDeeperThanTheOverlapBound) {
  std::mt19937 rng(11);
  const std::vector<Shape> shapes = convexShapes(rng);
  std::uniform_real_distribution<float> overlap(-0.02f, 0.12f);
  int checked = 0, single = 0, tight = 0;
  for (size_t i = 0; i < shapes.size(); ++i)
    for (size_t j = 0; j < shapes.size(); ++j)
      for (int trial = 0; trial < 400; ++trial) {
        const Transform xa = xf(Vec3::Zero(), randomTurn(rng));
        Transform xb = xf(Vec3::Zero(), randomTurn(rng));
        const Vec3 u = randomUnit(rng);
        // Placed along u so that the pair overlaps by the drawn amount along u.
        xb.p = (supportAlong(shapes[i], xa, u) + supportAlong(shapes[j], xb, -u) - overlap(rng)) * u;
        Manifold m;
        if (collide(shapes[i], xa, shapes[j], xb, 0.0f, m) == 0) continue;
        float deepest = -std::numeric_limits<float>::infinity();
        int at = 0;
        for (int p = 0; p < m.count; ++p)
          if (m.points[p].depth > deepest) deepest = m.points[p].depth, at = p;
        const Vec3 normal = m.points[at].normal;
        const Vec3 centres = (xb.p - xa.p).normalized();
        for (const Vec3& n : {normal, centres, u, randomUnit(rng)}) {
          const float bound = depthBoundFromOverlap(overlapAlong(shapes[i], xa, shapes[j], xb, n));
          ASSERT_LE(deepest, bound) << "shapes " << i << ", " << j << " trial " << trial << " along " << n.transpose();
        }
        ++checked;
        // A compound's reach is its farthest part's, not the touching part's: no tightness there.
        if (shapes[i].type == ShapeType::Compound || shapes[j].type == ShapeType::Compound) continue;
        const float alongNormal = overlapAlong(shapes[i], xa, shapes[j], xb, normal);
        ++single;
        tight += depthBoundFromOverlap(alongNormal) <= depthBoundFromOverlap(deepest) + 1e-3f;
      }
  ASSERT_GT(checked, 5000);
  EXPECT_GT(tight, 0.95 * single) << tight << " of " << single;
}

}  // namespace
}  // namespace haif::test
