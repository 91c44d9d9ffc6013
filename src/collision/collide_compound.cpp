// Compound shapes: every pair of parts whose bounds meet is collided by the ordinary pair routines,
// and the points of all of them are reduced to one manifold for the body pair.
#include "collision/collide.h"
#include "collision/collide_pairs.h"
#include "collision/compound.h"
#include "collision/contact_buffer.h"

#include <algorithm>

namespace haif {
namespace detail {

namespace {

// Part indices mixed into a feature id; parts 0 and 0 keep the id as it is, so a compound of one part
// at its centre makes the very manifold its part alone would.
uint32_t partId(uint32_t id, uint32_t partA, uint32_t partB) {
  return id ^ (partA * 0x9E3779B1u) ^ (partB * 0x85EBCA77u);
}

// Candidates of a compound pair, each with the part pair (its group) it came from.
struct GroupedBuffer {
  static constexpr int kCapacity = 64;
  ContactCandidate pts[kCapacity];
  uint32_t group[kCapacity];
  int count = 0;
};

// Points this far apart (m) or closer count as touching when places are handed out: a body's support
// comes first, the speculative points of parts merely near it after.
constexpr float kNearTouch = 0.01f;

// At most 4 of the candidates. Points from one part pair: the usual reduction (deepest, widest area).
// From several: first the deepest point of each touching part pair, deepest pair first, so a body held
// by two parts (a box in a corner of a drum, a table on its legs) keeps a point against each; then the
// touching points farthest from those kept, one place left for the nearest part pair not yet held;
// then the deepest of the rest. A place for every part pair, however far, had a box pressed on a
// turning drum's wall held by one corner while three places went to wall boxes 10-20 cm away (inside
// the drum's spin margin): it rocked from corner to corner, a step each, and worked its way through.
int selectPoints(const GroupedBuffer& in, ContactCandidate* out, uint32_t* outGroup) {
  if (in.count <= kMaxManifoldPoints) {
    std::copy_n(in.pts, in.count, out);
    std::copy_n(in.group, in.count, outGroup);
    return in.count;
  }
  bool oneGroup = true;
  for (int i = 1; i < in.count && oneGroup; ++i) oneGroup = in.group[i] == in.group[0];
  if (oneGroup) {
    const int n = reduceContacts(in.pts, in.count, out);
    std::fill_n(outGroup, n, in.group[0]);
    return n;
  }
  bool taken[GroupedBuffer::kCapacity] = {};
  int n = 0;
  auto take = [&](int i) {
    taken[i] = true;
    out[n] = in.pts[i];
    outGroup[n++] = in.group[i];
  };
  auto held = [&](int i) { return std::find(outGroup, outGroup + n, in.group[i]) != outGroup + n; };
  auto near = [&](int i) { return in.pts[i].depth >= -kNearTouch; };
  // The deepest point not taken (of a group not yet held, touching, if asked); -1 if none.
  auto deepest = [&](bool unheldOnly, bool touchingOnly) {
    int best = -1;
    for (int i = 0; i < in.count; ++i) {
      if (taken[i] || (unheldOnly && held(i)) || (touchingOnly && !near(i))) continue;
      if (best < 0 || in.pts[i].depth > in.pts[best].depth) best = i;
    }
    return best;
  };
  for (int i; n < kMaxManifoldPoints && (i = deepest(true, true)) >= 0;) take(i);
  const int reserve = deepest(true, false) >= 0 ? 1 : 0;
  while (n < kMaxManifoldPoints - reserve) {
    int best = -1;
    float far = -1.0f;
    for (int i = 0; i < in.count; ++i) {
      if (taken[i] || !near(i)) continue;
      float nearest = 1e30f;
      for (int k = 0; k < n; ++k) nearest = std::min(nearest, (in.pts[i].position - out[k].position).squaredNorm());
      if (nearest > far) {
        far = nearest;
        best = i;
      }
    }
    if (best < 0) break;
    take(best);
  }
  if (const int i = deepest(true, false); i >= 0 && n < kMaxManifoldPoints) take(i);
  for (int i; n < kMaxManifoldPoints && (i = deepest(false, false)) >= 0;) take(i);
  return n;
}

void add(GroupedBuffer& buf, const ContactPoint& p, uint32_t id, uint32_t group) {
  // Overlapping parts (the boxes of a drum meet with some overlap) report one touch twice: keep the
  // deeper, so the duplicate does not take one of the manifold's four places.
  for (int i = 0; i < buf.count; ++i) {
    ContactCandidate& c = buf.pts[i];
    if ((c.position - p.position).squaredNorm() < 1e-8f && c.normal.dot(p.normal) > 0.999f) {
      if (p.depth > c.depth) {
        c = ContactCandidate{p.position, p.normal, p.depth, id};
        buf.group[i] = group;
      }
      return;
    }
  }
  if (buf.count == GroupedBuffer::kCapacity) {
    ContactCandidate keep[kMaxManifoldPoints];
    uint32_t keepGroup[kMaxManifoldPoints];
    const int n = selectPoints(buf, keep, keepGroup);
    std::copy_n(keep, n, buf.pts);
    std::copy_n(keepGroup, n, buf.group);
    buf.count = n;
  }
  buf.pts[buf.count] = ContactCandidate{p.position, p.normal, p.depth, id};
  buf.group[buf.count++] = group;
}

// `a` is the compound; `b` any shape (a compound too). Normals from a to b.
int collideWithCompound(const CompoundShape& a, const Transform& xa, const Shape& b, const Transform& xb,
                        float margin, Manifold& m) {
  const Transform rel = xa.inverseTimes(xb);  // b in a's frame: a's part bounds are there already
  const bool bCompound = b.type == ShapeType::Compound;
  const uint32_t partsB = bCompound ? uint32_t(b.compound->parts.size()) : 1u;
  GroupedBuffer buf;
  for (uint32_t j = 0; j < partsB; ++j) {
    const Shape& sb = bCompound ? b.compound->parts[j].shape : b;
    Transform localB = rel, worldB = xb;
    if (bCompound) {
      const Transform& pj = b.compound->parts[j].local;
      localB = Transform{rel.apply(pj.p), rel.q * pj.q};
      worldB = Transform{xb.apply(pj.p), xb.q * pj.q};
    }
    const Aabb boxB = computeAabb(sb, localB).expanded(margin);
    for (uint32_t i = 0; i < uint32_t(a.parts.size()); ++i) {
      const CompoundShape::Part& pa = a.parts[i];
      if (!pa.box.overlaps(boxB)) continue;
      Manifold pm;
      if (collide(pa.shape, Transform{xa.apply(pa.local.p), xa.q * pa.local.q}, sb, worldB, margin, pm) == 0) continue;
      const uint32_t group = i * partsB + j;
      for (int k = 0; k < pm.count; ++k) add(buf, pm.points[k], partId(pm.points[k].id, i, j), group);
    }
  }
  ContactCandidate sel[kMaxManifoldPoints];
  uint32_t selGroup[kMaxManifoldPoints];
  const int n = selectPoints(buf, sel, selGroup);
  for (int i = 0; i < n; ++i) m.points[i] = ContactPoint{sel[i].position, sel[i].normal, sel[i].depth, sel[i].id};
  m.count = n;
  return n;
}

}  // namespace

int collideCompound(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb, float margin,
                    Manifold& m) {
  m.count = 0;
  if (a.type == ShapeType::Compound && a.compound) return collideWithCompound(*a.compound, xa, b, xb, margin, m);
  if (b.type != ShapeType::Compound || !b.compound) return 0;
  const int n = collideWithCompound(*b.compound, xb, a, xa, margin, m);
  for (int i = 0; i < n; ++i) m.points[i].normal = -m.points[i].normal;
  return n;
}

}  // namespace detail
}  // namespace haif
