// Polyhedron against polyhedron (box-hull, hull-hull, triangle-convex). SAT over the face normals of
// both and the cross products of all edge pairs, then clipping of the incident face against the side
// planes of the reference face, or one point between two edges. Computed in A's frame.
#include "collision/axis_preference.h"
#include "collision/clip_polygon.h"
#include "collision/geometry.h"
#include "collision/polytope.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace haif {
namespace detail {

namespace {

// Edges of the second polyhedron kept turned into the first one's frame for the pruned edge test
// (on the stack: collide never allocates); a hull with more takes the unpruned test.
constexpr int kMaxGaussEdges = 256;
// Their Gauss arcs are tested 8 edges at a time: per edge the negated normals c and d of its two
// faces and d × c, one array per coordinate (lanes past the last edge are zero, so they never pass).
constexpr int kGaussLanes = 8;
using GaussF = float __attribute__((vector_size(kGaussLanes * sizeof(float))));
using GaussI = int32_t __attribute__((vector_size(kGaussLanes * sizeof(float))));
struct GaussArcs {
  alignas(32) float c[3][kMaxGaussEdges], d[3][kMaxGaussEdges], dxc[3][kMaxGaussEdges];
  Vec3 p[kMaxGaussEdges], dir[kMaxGaussEdges];  // each edge's first vertex and direction
  int edge[kMaxGaussEdges];                      // its index in the polyhedron
};
inline GaussF loadLanes(const float* x) {
  GaussF v;
  std::memcpy(&v, x, sizeof(v));
  return v;
}
// Bit k set where lane k of the mask is.
inline uint32_t laneBits(GaussI m) {
  uint32_t bits = 0;
  for (int k = 0; k < kGaussLanes; ++k) bits |= uint32_t(m[k] != 0) << k;
  return bits;
}
// A polyhedron's vertices by coordinate, kGaussLanes to a vector: the separating-axis tests project
// every vertex on each axis they try (one vertex after another, each min waiting on the last, that
// was a fifth of a hull pair's time). Past kMaxLaneVerts a hull takes PolyView's loops.
constexpr int kMaxLaneVerts = 64;
static_assert(ConvexHull::kVertexLaneWidth == kGaussLanes, "a hull's vertex lanes are read kGaussLanes at a time");
struct VertexLanes {
  const float *x = nullptr, *y = nullptr, *z = nullptr;
  alignas(32) float own[3 * kMaxLaneVerts];  // a box's (or a hull's made without them), filled per pair
  const PolyView* poly = nullptr;
  int lanes = 0;  // 0: too many vertices

