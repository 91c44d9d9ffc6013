#include "haif/island_split.h"

#include "core/sort_key.h"
#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace haif {

uint32_t StripLayout::criticalRows() const {
  uint32_t even = 0, odd = 0;
  for (uint32_t s = 0; s < strips; ++s) {
    uint32_t& phase = s % 2 == 0 ? even : odd;
    phase = std::max(phase, rows[s]);
  }
  return even + odd + rows[strips];
}

// Puts keys_ in strip order: every key of strips [s0, s) before first(s) and the rest after, for
// each s in (s0, s1), recursing on the middle boundary. Inside a strip the order is left as it falls.
template <class First>
void IslandSplitter::selectBoundaries(uint32_t s0, uint32_t s1, const First& first) {
  if (s1 - s0 < 2) return;
  const uint32_t mid = (s0 + s1) / 2;
  std::nth_element(keys_.begin() + first(s0), keys_.begin() + first(mid), keys_.begin() + first(s1));
  selectBoundaries(s0, mid, first);
  selectBoundaries(mid, s1, first);
}

void IslandSplitter::split(const BodyStore& bodies, const ContactEdge* contacts, const Vec3& up, IslandSet& set,
                           uint32_t k, StripLayout& out) {
  const Island& isl = set.islands[k];
  const uint32_t* ids = set.bodies.data() + isl.firstBody;
  const uint32_t nb = isl.bodyCount;
  const uint32_t strips = std::min(kMaxStrips, std::max(2u, nb / kBodiesPerStrip));
  out.strips = strips;

  // Cut across the widest horizontal world axis (the one least aligned with up is never the
  // vertical one): strips are then columns, and a column keeps its layers in top-down order.
  int vertical = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(up[a]) > std::fabs(up[vertical])) vertical = a;
  int axis = -1;
  float widest = -1.0f;
  for (int a = 0; a < 3; ++a) {
    if (a == vertical) continue;
    float lo = 1e30f, hi = -1e30f;
    for (uint32_t j = 0; j < nb; ++j) {
      const float x = bodies.xf[ids[j]].p[a];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      axis = a;
    }
  }

  // Equal body counts per strip, by rank along the axis (ties by id: deterministic), one integer key
  // per body. Strip s holds ranks [first(s), first(s + 1)), first(s) = ceil(s nb / strips): only the
  // strips' boundaries need finding, not the whole order (a selection per boundary, halving the
  // range each time: n log(strips) work instead of a sort's n log(n)).
  keys_.resize(nb);
  for (uint32_t j = 0; j < nb; ++j) keys_[j] = ascendingKey(bodies.xf[ids[j]].p[axis], ids[j]);
  auto first = [&](uint32_t s) { return uint32_t((uint64_t(s) * nb + strips - 1) / strips); };
  selectBoundaries(0, strips, first);
  if (stripOfBody_.size() < bodies.size()) stripOfBody_.resize(bodies.size());
  for (uint32_t s = 0; s < strips; ++s)
    for (uint32_t r = first(s); r < first(s + 1); ++r) stripOfBody_[keyIndex(keys_[r])] = s;

  // Each contact goes to the lower strip of its island bodies (a static or kinematic end does not
  // count: it is never written); bodies further apart than neighbouring strips go to the tail.
  uint32_t* cs = set.contacts.data() + isl.firstContact;
  const uint32_t nc = isl.contactCount;
  stripOfContact_.resize(nc);
  for (uint32_t s = 0; s <= strips; ++s) out.rows[s] = 0;
  uint32_t count[kMaxStrips + 1] = {};
  for (uint32_t j = 0; j < nc; ++j) {
    const ContactEdge& c = contacts[cs[j]];
    const bool ma = bodies.isAwakeDynamic(c.a), mb = bodies.isAwakeDynamic(c.b);
    const uint32_t sa = ma ? stripOfBody_[c.a] : stripOfBody_[c.b];
    const uint32_t sb = mb ? stripOfBody_[c.b] : sa;
    const uint32_t lo = std::min(sa, sb), hi = std::max(sa, sb);
    const uint32_t s = hi - lo <= 1 ? lo : strips;
    stripOfContact_[j] = s;
    ++count[s];
    out.rows[s] += solverRowsFor(int(c.count));
  }
  out.start[0] = 0;
  for (uint32_t s = 0; s <= strips; ++s) out.start[s + 1] = out.start[s] + count[s];

  // Stable counting sort: the top-down order survives inside every strip.
  uint32_t cursor[kMaxStrips + 1];
  for (uint32_t s = 0; s <= strips; ++s) cursor[s] = out.start[s];
  scratch_.resize(nc);
  for (uint32_t j = 0; j < nc; ++j) scratch_[cursor[stripOfContact_[j]]++] = cs[j];
  std::copy(scratch_.begin(), scratch_.end(), cs);
}

}  // namespace haif
