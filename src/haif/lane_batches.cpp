#include "haif/lane_batches.h"

#include "haif/islands.h"

#include <algorithm>

namespace haif {

template <class Pair>
void LaneBatcher::batch(const BodyStore& bodies, const Pair* contacts, const float* level, uint32_t* ids, uint32_t n,
                        uint8_t* run) {
  if (n == 0) return;
  if (lastBatch_.size() < bodies.size()) lastBatch_.resize(bodies.size(), -1);
  if (level) colourLevels(bodies, contacts, level, ids, n);
  batchOf_.resize(n);
  fill_.clear();
  nextOpen_.clear();
  // First batch at or after i with room (fill_.size(): none). Full batches point past themselves.
  auto firstOpen = [&](uint32_t i) {
    const uint32_t m = uint32_t(fill_.size());
    while (i < m && fill_[i] == kLanes) {
      const uint32_t next = nextOpen_[i];
      if (next < m) nextOpen_[i] = nextOpen_[next];  // path halving: later searches skip further
      i = next;
    }
    return i;
  };
  for (uint32_t j = 0; j < n; ++j) {
    const Pair& c = contacts[ids[j]];
    // Only awake dynamic bodies are written by a sweep; static and kinematic ends are shared freely.
    const bool ma = bodies.isAwakeDynamic(c.a), mb = bodies.isAwakeDynamic(c.b);
    int32_t after = -1;
    if (ma) after = std::max(after, lastBatch_[c.a]);
    if (mb) after = std::max(after, lastBatch_[c.b]);
    const uint32_t b = firstOpen(uint32_t(after + 1));
    if (b == fill_.size()) {
      fill_.push_back(0);
      nextOpen_.push_back(b);
    }
    if (++fill_[b] == kLanes) nextOpen_[b] = b + 1;
    batchOf_[j] = b;
    if (ma) lastBatch_[c.a] = int32_t(b);
    if (mb) lastBatch_[c.b] = int32_t(b);
  }
  // Stable counting sort by batch: inside a batch the original order stays (it does not matter to
  // the result, but keeps the layout predictable).
  const uint32_t m = uint32_t(fill_.size());
  start_.resize(m + 1);
  start_[0] = 0;
  for (uint32_t b = 0; b < m; ++b) start_[b + 1] = start_[b] + fill_[b];
  scratch_.resize(n);
  for (uint32_t j = 0; j < n; ++j) scratch_[start_[batchOf_[j]]++] = ids[j];
  std::fill(run, run + n, uint8_t(0));
  for (uint32_t b = 0, s = 0; b < m; s += fill_[b], ++b) run[s] = fill_[b];
  std::copy(scratch_.begin(), scratch_.end(), ids);
  for (uint32_t j = 0; j < n; ++j) {  // leave lastBatch_ clear for the next range
    const Pair& c = contacts[ids[j]];
    lastBatch_[c.a] = lastBatch_[c.b] = -1;
  }
}

template <class Pair>
void LaneBatcher::colourLevels(const BodyStore& bodies, const Pair* contacts, const float* level, uint32_t* ids,
                               uint32_t n) {
  if (colours_.size() < bodies.size()) colours_.resize(bodies.size(), 0u);
  colourOf_.resize(n);
  scratch_.resize(n);
  for (uint32_t l0 = 0, l1; l0 < n; l0 = l1) {
    const float top = level[ids[l0]];
    for (l1 = l0 + 1; l1 < n && level[ids[l1]] >= top - kLevelTolerance; ++l1) {}
    if (l1 - l0 < 2) continue;
    // Greedy colouring in solve order: the smallest colour neither body has in this level.
    for (uint32_t j = l0; j < l1; ++j) {
      const Pair& c = contacts[ids[j]];
      const bool ma = bodies.isAwakeDynamic(c.a), mb = bodies.isAwakeDynamic(c.b);
      const uint32_t taken = (ma ? colours_[c.a] : 0u) | (mb ? colours_[c.b] : 0u);
      const uint32_t colour = ~taken ? uint32_t(__builtin_ctz(~taken)) : 31u;
      colourOf_[j] = uint8_t(colour);
      if (ma) colours_[c.a] |= 1u << colour;
      if (mb) colours_[c.b] |= 1u << colour;
    }
    // Colour by colour, solve order inside a colour (a stable counting sort).
    uint32_t at[33] = {};
    for (uint32_t j = l0; j < l1; ++j) ++at[colourOf_[j] + 1];
    for (int c = 0; c < 32; ++c) at[c + 1] += at[c];
    for (uint32_t j = l0; j < l1; ++j) scratch_[l0 + at[colourOf_[j]]++] = ids[j];
    for (uint32_t j = l0; j < l1; ++j) {
      const Pair& c = contacts[ids[j]];
      colours_[c.a] = colours_[c.b] = 0u;
      ids[j] = scratch_[j];
    }
  }
}

template void LaneBatcher::batch(const BodyStore&, const Contact*, const float*, uint32_t*, uint32_t, uint8_t*);
template void LaneBatcher::batch(const BodyStore&, const ContactEdge*, const float*, uint32_t*, uint32_t, uint8_t*);

}  // namespace haif