  explicit VertexLanes(const PolyView& P) : poly(&P) {
    if (P.numVerts > kMaxLaneVerts) return;
    lanes = ConvexHull::vertexLaneCount(size_t(P.numVerts));
    if (P.vertexLanes != nullptr) {  // a hull's, made once
      x = P.vertexLanes, y = x + lanes, z = y + lanes;
      return;
    }
    ConvexHull::fillVertexLanes(P.verts, size_t(P.numVerts), own);
    x = own, y = x + lanes, z = y + lanes;
  }
  GaussF project(int j, const Vec3& d) const {
    GaussF px, py, pz;
    std::memcpy(&px, x + j, sizeof(px));
    std::memcpy(&py, y + j, sizeof(py));
    std::memcpy(&pz, z + j, sizeof(pz));
    return px * d.x() + py * d.y() + pz * d.z();
  }
  // Halves folded onto each other: three vector mins, not seven lane extractions.
  static float least(GaussF v) {
    static_assert(kGaussLanes == 8, "the folds below are written for 8 lanes");
    using Half = float __attribute__((vector_size(kGaussLanes / 2 * sizeof(float))));
    Half h = __builtin_shufflevector(v, v, 0, 1, 2, 3);
    const Half g = __builtin_shufflevector(v, v, 4, 5, 6, 7);
    h = g < h ? g : h;
    Half q = __builtin_shufflevector(h, h, 2, 3, 0, 1);
    h = q < h ? q : h;
    q = __builtin_shufflevector(h, h, 1, 0, 3, 2);
    h = q < h ? q : h;
    return h[0];
  }
  float minDot(const Vec3& d) const {
    if (lanes == 0) return poly->minDot(d);
    GaussF lo = project(0, d);
    for (int j = kGaussLanes; j < lanes; j += kGaussLanes) {
      const GaussF p = project(j, d);
      lo = p < lo ? p : lo;
    }
    return least(lo);
  }
  void interval(const Vec3& d, float& lo, float& hi) const {
    if (lanes == 0) return poly->interval(d, lo, hi);
    GaussF l = project(0, d), h = l;
    for (int j = kGaussLanes; j < lanes; j += kGaussLanes) {
      const GaussF p = project(j, d);
      l = p < l ? p : l;
      h = p > h ? p : h;
    }
    lo = least(l);
    hi = -least(-h);
  }
};

// How much farther apart than their separation and the margin two edges may be and still make the
// contact (m).
constexpr float kEdgeGapTol = 1e-3f;
constexpr int kMaxIncident = 64;

// Among the edges parallel to edge e, the one farthest along d (its midpoint). Without parallel edges
// (most hulls) that is e, and the search is skipped (0.7 % of a hull pour's landing).
int supportingEdge(const PolyView& P, int e, const Vec3& d) {
  if (!P.parallelEdges) return e;
  const Vec3 dir = (P.verts[P.edges[e].second] - P.verts[P.edges[e].first]).normalized();
  int best = e;
  float bestDot = -1e30f;
  for (int k = 0; k < P.numEdges; ++k) {
    const Vec3& a = P.verts[P.edges[k].first];
    const Vec3& b = P.verts[P.edges[k].second];
    const Vec3 dk = b - a;
    if (!alongEdge(dk, dir)) continue;
    const float x = d.dot(a + b);
    if (x > bestDot) { bestDot = x; best = k; }
  }
  return best;
}

// The axis of an edge of A (from its point pa, along da) and an edge along db, turned out of A (its
// origin is inside it); false for parallel edges.
bool edgePairAxis(const Vec3& pa, const Vec3& da, const Vec3& db, Vec3& L) {
  L = da.cross(db);
  const float l2 = L.squaredNorm();
  if (l2 < 1e-8f * da.squaredNorm() * db.squaredNorm()) return false;
  L /= std::sqrt(l2);
  if (L.dot(pa) < 0.0f) L = -L;
  return true;
}

// How far B stays beyond A along L (A's frame; B turned by R and moved by t): negative overlaps.
float supportSeparation(const VertexLanes& A, const VertexLanes& B, const Mat3& R, const Vec3& t, const Vec3& L) {
  float aLo, aHi;
  A.interval(L, aLo, aHi);
  return B.minDot(R.transpose() * L) + t.dot(L) - aHi;
}

}  // namespace

int collidePolyPoly(const PolyView& A, const Transform& xa, const PolyView& B, const Transform& xb, float margin,
                    Manifold& m) {
  m.count = 0;
  const Mat3 Ra = xa.q.toRotationMatrix();
  const Mat3 R = Ra.transpose() * xb.q.toRotationMatrix();  // B -> A rotation
  const Vec3 t = Ra.transpose() * (xb.p - xa.p);
  const Mat3 Rt = R.transpose();
  const VertexLanes vertsA(A), vertsB(B);

  // How far B's vertices stay above a plane of A, and A's above a plane of B (in A's frame).
  auto aboveFaceA = [&](int f) {
    const ConvexHull::Face& F = A.faces[f];
    return vertsB.minDot(Rt * F.normal) + t.dot(F.normal) - F.offset;
  };
  auto aboveFaceB = [&](int f) {
    const ConvexHull::Face& F = B.faces[f];
    const Vec3 n = R * F.normal;
    return vertsA.minDot(n) - (F.offset + t.dot(n));
  };
  // The axis that kept the pair apart last time first (Manifold::apartAxis): a face of A, of B
  // (numbered after A's), or an edge pair (kEdgeNote, A's edge, B's edge). A face gives the answer
  // the loops below would: they stop at it or before it. An edge pair's axis may be one the pruned
  // edge search does not try (edges far from the other shape): the pair is then still apart beyond
  // the margin along it, and no point is made where the faces would have left one within the
  // margin (see `reach` below).
  constexpr uint32_t kEdgeNote = 0x40000000u;
  const uint32_t apart = m.apartAxis;
  m.apartAxis = kNoApartAxis;
  if (apart < uint32_t(A.numFaces + B.numFaces)) {
    const int f = int(apart);
    if ((f < A.numFaces ? aboveFaceA(f) : aboveFaceB(f - A.numFaces)) > margin) {
      m.apartAxis = apart;
      return 0;
    }
  }
  if ((apart & 0xC0000000u) == kEdgeNote) {
    const int i = int((apart >> 15) & 0x7FFFu), j = int(apart & 0x7FFFu);
    if (i < A.numEdges && j < B.numEdges) {
      const Vec3 pa = A.verts[A.edges[i].first];
      const Vec3 da = A.verts[A.edges[i].second] - pa;
      const Vec3 db = R * (B.verts[B.edges[j].second] - B.verts[B.edges[j].first]);
      Vec3 L;
      if (edgePairAxis(pa, da, db, L) && supportSeparation(vertsA, vertsB, R, t, L) > margin) {
        m.apartAxis = apart;
        return 0;
      }
    }
  }
  float sepA = -1e30f;
  int faceA = -1;
  for (int f = 0; f < A.numFaces; ++f) {
    const float s = aboveFaceA(f);
    if (s > margin) {
      m.apartAxis = uint32_t(f);
      return 0;
    }
    if (s > sepA) { sepA = s; faceA = f; }
  }
  float sepB = -1e30f;
  int faceB = -1;
  for (int f = 0; f < B.numFaces; ++f) {
    const float s = aboveFaceB(f);
    if (s > margin) {
      m.apartAxis = uint32_t(A.numFaces + f);
      return 0;
    }
    if (s > sepB) { sepB = s; faceB = f; }
  }
  // Edge pairs. With the faces beside every edge known, only pairs whose edges can touch are tried:
  // those whose arcs on the Gauss map cross (a face of the Minkowski difference), where the axis
  // is the edges' cross product turned out of A and the separation is read off two edge points;
  // otherwise one edge per direction, each axis measured over all vertices (far slower: a pair of
  // 20-vertex hulls took 70 us that way).
  float sepE = -1e30f;
  int edgeA = -1, edgeB = -1;
  Vec3 edgeAxis = Vec3::Zero();
  const float bestFaceSep = std::max(sepA, sepB);
  const bool gauss = A.edgeFaces && B.edgeFaces && B.numEdges <= kMaxGaussEdges && B.numVerts <= kMaxGaussEdges;
  // Returns false when an edge axis separates the shapes beyond the margin. `reach` >= 0: only edges
  // that come within reach of the other shape's box are tried (see below); negative: all.
  auto findEdgeAxis = [&](float reach) {
    sepE = -1e30f;
    edgeA = edgeB = -1;
    if (!gauss) {
      for (int i = 0; i < A.numAxisEdges; ++i) {
        const Vec3 da = A.verts[A.edges[i].second] - A.verts[A.edges[i].first];
        for (int j = 0; j < B.numAxisEdges; ++j) {
          const Vec3 dbB = B.verts[B.edges[j].second] - B.verts[B.edges[j].first];
          const Vec3 db = R * dbB;
          Vec3 L = da.cross(db);
          const float l2 = L.squaredNorm();
          if (l2 < 1e-8f * da.squaredNorm() * db.squaredNorm()) continue;  // parallel edges
          L /= std::sqrt(l2);
          float aLo, aHi, bLo, bHi;
          vertsA.interval(L, aLo, aHi);
          vertsB.interval(Rt * L, bLo, bHi);
          const float tl = t.dot(L);
          bLo += tl;
          bHi += tl;
          float s = bLo - aHi;
          if (aLo - bHi > s) { s = aLo - bHi; L = -L; }
          if (s > margin) return false;
          if (s > sepE) { sepE = s; edgeA = i; edgeB = j; edgeAxis = L; }
        }
      }
      return true;
    }
    // B's vertices in A's frame; each shape's box there, and the slabs the best faces of A and of B
    // bound the two shapes to, grown by `reach`: an edge near the other shape is in all of them.
    Vec3 vb[kMaxGaussEdges];
    Aabb boxA, boxB;
    for (int v = 0; v < A.numVerts; ++v) boxA.include(A.verts[v]);
    for (int v = 0; v < B.numVerts; ++v) boxB.include(vb[v] = R * B.verts[v] + t);
    const float grow = reach >= 0.0f ? reach : 1e30f;
    boxA = boxA.expanded(grow);
    boxB = boxB.expanded(grow);
    // Along A's face: A below its plane (offset oA), B above oA + sepA; along B's (n, turned into A's
    // frame): B below oB, A above oB + sepB.
    const Vec3 nA = faceA >= 0 ? A.faces[faceA].normal : Vec3::Zero();
    const Vec3 nB = faceB >= 0 ? Vec3(R * B.faces[faceB].normal) : Vec3::Zero();
    const float oA = faceA >= 0 ? A.faces[faceA].offset : 0.0f;
    const float oB = faceB >= 0 ? B.faces[faceB].offset + t.dot(nB) : 0.0f;
    // Which of the other shape's limits each vertex lies beyond (its box's six sides and the slab's
    // two): an edge is near the other shape unless both its ends lie beyond one limit. Read per vertex
    // once, not per edge (each vertex ends three or more edges).
    auto beyond = [](const Aabb& box, float d1, float lim1, float d2, float lim2, const Vec3& p) {
      return uint32_t(p.x() < box.lo.x()) | uint32_t(p.x() > box.hi.x()) << 1 | uint32_t(p.y() < box.lo.y()) << 2 |
             uint32_t(p.y() > box.hi.y()) << 3 | uint32_t(p.z() < box.lo.z()) << 4 | uint32_t(p.z() > box.hi.z()) << 5 |
             uint32_t(d1 > lim1) << 6 | uint32_t(d2 < lim2) << 7;
    };
    uint8_t offB[kMaxGaussEdges];  // B's vertices beyond A's limits
    for (int v = 0; v < B.numVerts; ++v)
      offB[v] = uint8_t(beyond(boxA, nA.dot(vb[v]), oA + grow, nB.dot(vb[v]), oB + sepB - grow, vb[v]));
    // A's vertices beyond B's limits (A's slab is its face's, B's is the other way round); a hull too
    // large for the array reads each edge's ends as it comes.
    const bool flagsA = A.numVerts <= kMaxGaussEdges;
    uint8_t offA[kMaxGaussEdges];
    auto offOfA = [&](const Vec3& p) {
      return beyond(boxB, -nA.dot(p), -(oA + sepA - grow), -nB.dot(p), -(oB + grow), p);
    };
    for (int v = 0; flagsA && v < A.numVerts; ++v) offA[v] = uint8_t(offOfA(A.verts[v]));
    auto nearB = [&](int i) {  // an edge of A near B
      const uint32_t a0 = A.edges[i].first, a1 = A.edges[i].second;
      return flagsA ? (offA[a0] & offA[a1]) == 0 : (offOfA(A.verts[a0]) & offOfA(A.verts[a1])) == 0;
    };
    // B's edges near A, each with its two face normals negated (the Gauss map of -B).
    // The near edges' indices are gathered first without a branch (whether an edge is near follows no
    // pattern: a mispredicted branch an edge cost more than the test), then only they are read.
    GaussArcs gb;
    int kept = 0;
    for (int j = 0; j < B.numEdges; ++j) {
      gb.edge[kept] = j;
      kept += (offB[B.edges[j].first] & offB[B.edges[j].second]) == 0;
    }
    for (int e = 0; e < kept; ++e) {
      const int j = gb.edge[e];
      const Vec3& q0 = vb[B.edges[j].first];
      const Vec3 c = -(R * B.faces[B.edgeFaces[j].first].normal);
      const Vec3 d = -(R * B.faces[B.edgeFaces[j].second].normal);
      const Vec3 dxc = d.cross(c);
      for (int k = 0; k < 3; ++k) {
        gb.c[k][e] = c[k];
        gb.d[k][e] = d[k];
        gb.dxc[k][e] = dxc[k];
      }
      gb.p[e] = q0;
      gb.dir[e] = R * (B.verts[B.edges[j].second] - B.verts[B.edges[j].first]);  // one rounding, not q1 - q0
    }
    const int lanesB = (kept + kGaussLanes - 1) / kGaussLanes * kGaussLanes;
    for (int j = kept; j < lanesB; ++j)
      for (int k = 0; k < 3; ++k) gb.c[k][j] = gb.d[k][j] = gb.dxc[k][j] = 0.0f;
    // A's edge i against the kept edges of B; false when an axis separates beyond the margin.
    auto tryEdgeA = [&](int i) {
      const Vec3 pa = A.verts[A.edges[i].first], pa1 = A.verts[A.edges[i].second];
      const Vec3& a = A.faces[A.edgeFaces[i].first].normal;
      const Vec3& b = A.faces[A.edgeFaces[i].second].normal;
      const Vec3 da = pa1 - pa;
      const Vec3 bxa = b.cross(a);
      for (int j0 = 0; j0 < lanesB; j0 += kGaussLanes) {
        auto dot = [&](const float (*x)[kMaxGaussEdges], const Vec3& v) {
          return loadLanes(x[0] + j0) * v.x() + loadLanes(x[1] + j0) * v.y() + loadLanes(x[2] + j0) * v.z();
        };
        const GaussF cba = dot(gb.c, bxa), dba = dot(gb.d, bxa), adc = dot(gb.dxc, a), bdc = dot(gb.dxc, b);
        const GaussF zero = {};
        const GaussI cross = (cba * dba < zero) & (adc * bdc < zero) & (cba * bdc > zero);
        for (uint32_t lanes = laneBits(cross); lanes != 0; lanes &= lanes - 1) {
          const int k = j0 + __builtin_ctz(lanes);
          Vec3 L;
          if (!edgePairAxis(pa, da, gb.dir[k], L)) continue;
          float s = L.dot(gb.p[k] - pa);
          if (s <= sepE && s <= margin) continue;
          // The two edges' lines are this far apart; that is the shapes' separation along L only
          // when the arcs truly cross. Where they barely do (a hull lying flat on a face: its face's
          // negated normal is the other's face normal to float precision) the sign tests are noise,
          // and over a long edge a tilt of 1e-5 put a hull 6 mm above a 1000 m ground box it rested
          // on: the edge contact won and made one point 250 m away. The supports decide instead.
          s = supportSeparation(vertsA, vertsB, R, t, L);
          if (s > margin) {
            if (i < 0x8000 && gb.edge[k] < 0x8000) m.apartAxis = kEdgeNote | uint32_t(i) << 15 | uint32_t(gb.edge[k]);
            return false;
          }
          if (s > sepE) { sepE = s; edgeA = i; edgeB = gb.edge[k]; edgeAxis = L; }
        }
      }
      return true;
    };
    // A's near edges gathered a chunk at a time, the same way as B's.
    constexpr int kChunk = 64;
    int nearEdgesA[kChunk];
    for (int i0 = 0; i0 < A.numEdges && kept > 0; i0 += kChunk) {
      const int i1 = std::min(A.numEdges, i0 + kChunk);
      int nearCount = 0;
      for (int i = i0; i < i1; ++i) {
        nearEdgesA[nearCount] = i;
        nearCount += nearB(i);
      }
      for (int e = 0; e < nearCount; ++e)
        if (!tryEdgeA(nearEdgesA[e])) return false;
    }
    return true;
  };
  // An edge pair makes the contact only when its axis beats the faces (sepE > bestFaceSep) without
  // separating them (sepE <= margin), and edgeContact takes it only when its edges lie within
  // |sepE| + margin + kEdgeGapTol of each other: an edge farther than max(-bestFaceSep, margin) +
  // margin + kEdgeGapTol from the other shape never makes the contact, and is not tried. (Were such
  // a pair's axis to separate the shapes, the faces may then leave a point within the margin where
  // there was none.) In a pile most of a hull's edges are that far from a neighbour; the edge pairs
  // were three quarters of a touching hull pair's time.
  constexpr float kNearSlack = 1e-3f;  // m: float noise in the boxes
  float reach = std::max(-bestFaceSep, margin) + margin + kEdgeGapTol + kNearSlack;
  if (!gauss) reach = -1.0f;  // every pair is tried
  if (!findEdgeAxis(reach)) return 0;
  if (faceA < 0 && faceB < 0) return 0;

  const bool refIsB = faceB >= 0 && (faceA < 0 || sepB > sepA + kFaceBTol);
  const float faceSep = refIsB ? sepB : sepA;
  // Edge-edge: one point between the closest points of the two edges, `sep` apart along the edge axis.
  auto edgeContact = [&](float sep) {
    // The axis came from the first edge pair with that direction; the touching edges are the
    // parallel ones that support A along +L and B along -L.
    const Vec3 L = edgeAxis, Lb = Rt * edgeAxis;
    edgeA = supportingEdge(A, edgeA, L);
    edgeB = supportingEdge(B, edgeB, -Lb);
    const Vec3 a0 = A.verts[A.edges[edgeA].first], a1 = A.verts[A.edges[edgeA].second];
    const Vec3 b0 = R * B.verts[B.edges[edgeB].first] + t, b1 = R * B.verts[B.edges[edgeB].second] + t;
    float s, u;
    closestSegmentSegment(a0, a1, b0, b1, s, u);
    const Vec3 qa = a0 + s * (a1 - a0), qb = b0 + u * (b1 - b0);
    // Edges that touch are |sepE| apart; ones farther apart than the margin allows are not the
    // touching ones, and a point between them would push from where nothing touches.
    const float gap = std::fabs(sepE) + margin + kEdgeGapTol;
    if ((qb - qa).squaredNorm() > gap * gap) return -1;
    const uint32_t id = 0x40000000u | ((uint32_t(edgeA) & 0x7FFFu) << 15) | (uint32_t(edgeB) & 0x7FFFu);
    return writeSingle(m, xa.apply(0.5f * (qa + qb)), Ra * edgeAxis, -sep, id);
  };
  if (edgeA >= 0 && edgeBeatsFace(sepE, faceSep, margin)) {
    const int count = edgeContact(sepE);
    if (count >= 0) return count;
  }

  // Reference face (in A's frame) and the incident face: the other's most anti-parallel face.
  const PolyView& ref = refIsB ? B : A;
  const PolyView& inc = refIsB ? A : B;
  const int rf = refIsB ? faceB : faceA;
  const ConvexHull::Face& RF = ref.faces[rf];
  const Vec3 nRef = refIsB ? Vec3(R * RF.normal) : RF.normal;
  const float offRef = refIsB ? RF.offset + t.dot(nRef) : RF.offset;
  // Incident face normals live in inc's frame: bring nRef there.
  const Vec3 nInInc = refIsB ? nRef : Vec3(Rt * nRef);
  // The incident face is the most anti-parallel among the faces that hold inc's deepest vertex along
  // -nRef. The most anti-parallel face of all may not hold it (a vertex with a long thin normal cone),
  // and then every clipped point lies higher than that vertex: the contact came out too far, or beyond
  // the margin with nothing left to clip (a pile hull over the ground got a 5 m deep edge fallback).
  int deepestVert = 0;
  float lowest = 1e30f;
  for (int v = 0; v < inc.numVerts; ++v) {
    const float d = inc.verts[v].dot(nInInc);
    if (d < lowest) { lowest = d; deepestVert = v; }
  }
  int incFace = 0;
  float best = 1e30f;
  for (int f = 0; f < inc.numFaces; ++f) {
    const ConvexHull::Face& F = inc.faces[f];
    const float d = F.normal.dot(nInInc);
    if (d >= best) continue;
    const uint32_t* fv = inc.faceVerts + F.first;
    if (std::find(fv, fv + F.count, uint32_t(deepestVert)) == fv + F.count) continue;
    best = d;
    incFace = f;
  }

  ClipPoint bufA[kMaxClipVerts], bufB[kMaxClipVerts];
  const int nInc = std::min<int>(int(inc.faces[incFace].count), kMaxIncident);
  for (int k = 0; k < nInc; ++k) {
    const Vec3& v = inc.faceVertex(incFace, k);
    bufA[k] = ClipPoint{refIsB ? v : Vec3(R * v + t), uint16_t(k), uint8_t(k & 0x7F)};
  }
  int n = nInc;
  ClipPoint* cur = bufA;
  ClipPoint* nxt = bufB;
  const int nRefV = int(RF.count);
  for (int k = 0; k < nRefV && n > 0; ++k) {
    const Vec3& v0 = ref.faceVertex(rf, k);
    const Vec3& v1 = ref.faceVertex(rf, (k + 1) % nRefV);
    const Vec3 p0 = refIsB ? Vec3(R * v0 + t) : v0;
    const Vec3 p1 = refIsB ? Vec3(R * v1 + t) : v1;
    const Vec3 side = (p1 - p0).cross(nRef);  // outward for a CCW face
    const float len = side.norm();
    if (len < 1e-12f) continue;
    n = clipPolygon(cur, n, nxt, side / len, side.dot(p0) / len, uint32_t(k));
    std::swap(cur, nxt);
  }

  const Vec3 nWorld = Ra * (refIsB ? Vec3(-nRef) : nRef);
  const uint32_t idBase = (refIsB ? 0x80000000u : 0u) | ((uint32_t(rf) & 0x7Fu) << 23) |
                          ((uint32_t(incFace) & 0x7Fu) << 16);
  ContactBuffer buf;
  for (int i = 0; i < n; ++i) {
    const float s = nRef.dot(cur[i].p) - offRef;
    if (s > margin) continue;
    buf.add(xa.apply(cur[i].p - (0.5f * s) * nRef), nWorld, -s, idBase | cur[i].fid);
  }
  // Clipping can leave nothing when the faces only meet at a rim (thin triangles): use the edges then.
  // No axis is deeper than the face axis's separation (SAT keeps the largest), so neither is the contact.
  // The edges far from the other shape were not tried (reach): they may hold the pair used here.
  if (buf.count == 0 && reach >= 0.0f && !findEdgeAxis(-1.0f)) return 0;
  if (buf.count == 0 && edgeA >= 0 && sepE <= margin) return std::max(0, edgeContact(std::max(sepE, faceSep)));
  return writeManifold(buf, m);
}

}  // namespace detail
}  // namespace haif
