// Quickhull in double precision (the hull is built once; robustness matters more than speed):
// start from a tetrahedron of extreme points, repeatedly add the point farthest outside a face,
// replace the faces it sees by a cone over their horizon. Then merge coplanar triangles into
// polygons and integrate mass properties over a fan of tetrahedra.
#include "collision/convex_hull.h"
#include "collision/geometry.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace haif {

namespace {

using V3 = Eigen::Vector3d;

struct Tri {
  int v[3];
  V3 n;
  double d;
  bool alive;
};

struct Hull {
  std::vector<V3> p;
  std::vector<Tri> tris;
  V3 inner;  // a point strictly inside, used to orient faces
  double eps;

  double dist(const Tri& t, int i) const { return t.n.dot(p[size_t(i)]) - t.d; }

  int addTri(int a, int b, int c) {
    Tri t{{a, b, c}, V3::Zero(), 0.0, true};
    V3 n = (p[size_t(b)] - p[size_t(a)]).cross(p[size_t(c)] - p[size_t(a)]);
    const double len = n.norm();
    n = len > 0.0 ? V3(n / len) : V3::UnitX();
    if (n.dot(inner - p[size_t(a)]) > 0.0) {  // keep the interior behind every face
      std::swap(t.v[1], t.v[2]);
      n = -n;
    }
    t.n = n;
    t.d = n.dot(p[size_t(a)]);
    tris.push_back(t);
    return int(tris.size()) - 1;
  }
};

bool fail(std::string* error, const std::string& msg) {
  if (error) *error = msg;
  return false;
}

uint64_t edgeKey(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

}  // namespace

std::shared_ptr<ConvexHull> buildConvexHull(const std::vector<Vec3>& points, std::string* error) {
  const int np = int(points.size());
  if (np < 4) {
    fail(error, "convex hull needs at least 4 points, got " + std::to_string(np));
    return nullptr;
  }
  for (int i = 0; i < np; ++i) {
    if (!isFinite(points[size_t(i)])) {
      fail(error, "convex hull point " + std::to_string(i) + " is not finite");
      return nullptr;
    }
  }
  Hull h;
  h.p.reserve(size_t(np));
  for (const Vec3& v : points) h.p.push_back(v.cast<double>());
  V3 lo = h.p[0], hi = h.p[0];
  for (const V3& v : h.p) { lo = lo.cwiseMin(v); hi = hi.cwiseMax(v); }
  const double size = (hi - lo).maxCoeff();
  h.eps = 1e-6 * std::max(size, hi.cwiseAbs().maxCoeff() * 1e-3);
  if (!(size > 1e-9)) {
    fail(error, "convex hull points all coincide");
    return nullptr;
  }

  // Initial tetrahedron: the farthest pair among the axis extremes, then the farthest point from
  // their line, then the farthest from their plane.
  int ext[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < np; ++i)
    for (int k = 0; k < 3; ++k) {
      if (h.p[size_t(i)][k] < h.p[size_t(ext[2 * k])][k]) ext[2 * k] = i;
      if (h.p[size_t(i)][k] > h.p[size_t(ext[2 * k + 1])][k]) ext[2 * k + 1] = i;
    }
  int i0 = ext[0], i1 = ext[1];
  for (int a = 0; a < 6; ++a)
    for (int b = a + 1; b < 6; ++b)
      if ((h.p[size_t(ext[a])] - h.p[size_t(ext[b])]).squaredNorm() > (h.p[size_t(i0)] - h.p[size_t(i1)]).squaredNorm()) {
        i0 = ext[a];
        i1 = ext[b];
      }
  const V3 dir = (h.p[size_t(i1)] - h.p[size_t(i0)]).normalized();
  int i2 = -1;
  double best = h.eps;
  for (int i = 0; i < np; ++i) {
    const V3 r = h.p[size_t(i)] - h.p[size_t(i0)];
    const double d = (r - r.dot(dir) * dir).norm();
    if (d > best) { best = d; i2 = i; }
  }
  if (i2 < 0) {
    fail(error, "convex hull points are collinear (degenerate)");
    return nullptr;
  }
  const V3 pn = (h.p[size_t(i1)] - h.p[size_t(i0)]).cross(h.p[size_t(i2)] - h.p[size_t(i0)]).normalized();
  int i3 = -1;
  best = h.eps;
  for (int i = 0; i < np; ++i) {
    const double d = std::fabs(pn.dot(h.p[size_t(i)] - h.p[size_t(i0)]));
    if (d > best) { best = d; i3 = i; }
  }
  if (i3 < 0) {
    fail(error, "convex hull points are coplanar (degenerate, no volume)");
    return nullptr;
  }
  h.inner = 0.25 * (h.p[size_t(i0)] + h.p[size_t(i1)] + h.p[size_t(i2)] + h.p[size_t(i3)]);
  h.addTri(i0, i1, i2);
  h.addTri(i0, i1, i3);
  h.addTri(i0, i2, i3);
  h.addTri(i1, i2, i3);

  // Outside sets: each point remembers one face it lies in front of (-1: inside, done).
  std::vector<int> owner(size_t(np), -1);
  auto assign = [&](int i, int firstTri) {
    owner[size_t(i)] = -1;
    for (int t = firstTri; t < int(h.tris.size()); ++t)
      if (h.tris[size_t(t)].alive && h.dist(h.tris[size_t(t)], i) > h.eps) { owner[size_t(i)] = t; return; }
  };
  for (int i = 0; i < np; ++i)
    if (i != i0 && i != i1 && i != i2 && i != i3) assign(i, 0);

  std::vector<int> visible;
  std::vector<std::pair<int, int>> visEdges, horizon;
  for (int iter = 0; iter < np; ++iter) {
    int eye = -1;
    best = 0.0;
    for (int i = 0; i < np; ++i) {
      if (owner[size_t(i)] < 0) continue;
      const double d = h.dist(h.tris[size_t(owner[size_t(i)])], i);
      if (d > best) { best = d; eye = i; }
    }
    if (eye < 0) break;
    visible.clear();
    visEdges.clear();
    horizon.clear();
    for (int t = 0; t < int(h.tris.size()); ++t) {
      Tri& tr = h.tris[size_t(t)];
      if (!tr.alive || h.dist(tr, eye) <= h.eps) continue;
      visible.push_back(t);
      for (int k = 0; k < 3; ++k) visEdges.emplace_back(tr.v[k], tr.v[(k + 1) % 3]);
    }
    for (const auto& e : visEdges) {
      bool shared = false;
      for (const auto& f : visEdges)
        if (f.first == e.second && f.second == e.first) { shared = true; break; }
      if (!shared) horizon.push_back(e);
    }
    for (int t : visible) h.tris[size_t(t)].alive = false;
    const int firstNew = int(h.tris.size());
    for (const auto& e : horizon) h.addTri(e.first, e.second, eye);
    owner[size_t(eye)] = -1;
    for (int i = 0; i < np; ++i) {
      const int o = owner[size_t(i)];
      if (o < 0 || h.tris[size_t(o)].alive) continue;
      assign(i, firstNew);
      if (owner[size_t(i)] < 0) assign(i, 0);  // still outside an older face? keep it
    }
  }

  // Merge coplanar neighbours into polygons: grow each group from a seed triangle while the
  // neighbour's plane matches the seed's (comparing with the seed, not the neighbour, stops a finely
  // tessellated curve from merging into one warped face).
  std::vector<int> alive;
  for (int t = 0; t < int(h.tris.size()); ++t)
    if (h.tris[size_t(t)].alive) alive.push_back(t);
  std::unordered_map<uint64_t, int> edgeTri;
  for (int t : alive)
    for (int k = 0; k < 3; ++k) edgeTri[edgeKey(h.tris[size_t(t)].v[k], h.tris[size_t(t)].v[(k + 1) % 3])] = t;
  std::unordered_map<int, int> group;
  std::vector<std::vector<int>> groups;
  for (int seed : alive) {
    if (group.count(seed)) continue;
    const Tri& s = h.tris[size_t(seed)];
    std::vector<int> members{seed};
    group[seed] = int(groups.size());
    for (size_t q = 0; q < members.size(); ++q) {
      const Tri& t = h.tris[size_t(members[q])];
      for (int k = 0; k < 3; ++k) {
        auto it = edgeTri.find(edgeKey(t.v[(k + 1) % 3], t.v[k]));
        if (it == edgeTri.end() || group.count(it->second)) continue;
        const Tri& u = h.tris[size_t(it->second)];
        bool coplanar = u.n.dot(s.n) > 1.0 - 1e-6;
        for (int j = 0; j < 3 && coplanar; ++j) coplanar = std::fabs(h.dist(s, u.v[j])) <= 4.0 * h.eps;
        if (!coplanar) continue;
        group[it->second] = int(groups.size());
        members.push_back(it->second);
      }
    }
    groups.push_back(std::move(members));
  }

  // Polygon loops: the group's directed edges without their reverse in the group, chained.
  std::vector<std::vector<int>> loops;
  for (const auto& g : groups) {
    std::unordered_map<int, int> next;
    int start = -1;
    size_t boundary = 0;
    for (int t : g)
      for (int k = 0; k < 3; ++k) {
        const int a = h.tris[size_t(t)].v[k], b = h.tris[size_t(t)].v[(k + 1) % 3];
        auto it = edgeTri.find(edgeKey(b, a));
        if (it != edgeTri.end() && group[it->second] == group[g[0]]) continue;
        next[a] = b;
        start = a;
        ++boundary;
      }
    std::vector<int> loop;
    int v = start;
    while (v >= 0 && loop.size() <= boundary) {
      loop.push_back(v);
      auto it = next.find(v);
      v = it == next.end() ? -1 : it->second;
      if (v == start) break;
    }
    if (v != start || loop.size() != boundary) {
      // Not a simple loop (numerically odd input): keep the group's triangles as separate faces.
      for (int t : g) loops.push_back({h.tris[size_t(t)].v[0], h.tris[size_t(t)].v[1], h.tris[size_t(t)].v[2]});
      continue;
    }
    // Drop vertices that sit on a straight run of the boundary.
    std::vector<int> clean;
    const int n = int(loop.size());
    for (int i = 0; i < n; ++i) {
      const V3& a = h.p[size_t(loop[size_t((i + n - 1) % n)])];
      const V3& b = h.p[size_t(loop[size_t(i)])];
      const V3& c = h.p[size_t(loop[size_t((i + 1) % n)])];
      if ((b - a).cross(c - b).norm() > 1e-9 * (b - a).norm() * (c - b).norm()) clean.push_back(loop[size_t(i)]);
    }
    loops.push_back(clean.size() >= 3 ? clean : loop);
  }

  // Mass properties over a fan of tetrahedra from an interior reference point.
  const V3 o = h.inner;
  double vol = 0.0;
  V3 csum = V3::Zero();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& loop : loops)
    for (size_t k = 1; k + 1 < loop.size(); ++k) {
      const V3 a = h.p[size_t(loop[0])] - o, b = h.p[size_t(loop[k])] - o, c = h.p[size_t(loop[k + 1])] - o;
      const double det = a.dot(b.cross(c));
      vol += det / 6.0;
      const V3 s = a + b + c;
      csum += det * s / 24.0;
      cov += det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  if (!(vol > h.eps * size * size)) {
    fail(error, "convex hull has no volume (degenerate point set)");
    return nullptr;
  }
  const V3 com = csum / vol;  // relative to o
  cov -= vol * com * com.transpose();
  const Eigen::Matrix3d inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
  const V3 shift = o + com;  // the input-frame centroid

  auto hull = std::make_shared<ConvexHull>();
  std::unordered_map<int, uint32_t> remap;
  for (const auto& loop : loops) {
    ConvexHull::Face f;
    f.first = uint32_t(hull->faceVertices.size());
    f.count = uint32_t(loop.size());
    V3 nn = V3::Zero();  // Newell normal: robust for slightly non-planar polygons
    for (size_t k = 0; k < loop.size(); ++k) {
      const V3& a = h.p[size_t(loop[k])];
      const V3& b = h.p[size_t(loop[(k + 1) % loop.size()])];
      nn += V3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
    }
    nn.normalize();
    double off = 0.0;
    for (int idx : loop) {
      auto it = remap.find(idx);
      if (it == remap.end()) {
        it = remap.emplace(idx, uint32_t(hull->vertices.size())).first;
        hull->vertices.push_back((h.p[size_t(idx)] - shift).cast<float>());
      }
      hull->faceVertices.push_back(it->second);
      off += nn.dot(h.p[size_t(idx)] - shift);
    }
    f.normal = nn.cast<float>();
    f.offset = float(off / double(loop.size()));
    hull->faces.push_back(f);
  }
  std::unordered_map<uint64_t, bool> seen;
  for (const auto& f : hull->faces)
    for (uint32_t k = 0; k < f.count; ++k) {
      uint32_t a = hull->faceVertices[f.first + k], b = hull->faceVertices[f.first + (k + 1) % f.count];
      if (a > b) std::swap(a, b);
      if (seen.emplace(edgeKey(int(a), int(b)), true).second) hull->edges.emplace_back(a, b);
    }
  // Edges with a direction not seen before go first: the separating-axis test needs only those.
  std::vector<std::pair<uint32_t, uint32_t>> axes, rest;
  for (const auto& e : hull->edges) {
    const Vec3 d = hull->vertices[e.second] - hull->vertices[e.first];
    bool parallel = false;
    for (const auto& x : axes) {
      const Vec3 dx = hull->vertices[x.second] - hull->vertices[x.first];
      if (d.cross(dx).squaredNorm() <= 1e-10f * d.squaredNorm() * dx.squaredNorm()) {
        parallel = true;
        break;
      }
    }
    (parallel ? rest : axes).push_back(e);
  }
  hull->axisEdges = uint32_t(axes.size());
  hull->edges = axes;
  hull->edges.insert(hull->edges.end(), rest.begin(), rest.end());
  // The faces beside each edge: a closed polyhedron has exactly two.
  std::unordered_map<uint64_t, std::vector<uint32_t>> facesOf;
  for (uint32_t fi = 0; fi < hull->faces.size(); ++fi) {
    const auto& f = hull->faces[fi];
    for (uint32_t k = 0; k < f.count; ++k) {
      uint32_t a = hull->faceVertices[f.first + k], b = hull->faceVertices[f.first + (k + 1) % f.count];
      if (a > b) std::swap(a, b);
      facesOf[edgeKey(int(a), int(b))].push_back(fi);
    }
  }
  for (const auto& e : hull->edges) {
    const auto& fs = facesOf[edgeKey(int(e.first), int(e.second))];
    if (fs.size() != 2) {
      hull->edgeFaces.clear();
      break;
    }
    hull->edgeFaces.emplace_back(fs[0], fs[1]);
  }
  hull->parallelEdges = false;
  for (size_t e = 0; e < hull->edges.size() && !hull->parallelEdges; ++e) {
    const auto [a, b] = hull->edges[e];
    const Vec3 dir = (hull->vertices[b] - hull->vertices[a]).normalized();
    for (size_t k = 0; k < hull->edges.size() && !hull->parallelEdges; ++k)
      hull->parallelEdges = k != e && detail::alongEdge(hull->vertices[hull->edges[k].second] - hull->vertices[hull->edges[k].first], dir);
  }
  hull->vertexLanes.resize(3 * size_t(ConvexHull::vertexLaneCount(hull->vertices.size())));
  ConvexHull::fillVertexLanes(hull->vertices.data(), hull->vertices.size(), hull->vertexLanes.data());
  hull->centroid = shift.cast<float>();
  hull->volume = float(vol);
  hull->inertiaPerDensity = inertia.cast<float>();
  return hull;
}

}  // namespace haif
