// Static plane against convex shapes. The plane is the first shape, so normals are the plane normal.
// Points are the convex shape's deepest features (vertices, sphere ends), each with its own id.
#include "collision/collide_pairs.h"
#include "collision/contact_buffer.h"

namespace haif {
namespace detail {

namespace {

struct WorldPlane {
  Vec3 n;
  float d;
};

WorldPlane worldPlane(const Shape& p, const Transform& xp) {
  WorldPlane w;
  w.n = xp.rotate(p.planeNormal);
  w.d = p.planeOffset + w.n.dot(xp.p);
  return w;
}

// One sphere (centre c, radius r) against the plane; adds a candidate when within margin.
void addSphere(const WorldPlane& pl, const Vec3& c, float r, float margin, uint32_t id, ContactBuffer& buf) {
  const float s = pl.n.dot(c) - pl.d - r;
  if (s > margin) return;
  // Midway between the sphere's lowest point and its projection on the plane.
  const Vec3 low = c - r * pl.n;
  buf.add(low - (0.5f * s) * pl.n, pl.n, -s, id);
}

}  // namespace

int collidePlaneSphere(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                       Manifold& m) {
  ContactBuffer buf;
  addSphere(worldPlane(a, xa), xb.p, b.radius, margin, 0, buf);
  return writeManifold(buf, m);
}

int collidePlaneCapsule(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                        Manifold& m) {
  const WorldPlane pl = worldPlane(a, xa);
  const Vec3 axis = xb.rotate(Vec3(0.0f, b.halfHeight, 0.0f));
  ContactBuffer buf;
  addSphere(pl, xb.p - axis, b.radius, margin, 0, buf);
  addSphere(pl, xb.p + axis, b.radius, margin, 1, buf);
  return writeManifold(buf, m);
}

int collidePlaneBox(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                    Manifold& m) {
  m.count = 0;
  const WorldPlane pl = worldPlane(a, xa);
  const Mat3 R = xb.q.toRotationMatrix();
  const Vec3 nb = R.transpose() * pl.n;  // plane normal in the box frame
  const Vec3& h = b.halfExtents;
  const float centre = pl.n.dot(xb.p) - pl.d;
  if (centre - h.dot(nb.cwiseAbs()) > margin) return 0;  // even the lowest corner is too far
  ContactCandidate cand[8];
  int n = 0;
  for (uint32_t v = 0; v < 8; ++v) {
    const Vec3 local((v & 1) ? h.x() : -h.x(), (v & 2) ? h.y() : -h.y(), (v & 4) ? h.z() : -h.z());
    const float s = centre + nb.dot(local);
    if (s > margin) continue;
    const Vec3 w = xb.p + R * local;
    cand[n++] = ContactCandidate{w - (0.5f * s) * pl.n, pl.n, -s, v};
  }
  ContactCandidate sel[kMaxManifoldPoints];
  const int ns = reduceContacts(cand, n, sel);
  for (int i = 0; i < ns; ++i) m.points[i] = ContactPoint{sel[i].position, sel[i].normal, sel[i].depth, sel[i].id};
  m.count = ns;
  return ns;
}

int collidePlaneHull(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                     Manifold& m) {
  const WorldPlane pl = worldPlane(a, xa);
  const Mat3 R = xb.q.toRotationMatrix();
  const Vec3 nb = R.transpose() * pl.n;
  const float centre = pl.n.dot(xb.p) - pl.d;
  const ConvexHull& hull = *b.hull;
  ContactBuffer buf;
  for (size_t v = 0; v < hull.vertices.size(); ++v) {
    const float s = centre + nb.dot(hull.vertices[v]);
    if (s > margin) continue;
    buf.add(xb.p + R * hull.vertices[v] - (0.5f * s) * pl.n, pl.n, -s, uint32_t(v));
  }
  return writeManifold(buf, m);
}

}  // namespace detail
}  // namespace haif
