// Rounded core (sphere centre or capsule segment, plus a radius) against a polyhedron.
// Shallow case (the core does not touch the solid): exact closest points over the polyhedron's faces
// and edges; a capsule lying on a face gets two points. Deep case (the core pierces the solid): SAT on
// the face normals and segment x edge axes, so the normal is still the cheapest way out.
#include "collision/axis_preference.h"
#include "collision/geometry.h"
#include "collision/polytope.h"

#include <algorithm>

namespace haif {
namespace detail {

namespace {

constexpr float kFaceTol = 1e-3f;
// Depth (m) by which the closest point must pass a face's points to be added to them.
constexpr float kDepthAgree = 1e-4f;
// Faces whose planes the closest-point search reads the ends' heights over, kept on the stack.
constexpr int kMaxHeights = 256;
// How far (m) below the highest plane a face's plane may be and still hold an end's closest point:
// insideFace's tolerance lets a foot just past a face's rim count as on it.
constexpr float kHighestTol = 1e-3f;
// An edge whose bound is within this distance (m) of the best is skipped too: a capsule lying over a
// face's edge is as far from it as from the plane, and rounding put every other edge's bound a hair
// under the best (a tie, which either edge wins equally).
constexpr float kNearTie = 1e-6f;

// True when p, on face f's plane, lies inside the face polygon (with a small tolerance).
bool insideFace(const PolyView& P, int f, const Vec3& p) {
  const ConvexHull::Face& F = P.faces[f];
  const int n = int(F.count);
  for (int k = 0; k < n; ++k) {
    const Vec3& a = P.faceVertex(f, k);
    const Vec3& b = P.faceVertex(f, (k + 1) % n);
    if ((b - a).cross(F.normal).dot(p - a) > 1e-6f) return false;
  }
  return true;
}

// Does segment c0-c1 touch the solid? (Cyrus-Beck against the face planes; triangles are flat, so
// for them the plane crossing must also lie inside the triangle.)
bool segmentPierces(const PolyView& P, const Vec3& c0, const Vec3& c1) {
  if (P.flat) {
    const ConvexHull::Face& F = P.faces[0];
    const float d0 = F.normal.dot(c0) - F.offset, d1 = F.normal.dot(c1) - F.offset;
    if ((d0 > 0.0f && d1 > 0.0f) || (d0 < 0.0f && d1 < 0.0f)) return false;
    const float den = d0 - d1;
    const Vec3 x = std::fabs(den) > 1e-12f ? Vec3(c0 + (d0 / den) * (c1 - c0)) : c0;
    return insideFace(P, 0, x);
  }
  float t0 = 0.0f, t1 = 1.0f;
  for (int f = 0; f < P.numFaces; ++f) {
    const ConvexHull::Face& F = P.faces[f];
    const float d0 = F.normal.dot(c0) - F.offset, d1 = F.normal.dot(c1) - F.offset;
    if (d0 > 0.0f && d1 > 0.0f) return false;
    if (d0 > 0.0f) t0 = std::max(t0, d0 / (d0 - d1));
    else if (d1 > 0.0f) t1 = std::min(t1, d0 / (d0 - d1));
    if (t0 > t1) return false;
  }
  return true;
}

// Clips segment [p0, p1] against the side planes of face f. Returns false if nothing is left.
bool clipToFace(const PolyView& P, int f, Vec3& p0, Vec3& p1) {
  const ConvexHull::Face& F = P.faces[f];
  const int n = int(F.count);
  for (int k = 0; k < n; ++k) {
    const Vec3& a = P.faceVertex(f, k);
    const Vec3& b = P.faceVertex(f, (k + 1) % n);
    const Vec3 side = (b - a).cross(F.normal);
    const float d0 = side.dot(p0 - a), d1 = side.dot(p1 - a);
    if (d0 > 0.0f && d1 > 0.0f) return false;
    if (d0 > 0.0f) p0 = p0 + (d0 / (d0 - d1)) * (p1 - p0);
    else if (d1 > 0.0f) p1 = p0 + (d0 / (d0 - d1)) * (p1 - p0);
  }
  return true;
}

// Contacts of the core clipped to face f (poly frame), each at its own height above the face.
int faceContacts(const PolyView& P, int f, const Vec3& c0, const Vec3& c1, bool isSeg, float r, float margin,
                 const Transform& xp, Manifold& m) {
  const ConvexHull::Face& F = P.faces[f];
  Vec3 q0 = c0, q1 = c1;
  if (isSeg && !clipToFace(P, f, q0, q1)) return 0;
  const Vec3 nw = xp.rotate(F.normal);
  const Vec3 pts[2] = {q0, q1};
  int count = 0;
  for (int i = 0; i < (isSeg ? 2 : 1); ++i) {
    const float h = F.normal.dot(pts[i]) - F.offset;
    const float sep = h - r;
    if (sep > margin) continue;
    // Midway between the face (h below the point) and the core surface (r below the point).
    const Vec3 pos = pts[i] - (0.5f * (h + r)) * F.normal;
    m.points[count++] = ContactPoint{xp.apply(pos), nw, -sep, 0x10000u | (uint32_t(f) << 1) | uint32_t(i)};
  }
  m.count = count;
  return count;
}

}  // namespace

int collideCorePoly(const Vec3& w0, const Vec3& w1, float r, const PolyView& P, const Transform& xp, float margin,
                    Manifold& m) {
  m.count = 0;
  const Vec3 c0 = xp.applyInverse(w0), c1 = xp.applyInverse(w1);
  const Vec3 seg = c1 - c0;
  const bool isSeg = seg.squaredNorm() > 1e-12f;
  // The face that kept the pair apart last time first (Manifold::apartAxis): the loop below would
  // stop at it or before it, with the same answer.
  auto beyondFace = [&](int f) {
    const ConvexHull::Face& F = P.faces[f];
    return std::min(F.normal.dot(c0), F.normal.dot(c1)) - F.offset - r;
  };
  const uint32_t apart = m.apartAxis;
  m.apartAxis = kNoApartAxis;
  if (apart < uint32_t(P.numFaces) && beyondFace(int(apart)) > margin) {
    m.apartAxis = apart;
    return 0;
  }
  // How far the core stays beyond each face plane, the largest kept for the deep case below. The
  // whole core beyond one by more than r + margin: no point can be within the margin. Most pairs
  // the broad phase keeps are this far apart, and the closest-feature search costs a pass over
  // every face and edge. The ends' heights over the face planes are kept (up to kMaxHeights faces)
  // for the closest-point search below.
  const bool heightsKept = P.numFaces <= kMaxHeights;
  float above[2][kMaxHeights];
  float highest[2] = {-1e30f, -1e30f};  // each end's greatest height; not kept: every face is tried
  float bestF = -1e30f;
  int face = 0;
  for (int f = 0; f < P.numFaces; ++f) {
    const ConvexHull::Face& F = P.faces[f];
    const float d0 = F.normal.dot(c0), d1 = F.normal.dot(c1);
    if (heightsKept) {
      above[0][f] = d0 - F.offset, above[1][f] = d1 - F.offset;
      highest[0] = std::max(highest[0], above[0][f]);
      highest[1] = std::max(highest[1], above[1][f]);
    }
    const float s = std::min(d0, d1) - F.offset - r;
    if (s > margin) {
      m.apartAxis = uint32_t(f);
      return 0;
    }
    if (s > bestF) { bestF = s; face = f; }
  }

  if (!segmentPierces(P, c0, c1)) {
    // Closest points: endpoint-face, endpoint-edge and segment-edge cover every pair of features.
    // Every point of the solid lies below every face plane, so an end is at least as far from it as
    // it is above the highest plane, and its foot on a face is its closest point only on the planes
    // it is that high above: the other faces are not tried. An edge lies in both its faces' planes,
    // so the core is at least as far from it as the lower end is above either, and from the whole
    // solid as far as above the plane it is highest over: an edge that cannot beat the best so far is
    // skipped. Only a few of a hull's faces and edges are left to try (they were most of a sphere's
    // or capsule's pair with a hull).
    float best = 1e30f;
    Vec3 pc = c0, pp = c0;
    uint32_t id = 0;
    for (int e = 0; e < (isSeg ? 2 : 1); ++e) {
      const Vec3& c = e ? c1 : c0;
      for (int f = 0; f < P.numFaces; ++f) {
        const float h = heightsKept ? above[e][f] : P.faces[f].normal.dot(c) - P.faces[f].offset;
        if (h <= 0.0f || h * h >= best || h < highest[e] - kHighestTol) continue;
        const Vec3 q = c - h * P.faces[f].normal;
        if (!insideFace(P, f, q)) continue;
        best = h * h;
        pc = c;
        pp = q;
        id = 0x20000u | uint32_t(f);
      }
    }
    const bool pruneEdges = heightsKept && P.edgeFaces != nullptr;
    // The core is no nearer the solid than its lower end is above any one face plane (bestF + r is
    // the largest of those heights).
    const float nearest = bestF + r;
    float cut = std::sqrt(best) - kNearTie;  // edges whose bound reaches this cannot win
    for (int k = 0; k < P.numEdges; ++k) {
      if (pruneEdges) {
        const uint32_t f1 = P.edgeFaces[k].first, f2 = P.edgeFaces[k].second;
        const float lower = std::max({std::min(above[0][f1], above[isSeg][f1]),
                                      std::min(above[0][f2], above[isSeg][f2]), nearest});
        if (lower > 0.0f && lower >= cut) continue;
        // From the closest point of an edge the core lies in the edge's normal cone, a positive sum
        // of its two face normals: above one of the two planes at least. An edge the core is
        // nowhere above either face of is not nearest (a sphere off a hull's corner tried every
        // edge, none ruled out before one was found).
        if (std::max({above[0][f1], above[isSeg][f1], above[0][f2], above[isSeg][f2]}) <= 0.0f) continue;
      }
      const Vec3& a = P.verts[P.edges[k].first];
      const Vec3& b = P.verts[P.edges[k].second];
      // The edge lies in the ball about its midpoint through its ends: the core is no nearer it
      // than to that ball. An edge beyond the best so far (with room for rounding) cannot win.
      if (best < 1e30f) {
        const Vec3 mid = 0.5f * (a + b);
        const float toMid = isSeg ? (mid - closestOnSegment(mid, c0, c1)).norm() : (mid - c0).norm();
        if (toMid - 0.5f * (b - a).norm() > (cut + kNearTie) * 1.0001f + 1e-6f) continue;
      }
      Vec3 qc, qp;
      if (isSeg) {
        float s, u;
        closestSegmentSegment(c0, c1, a, b, s, u);
        qc = c0 + s * seg;
        qp = a + u * (b - a);
      } else {
        qc = c0;
        qp = closestOnSegment(c0, a, b);
      }
      const float d2 = (qc - qp).squaredNorm();
      if (d2 < best) {
        best = d2;
        cut = std::sqrt(best) - kNearTie;
        pc = qc;
        pp = qp;
        id = 0x30000u | uint32_t(k);
      }
    }
    const float dist = std::sqrt(best);
    if (dist - r > margin) return 0;
    if (dist > 1e-6f) {
      const Vec3 n = (pc - pp) / dist;
      if (isSeg) {
        // A capsule over a face: a point for each end within the margin of it, the segment clipped
        // to the face. Only a capsule lying flat got two, and a tilted one landing on its low end
        // swung the other end 0.27 m into the ground before the step after saw it.
        int f = 0;
        float al = -2.0f;
        for (int k = 0; k < P.numFaces; ++k) {
          const float d = P.faces[k].normal.dot(n);
          if (d > al) { al = d; f = k; }
        }
        if (al > 1.0f - kFaceTol && faceContacts(P, f, c0, c1, true, r, margin, xp, m) > 0) {
          // The face's points sit at the clipped segment's heights over its plane. A segment whose
          // end hangs past the face's edge and dips below that plane is nearer the edge than any of
          // them: the closest point joins them, else the depth jumped by 1.3 cm as a 1 mm move
          // turned the closest feature from the edge to the face.
          float deepest = m.points[0].depth;
          for (int i = 1; i < m.count; ++i) deepest = std::max(deepest, m.points[i].depth);
          if (r - dist > deepest + kDepthAgree)
            m.points[m.count++] = ContactPoint{xp.apply(0.5f * (pp + pc - r * n)), xp.rotate(n), r - dist, id};
          return m.count;
        }
      }
      const Vec3 pos = 0.5f * (pp + pc - r * n);
      return writeSingle(m, xp.apply(pos), xp.rotate(n), r - dist, id);
    }
  }

  // Deep: SAT over face normals (bestF, above) and segment x edge axes for a capsule.
  float bestE = -1e30f;
  int edge = -1;
  Vec3 axis = Vec3::Zero();
  if (isSeg) {
    for (int k = 0; k < P.numEdges; ++k) {
      const Vec3 d = P.verts[P.edges[k].second] - P.verts[P.edges[k].first];
      Vec3 L = seg.cross(d);
      const float l2 = L.squaredNorm();
      if (l2 < 1e-8f * seg.squaredNorm() * d.squaredNorm()) continue;
      L /= std::sqrt(l2);
      float lo, hi;
      P.interval(L, lo, hi);
      const float a = L.dot(c0), b = L.dot(c1);
      float s = std::min(a, b) - hi;
      if (lo - std::max(a, b) > s) { s = lo - std::max(a, b); L = -L; }
      s -= r;
      if (s > bestE) { bestE = s; edge = k; axis = L; }
    }
  }
  // The polyhedra's face-or-edge rule (axis_preference.h), without its margin share: that was
  // measured on polyhedron landings only.
  if (edge >= 0 && edgeBeatsFace(bestE, bestF, 0.0f)) {
    if (bestE > margin) return 0;
    const Vec3& a = P.verts[P.edges[edge].first];
    const Vec3& b = P.verts[P.edges[edge].second];
    float s, u;
    closestSegmentSegment(c0, c1, a, b, s, u);
    const Vec3 qc = c0 + s * seg, qp = a + u * (b - a);
    // Midway between the two surfaces along the axis (the core sits -bestE - r past the edge).
    const Vec3 pos = 0.5f * (qp + qc - r * axis);
    return writeSingle(m, xp.apply(pos), xp.rotate(axis), -bestE, 0x40000u | uint32_t(edge));
  }
  if (faceContacts(P, face, c0, c1, isSeg, r, margin, xp, m) > 0) return m.count;
  // Nothing of the segment lies over the face: use its deepest end.
  const ConvexHull::Face& F = P.faces[face];
  const Vec3 c = F.normal.dot(c0) <= F.normal.dot(c1) ? c0 : c1;
  return faceContacts(P, face, c, c, false, r, margin, xp, m);
}

}  // namespace detail
}  // namespace haif
