// A sphere or capsule near a polyhedron, not touching its solid: the contact's depth is the radius
// less the distance from the core to the solid. collideCorePoly tries only the faces and edges that
// can hold the closest point; that must find what every triangle of every face finds.
#include "collision/convex_hull.h"
#include "collision/geometry.h"
#include "collision/polytope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

namespace haif {
namespace detail {
namespace {

// Distance from segment c0-c1 to a triangle it does not cross: from an end to the triangle, or
// between the segment and an edge of the triangle.
float segmentTriangleDistance(const Vec3& c0, const Vec3& c1, const Vec3& a, const Vec3& b, const Vec3& c) {
  int region = 0;
  float best = std::min((closestOnTriangle(c0, a, b, c, region) - c0).norm(), (closestOnTriangle(c1, a, b, c, region) - c1).norm());
  const Vec3 corners[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = corners[k];
    const Vec3& q = corners[(k + 1) % 3];
    float s, u;
    closestSegmentSegment(c0, c1, p, q, s, u);
    best = std::min(best, (c0 + s * (c1 - c0) - (p + u * (q - p))).norm());
  }
  return best;
}

// Distance from the segment to the hull's surface, over every face cut into a fan of triangles.
float distanceToHull(const ConvexHull& h, const Vec3& c0, const Vec3& c1) {
  float best = 1e30f;
  for (const ConvexHull::Face& f : h.faces) {
    const Vec3& v0 = h.vertices[h.faceVertices[f.first]];
    for (uint32_t k = 1; k + 1 < f.count; ++k)
      best = std::min(best, segmentTriangleDistance(c0, c1, v0, h.vertices[h.faceVertices[f.first + k]],
                                                    h.vertices[h.faceVertices[f.first + k + 1]]));
  }
  return best;
}

bool inside(const ConvexHull& h, const Vec3& p) {
  for (const ConvexHull::Face& f : h.faces)
    if (f.normal.dot(p) > f.offset) return false;
  return true;
}

TEST(CorePolyClosest, SpheresAndCapsulesNearRandomHullsAreAsDeepAsTheirDistanceSays) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  constexpr float kMargin = 0.02f;
  int compared = 0, capsules = 0, overlapping = 0;
  for (int shapes = 0; shapes < 6; ++shapes) {
    std::vector<Vec3> pts;
    const int n = 12 + int(rng() % 19);
    for (int i = 0; i < n; ++i) pts.emplace_back(0.3f * u(rng), 0.2f * u(rng), 0.25f * u(rng));
    const auto hull = buildConvexHull(pts, nullptr);
    ASSERT_TRUE(hull);
    const PolyView P = hullView(*hull);
    for (int trial = 0; trial < 400; ++trial) {
      const float r = 0.05f + 0.2f * std::fabs(u(rng));
      const float half = trial % 2 ? 0.05f + 0.25f * std::fabs(u(rng)) : 0.0f;
      const Vec3 axis = half * Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      // Out along dir to where the core starts to touch, then from 3 cm apart to a third of r deep.
      float in = 0.0f, out = 2.0f;
      for (int k = 0; k < 30; ++k) {
        const Vec3 c = 0.5f * (in + out) * dir;
        const bool pierced = inside(*hull, c - axis) || inside(*hull, c + axis);
        (pierced || distanceToHull(*hull, c - axis, c + axis) < r ? in : out) = 0.5f * (in + out);
      }
      const Vec3 centre = (out + (0.03f + r / 3.0f) * 0.5f * (u(rng) + 1.0f) - r / 3.0f) * dir;
      const Vec3 c0 = centre - axis, c1 = centre + axis;
      if (inside(*hull, c0) || inside(*hull, c1)) continue;
      const float dist = distanceToHull(*hull, c0, c1);
      if (dist < 1e-3f) continue;  // the core may cross a face: the deep case, not this one
      Manifold m;
      collideCorePoly(c0, c1, r, P, Transform{}, kMargin, m);
      if (dist - r > kMargin) {
        EXPECT_EQ(m.count, 0) << "hull " << shapes << ", trial " << trial;
        continue;
      }
      ASSERT_GT(m.count, 0) << "hull " << shapes << ", trial " << trial << ": " << dist - r << " m apart";
      float deepest = -1e30f;
      for (int k = 0; k < m.count; ++k) deepest = std::max(deepest, m.points[k].depth);
      // A face merged from nearly coplanar triangles lies within a few eps of its points, not on
      // them: the two measures agree to 0.1 mm (the closest point taken from the wrong feature is
      // off by far more).
      EXPECT_NEAR(deepest, r - dist, 1e-4f) << "hull " << shapes << ", trial " << trial;
      ++compared;
      capsules += half > 0.0f;
      overlapping += dist < r;
    }
  }
  EXPECT_GT(compared, 1500) << "test set-up: most trials must be within the margin";
  EXPECT_GT(capsules, 700);
  EXPECT_GT(overlapping, 700);
}

}  // namespace
}  // namespace detail
}  // namespace haif
