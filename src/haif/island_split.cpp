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

void IslandSplitter::selectMiddle(uint32_t s0, uint32_t s1, uint32_t nb, uint32_t strips) {
  const uint32_t mid = (s0 + s1) / 2;
  std::nth_element(keys_.begin() + firstRank(s0, nb, strips), keys_.begin() + firstRank(mid, nb, strips),
                   keys_.begin() + firstRank(s1, nb, strips));
}

void IslandSplitter::spanBodies(const BodyStore& bodies, const uint32_t* ids, uint32_t nb, int vertical, uint32_t c) {
  float* span = span_.data() + size_t(c) * 6;
  for (int a = 0; a < 3; ++a) {
    float lo = 1e30f, hi = -1e30f;
    if (a != vertical)
      for (uint32_t j = c * kChunk; j < std::min(nb, (c + 1) * kChunk); ++j) {
        const float x = bodies.xf[ids[j]].p[a];
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    span[2 * a] = lo;
    span[2 * a + 1] = hi;
  }
}

int IslandSplitter::cutAxis(int vertical, uint32_t bodyChunks) const {
  int axis = -1;
  float widest = -1.0f;
  for (int a = 0; a < 3; ++a) {
    if (a == vertical) continue;
    float lo = 1e30f, hi = -1e30f;
    for (uint32_t c = 0; c < bodyChunks; ++c) {
      lo = std::min(lo, span_[size_t(c) * 6 + 2 * a]);
      hi = std::max(hi, span_[size_t(c) * 6 + 2 * a + 1]);
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      axis = a;
    }
  }
  return axis;
}

void IslandSplitter::keyBodies(const BodyStore& bodies, const uint32_t* ids, uint32_t nb, int axis, uint32_t c) {
  for (uint32_t j = c * kChunk; j < std::min(nb, (c + 1) * kChunk); ++j)
    keys_[j] = ascendingKey(bodies.xf[ids[j]].p[axis], ids[j]);
}

// A contact goes to the lower strip of its island bodies (a static or kinematic end does not count:
// it is never written); bodies further apart than neighbouring strips go to the tail.
void IslandSplitter::classifyContacts(const BodyStore& bodies, const ContactEdge* contacts, const uint32_t* cs,
                                      uint32_t nc, uint32_t strips, uint32_t c) {
  uint32_t* count = count_.data() + size_t(c) * (kMaxStrips + 1);
  uint32_t* rows = rows_.data() + size_t(c) * (kMaxStrips + 1);
  std::vector<uint32_t>& immovable = immovableOfChunk_[c];
  immovable.clear();
  auto noteImmovable = [&](uint32_t body) {  // a pile touches few: a short list, sorted later
    if (immovable.size() >= 16 || std::find(immovable.begin(), immovable.end(), body) == immovable.end())
      immovable.push_back(body);
  };
  for (uint32_t j = c * kChunk; j < std::min(nc, (c + 1) * kChunk); ++j) {
    const ContactEdge& e = contacts[cs[j]];
    const bool ma = bodies.isAwakeDynamic(e.a), mb = bodies.isAwakeDynamic(e.b);
    if (!ma) noteImmovable(e.a);
    if (!mb) noteImmovable(e.b);
    const uint32_t sa = ma ? stripOfBody_[e.a] : stripOfBody_[e.b];
    const uint32_t sb = mb ? stripOfBody_[e.b] : sa;
    const uint32_t lo = std::min(sa, sb), hi = std::max(sa, sb);
    const uint32_t s = hi - lo <= 1 ? lo : strips;
    stripOfContact_[j] = s;
    ++count[s];
    rows[s] += solverRowsFor(int(e.count));
  }
}

// Strip s starts after every earlier strip; inside it, chunk c's contacts after those of chunks < c.
void IslandSplitter::placeContacts(StripLayout& out, uint32_t contactChunks) {
  const uint32_t strips = out.strips;
  out.start[0] = 0;
  for (uint32_t s = 0; s <= strips; ++s) {
    uint32_t at = out.start[s], rows = 0;
    for (uint32_t c = 0; c < contactChunks; ++c) {
      const size_t i = size_t(c) * (kMaxStrips + 1) + s;
      cursor_[i] = at;
      at += count_[i];
      rows += rows_[i];
    }
    out.start[s + 1] = at;
    out.rows[s] = rows;
  }
}

void IslandSplitter::scatterContacts(const uint32_t* cs, uint32_t nc, uint32_t c) {
  uint32_t* cursor = cursor_.data() + size_t(c) * (kMaxStrips + 1);
  for (uint32_t j = c * kChunk; j < std::min(nc, (c + 1) * kChunk); ++j) scratch_[cursor[stripOfContact_[j]]++] = cs[j];
}

}  // namespace haif
