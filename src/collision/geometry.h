// Small closest-point helpers shared by the pair routines (inline: they sit in inner loops).
#pragma once

#include "core/math.h"

namespace haif {
namespace detail {

/// Closest point to p on segment [a, b].
inline Vec3 closestOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const float dd = d.squaredNorm();
  if (dd < 1e-12f) return a;
  const float t = std::clamp((p - a).dot(d) / dd, 0.0f, 1.0f);
  return a + t * d;
}

/// Closest points between segments [p0, p1] and [q0, q1]: s, t are the parameters (0..1).
inline void closestSegmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, float& s,
                                  float& t) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const float a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const float eps = 1e-12f;
  if (a <= eps && e <= eps) { s = t = 0.0f; return; }
  if (a <= eps) { s = 0.0f; t = std::clamp(f / e, 0.0f, 1.0f); return; }
  const float c = d1.dot(r);
  if (e <= eps) { t = 0.0f; s = std::clamp(-c / a, 0.0f, 1.0f); return; }
  const float b = d1.dot(d2);
  const float denom = a * e - b * b;
  // Parallel segments: any s works; 0 is as good as any, the clamps below settle t and s.
  s = denom > 1e-10f * a * e ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
  t = (b * s + f) / e;
  if (t < 0.0f) { t = 0.0f; s = std::clamp(-c / a, 0.0f, 1.0f); }
  else if (t > 1.0f) { t = 1.0f; s = std::clamp((b - c) / a, 0.0f, 1.0f); }
}

/// Closest point to p on triangle (a, b, c), by the Voronoi region of p. `region` receives
/// 0 for the face interior, 1..3 for vertices a, b, c, 4..6 for edges ab, bc, ca.
inline Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int& region) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0f && d2 <= 0.0f) { region = 1; return a; }
  const Vec3 bp = p - b;
  const float d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0f && d4 <= d3) { region = 2; return b; }
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) { region = 4; return a + (d1 / (d1 - d3)) * ab; }
  const Vec3 cp = p - c;
  const float d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0f && d5 <= d6) { region = 3; return c; }
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) { region = 6; return a + (d2 / (d2 - d6)) * ac; }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    region = 5;
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  region = 0;
  const float denom = 1.0f / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Edge direction d runs along the unit direction u, to within 1e-3 rad: the edges among which an edge
/// contact looks for the one that supports its shape (collidePolyPoly).
inline bool alongEdge(const Vec3& d, const Vec3& u) { return !(d.cross(u).squaredNorm() > 1e-6f * d.squaredNorm()); }

/// Any unit vector perpendicular-safe fallback used when a direction degenerates.
inline Vec3 safeNormalize(const Vec3& v, const Vec3& fallback) {
  const float l2 = v.squaredNorm();
  return l2 > 1e-20f ? Vec3(v / std::sqrt(l2)) : fallback;
}

}  // namespace detail
}  // namespace haif
