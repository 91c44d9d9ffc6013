#include "haif/turn_projection.h"

#include "collision/collide.h"

#include <algorithm>

namespace haif {

namespace {

/// |n . up| above which a pair is one body resting on the other (within 60 degrees of vertical).
constexpr float kStacked = 0.5f;
/// Rounds of pairs: the turned bodies' own, then those of the bodies each round moved.
constexpr int kRounds = 3;

}  // namespace

uint32_t TurnProjection::apply(BodyStore& bodies, const std::vector<Shape>& shapes,
                               const std::vector<Contact>& contacts, const ContactEdge* edges,
                               const int32_t* islandOfBody, const IslandSet& islands, const Vec3& up, float dt,
                               const TurnProjectionSettings& settings) {
  if (settings.angle <= 0.0f) return 0;
  const uint32_t n = uint32_t(bodies.size());
  active_.assign(n, 0);
  const float limit2 = (settings.angle / dt) * (settings.angle / dt);
  auto jointed = [&](uint32_t i) { return islandOfBody[i] >= 0 && islands.islands[islandOfBody[i]].jointCount > 0; };
  bool any = false;
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies.w[i].squaredNorm() <= limit2) continue;  // the velocities are packed; shapes are not
    if (shapes[i].type == ShapeType::Sphere || !bodies.isAwakeDynamic(i) || jointed(i)) continue;
    any = true;
    active_[i] = 1;
  }
  if (!any) return 0;  // most steps of most scenes: nothing more to read
  // A body held against a kinematic one is left where the solver put it: the kinematic pair is not
  // collided again, and a push away from a neighbour could drive it into the mover (a bar crushing a
  // pile against a wall).
  held_.assign(n, 0);
  const uint32_t pairCount = uint32_t(contacts.size());
  for (uint32_t c = 0; c < pairCount; ++c) {
    const ContactEdge& k = edges[c];  // a, b and the point count, packed: the contacts are large
    if (k.count == 0) continue;
    if (bodies.kind[k.a] == BodyKind::Kinematic) held_[k.b] = 1;
    if (bodies.kind[k.b] == BodyKind::Kinematic) held_[k.a] = 1;
  }
  auto movable = [&](uint32_t i) { return bodies.isAwakeDynamic(i) && !jointed(i) && !held_[i]; };
  for (uint32_t i = 0; i < n; ++i) active_[i] &= uint8_t(!held_[i]);
  done_.assign(pairCount, 0);
  uint32_t moved = 0;
  Manifold m;
  // Round 1 takes the pairs of the turned bodies; each later round those of the bodies the round
  // before moved (a box lifted out of a ball under it may now sit in the ball above it).
  for (int round = 0; round < kRounds && any; ++round) {
    pairs_.clear();
    for (uint32_t c = 0; c < pairCount; ++c) {
      const ContactEdge& k = edges[c];
      if (done_[c] || !(active_[k.a] || active_[k.b])) continue;
      if (bodies.kind[k.a] == BodyKind::Kinematic || bodies.kind[k.b] == BodyKind::Kinematic) continue;
      if (jointed(k.a) || jointed(k.b)) continue;
      done_[c] = 1;
      pairs_.emplace_back(up.dot(bodies.xf[k.a].p + bodies.xf[k.b].p), c);
    }
    std::sort(pairs_.begin(), pairs_.end());  // lowest first; ties by contact index
    std::fill(active_.begin(), active_.end(), 0);
    any = false;
    for (const auto& [height, c] : pairs_) {
      const ContactEdge& k = edges[c];
      if (collide(shapes[k.a], bodies.xf[k.a], shapes[k.b], bodies.xf[k.b], 0.0f, m) == 0) continue;
      int deepest = 0;
      for (int i = 1; i < m.count; ++i)
        if (m.points[i].depth > m.points[deepest].depth) deepest = i;
      if (!(m.points[deepest].depth > settings.keep)) continue;  // the usual case: read no contact
      const float excess = m.points[deepest].depth - std::max(settings.keep, contacts[c].manifold.deepest());
      if (!(excess > 0.0f)) continue;
      const Vec3 normal = m.points[deepest].normal;  // from a to b
      float ia = movable(k.a) ? bodies.invMass[k.a] : 0.0f;
      float ib = movable(k.b) ? bodies.invMass[k.b] : 0.0f;
      // One on top of the other: the lower one was settled already (its pairs came first), and
      // only the upper one moves.
      const float along = normal.dot(up);
      if (along > kStacked && ib > 0.0f) ia = 0.0f;
      if (along < -kStacked && ia > 0.0f) ib = 0.0f;
      if (ia + ib <= 0.0f) continue;
      const float share = excess / (ia + ib);
      if (ia > 0.0f) bodies.xf[k.a].p -= (share * ia) * normal, active_[k.a] = 1, any = true;
      if (ib > 0.0f) bodies.xf[k.b].p += (share * ib) * normal, active_[k.b] = 1, any = true;
      ++moved;
    }
  }
  return moved;
}

}  // namespace haif
