// Contact reduction: keep the points that best hold the two bodies, i.e. the deepest one (it has
// the largest error to fix) and those spanning the largest area (they resist rotation).
#include "collision/contact_buffer.h"

namespace haif {
namespace detail {

namespace {

// Spread is measured across the contact (along the surfaces), never along the normal: a box thinner
// than the speculative margin has all 8 corners in reach of a plane, and its top corners, half its
// thickness farther in 3D, displaced a bottom corner (a Jenga block of 1.5 cm stood on 3 points
// and a real-size tower fell at 10 iterations). Candidates that spread the patch equally (a top
// corner above a bottom one) go to the deeper.
bool spreadsMore(float score, float depth, float bestScore, float bestDepth) {
  const float tie = 1e-4f * bestScore;
  return score > bestScore + tie || (score >= bestScore - tie && depth > bestDepth);
}

}  // namespace

int reduceContacts(const ContactCandidate* pts, int count, ContactCandidate* out) {
  if (count <= kMaxManifoldPoints) {
    for (int i = 0; i < count; ++i) out[i] = pts[i];
    return count;
  }
  float maxDepth = -1e30f;
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    maxDepth = std::max(maxDepth, pts[i].depth);
    centre += pts[i].position;
  }
  centre /= float(count);

  // 1: deepest; among (nearly) equally deep points take the one farthest from the patch centre so
  // that a flat resting patch keeps its corners rather than an arbitrary inner point.
  const float depthTol = 1e-3f;
  int i1 = 0;
  float best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (pts[i].depth < maxDepth - depthTol) continue;
    const float d = (pts[i].position - centre).squaredNorm();
    if (d > best) { best = d; i1 = i; }
  }
  const Vec3 p1 = pts[i1].position;
  const Vec3 n = pts[i1].normal;

  // 2: farthest from the first, across the normal.
  int i2 = -1;
  best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (i == i1) continue;
    const Vec3 r = pts[i].position - p1;
    const float d = (r - r.dot(n) * n).squaredNorm();
    if (i2 < 0 || spreadsMore(d, pts[i].depth, best, pts[i2].depth)) { best = d; i2 = i; }
  }
  const Vec3 p2 = pts[i2].position;

  // 3: largest triangle with the first two.
  int i3 = -1;
  float signedArea3 = 0.0f;
  best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (i == i1 || i == i2) continue;
    const float a = (p2 - p1).cross(pts[i].position - p1).dot(n);
    if (i3 < 0 || spreadsMore(std::fabs(a), pts[i].depth, best, pts[i3].depth)) { best = std::fabs(a); i3 = i; signedArea3 = a; }
  }
  // Orient the triangle counter-clockwise about n so "outside an edge" is a negative area.
  int t0 = i1, t1 = i2, t2 = i3;
  if (signedArea3 < 0.0f) std::swap(t1, t2);
  const Vec3 a = pts[t0].position, b = pts[t1].position, c = pts[t2].position;

  // 4: the point that adds the most area outside the triangle.
  int i4 = -1;
  best = 0.0f;
  for (int i = 0; i < count; ++i) {
    if (i == i1 || i == i2 || i == i3) continue;
    const Vec3& p = pts[i].position;
    const float e0 = (b - a).cross(p - a).dot(n);
    const float e1 = (c - b).cross(p - b).dot(n);
    const float e2 = (a - c).cross(p - c).dot(n);
    const float added = -std::min(e0, std::min(e1, e2));
    if (added > 0.0f && (i4 < 0 || spreadsMore(added, pts[i].depth, best, pts[i4].depth))) { best = added; i4 = i; }
  }
  out[0] = pts[i1];
  out[1] = pts[i2];
  out[2] = pts[i3];
  if (i4 < 0) return 3;
  out[3] = pts[i4];
  return 4;
}

int writeManifold(const ContactBuffer& buf, Manifold& m) {
  ContactCandidate sel[kMaxManifoldPoints];
  const int n = reduceContacts(buf.pts, buf.count, sel);
  for (int i = 0; i < n; ++i) m.points[i] = ContactPoint{sel[i].position, sel[i].normal, sel[i].depth, sel[i].id};
  m.count = n;
  return n;
}

}  // namespace detail
}  // namespace haif
