// Helpers shared by the narrow-phase tests.
#pragma once

#include "collision/collide.h"

#include <gtest/gtest.h>

#include <initializer_list>
#include <random>

namespace haif {
namespace test {

inline Transform xf(const Vec3& p, const Quat& q = Quat::Identity()) {
  Transform t;
  t.p = p;
  t.q = q.normalized();
  return t;
}

inline Quat axisAngle(const Vec3& axis, float angle) { return Quat(Eigen::AngleAxisf(angle, axis.normalized())); }

/// A rotation drawn uniformly (a normalised Gaussian quaternion).
inline Quat randomTurn(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

/// The same points, bit for bit: ids, depths, positions and normals.
inline void expectSameContacts(const Manifold& got, const Manifold& want) {
  ASSERT_EQ(got.count, want.count);
  for (int i = 0; i < got.count; ++i) {
    EXPECT_EQ(got.points[i].id, want.points[i].id);
    EXPECT_EQ(got.points[i].depth, want.points[i].depth);
    EXPECT_EQ(got.points[i].position, want.points[i].position);
    EXPECT_EQ(got.points[i].normal, want.points[i].normal);
  }
}

/// Index of the manifold point closest to p (or -1).
inline int findPoint(const Manifold& m, const Vec3& p, float tol) {
  for (int i = 0; i < m.count; ++i)
    if ((m.points[i].position - p).norm() <= tol) return i;
  return -1;
}

inline void expectVecNear(const Vec3& a, const Vec3& b, float tol) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
  EXPECT_NEAR(a.z(), b.z(), tol);
}

/// Every point has the given normal and depth.
inline void expectAll(const Manifold& m, const Vec3& n, float depth, float tol = 1e-4f) {
  for (int i = 0; i < m.count; ++i) {
    expectVecNear(m.points[i].normal, n, tol);
    EXPECT_NEAR(m.points[i].depth, depth, tol);
  }
}

/// A fast pair gets a wide speculative margin, which must never turn an overlap into a gap:
/// `collideAt(margin, m)` collides one pair. `overlapping` says whether it is at least 1 cm deep at
/// margin 0 (else there is nothing to check); the result fails, naming the margin, when it is and
/// one of `margins` reads no overlap.
template <class Collide>
::testing::AssertionResult overlapKeptAtWideMargins(Collide&& collideAt, std::initializer_list<float> margins,
                                                   bool& overlapping) {
  Manifold tight;
  overlapping = collideAt(0.0f, tight) > 0 && tight.deepest() >= 0.01f;
  if (!overlapping) return ::testing::AssertionSuccess();
  for (const float margin : margins) {
    Manifold wide;
    collideAt(margin, wide);
    if (!(wide.deepest() > 0.0f))
      return ::testing::AssertionFailure() << tight.deepest() << " m deep at margin 0, " << wide.count
                                           << " points and no overlap at margin " << margin;
  }
  return ::testing::AssertionSuccess();
}

/// collide() in both orders: the reversed call must give the same points with flipped normals.
inline int collideBoth(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                       Manifold& m) {
  const int n = collide(a, xa, b, xb, margin, m);
  Manifold r;
  const int nr = collide(b, xb, a, xa, margin, r);
  EXPECT_EQ(n, nr);
  for (int i = 0; i < std::min(n, nr); ++i) {
    int k = findPoint(r, m.points[i].position, 1e-4f);
    EXPECT_GE(k, 0) << "reversed call lacks point " << i;
    if (k >= 0) {
      expectVecNear(r.points[k].normal, -m.points[i].normal, 1e-4f);
      EXPECT_NEAR(r.points[k].depth, m.points[i].depth, 1e-4f);
    }
  }
  return n;
}

}  // namespace test
}  // namespace haif
