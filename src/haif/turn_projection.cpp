#include "haif/turn_projection.h"

#include "collision/collide.h"

#include <algorithm>

namespace haif {

namespace {

/// |n . up| above which a pair is one body resting on the other (within 60 degrees of vertical).
constexpr float kStacked = 0.5f;
/// Rounds of pairs: the turned bodies' own, then those of the bodies each round moved.
constexpr int kRounds = 6;
/// A pair is collided again when its linear read of the step's end is this much (m) past its target.
constexpr float kCrushSlack = 0.005f;
/// Excess depth (m) below which a pair is not moved: rounding after a pair was moved to its target.
constexpr float kLeastMove = 1e-4f;

}  // namespace

uint32_t TurnProjection::apply(BodyStore& bodies, const std::vector<Shape>& shapes,
                               const std::vector<Contact>& contacts, const ContactEdge* edges,
                               const int32_t* islandOfBody, const IslandSet& islands, const Vec3& up,
                               const float* reach, float dt, float contactMargin,
                               const TurnProjectionSettings& settings) {
  if (settings.angle <= 0.0f) return 0;
  const uint32_t n = uint32_t(bodies.size());
  const uint32_t pairCount = uint32_t(contacts.size());
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
  // The depth a pair may keep: what it began the step with, within [keep, crushKeep], and deeper
  // than that by no more than crushRecover: what the step added goes, depth it began with only by a
  // bounded amount a step, as the solver's own push-out would (bodies spawned a metre into each
  // other were thrown apart in one step, one of them 0.38 m into the ground).
  auto target = [&](uint32_t c) {
    const float start = edges[c].deepest;
    return std::max(std::max(settings.keep, std::min(start, settings.crushKeep)), start - settings.crushRecover);
  };
  // Pairs driven into each other without a turn: each point's depth at the end of the step, read
  // linearly from its depth at the start and the bodies' final velocities.
  crushed_.assign(pairCount, 0);
  if (settings.crushKeep > 0.0f) {
    // A bound from the packed edges and velocities first: a resting pile's pairs (most pairs of
    // most steps) end where they began, and their contacts, which are large, are not read.
    motion_.resize(n);
    for (uint32_t i = 0; i < n; ++i) motion_[i] = bodies.v[i].norm() + bodies.w[i].norm() * reach[i];
    for (uint32_t c = 0; c < pairCount; ++c) {
      const ContactEdge& e = edges[c];
      if (!bodies.isAwakeDynamic(e.a) && !bodies.isAwakeDynamic(e.b)) continue;
      const float closing = dt * (motion_[e.a] + motion_[e.b]);
      if (e.count == 0 ? closing <= contactMargin : e.deepest + closing <= target(c) + kCrushSlack) continue;
      const Contact& k = contacts[c];
      const Vec3 va = bodies.v[k.a], vb = bodies.v[k.b], wa = bodies.w[k.a], wb = bodies.w[k.b];
      if (k.manifold.count == 0) {
        // No point: the pair was farther apart than it closed at the step's start. A body struck
        // within the step closes faster (a ball falling at 12 m/s onto one at 13, stopped by what it
        // landed on, was met 8 cm deep): where the final boxes overlap, it is collided again.
        if ((vb - va).squaredNorm() * dt * dt <= contactMargin * contactMargin) continue;
        if (computeAabb(shapes[k.a], bodies.xf[k.a]).overlaps(computeAabb(shapes[k.b], bodies.xf[k.b])))
          crushed_[c] = 1, any = true;
        continue;
      }
      const Vec3 pa = bodies.xf[k.a].p, pb = bodies.xf[k.b].p;
      float predicted = -1e30f;
      for (int i = 0; i < k.manifold.count; ++i) {
        const ContactPoint& p = k.manifold.points[i];
        const Vec3 rel = vb + wb.cross(p.position - pb) - va - wa.cross(p.position - pa);
        predicted = std::max(predicted, p.depth + dt * rel.norm());
      }
      if (predicted > target(c) + kCrushSlack) crushed_[c] = 1, any = true;
    }
  }
  if (!any) return 0;  // most steps of most scenes: nothing more to read
  // A body held against a kinematic one is left where the solver put it: the kinematic pair is not
  // collided again, and a push away from a neighbour could drive it into the mover (a bar crushing a
  // pile against a wall).
  held_.assign(n, 0);
  for (uint32_t c = 0; c < pairCount; ++c) {
    const ContactEdge& k = edges[c];  // a, b and the point count, packed: the contacts are large
    if (k.count == 0) continue;
    if (bodies.kind[k.a] == BodyKind::Kinematic) held_[k.b] = 1;
    if (bodies.kind[k.b] == BodyKind::Kinematic) held_[k.a] = 1;
    // Pressed from both sides by what cannot move (haif/pinch.h): out of one is into the other.
    if (contacts[c].pinched) held_[k.a] = held_[k.b] = 1;
  }
  auto movable = [&](uint32_t i) { return bodies.isAwakeDynamic(i) && !jointed(i) && !held_[i]; };
  for (uint32_t i = 0; i < n; ++i) active_[i] &= uint8_t(!held_[i]);
  uint32_t moved = 0;
  // Moves are numbered; a pair is collided again only when one of its bodies moved after it was
  // last collided (a pair taken after its body moved, later in the same round, is where it was).
  movedAt_.assign(n, 0);
  collidedAt_.assign(pairCount, 0);
  uint32_t clock = 1;
  Manifold m;
  // Round 1 takes the pairs of the turned bodies; each later round those of the bodies the round
  // before moved (a box lifted out of a ball under it may now sit in the ball above it).
  for (int round = 0; round < kRounds && any; ++round) {
    pairs_.clear();
    for (uint32_t c = 0; c < pairCount; ++c) {
      const ContactEdge& k = edges[c];
      if (!(active_[k.a] || active_[k.b] || (round == 0 && crushed_[c]))) continue;
      if (collidedAt_[c] != 0 && std::max(movedAt_[k.a], movedAt_[k.b]) < collidedAt_[c]) continue;
      if (bodies.kind[k.a] == BodyKind::Kinematic || bodies.kind[k.b] == BodyKind::Kinematic) continue;
      if (jointed(k.a) || jointed(k.b)) continue;
      pairs_.emplace_back(up.dot(bodies.xf[k.a].p + bodies.xf[k.b].p), c);
    }
    std::sort(pairs_.begin(), pairs_.end());  // lowest first; ties by contact index
    std::fill(active_.begin(), active_.end(), 0);
    any = false;
    for (const auto& [height, c] : pairs_) {
      const ContactEdge& k = edges[c];
      collidedAt_[c] = clock;
      if (collide(shapes[k.a], bodies.xf[k.a], shapes[k.b], bodies.xf[k.b], 0.0f, m) == 0) continue;
      int deepest = 0;
      for (int i = 1; i < m.count; ++i)
        if (m.points[i].depth > m.points[deepest].depth) deepest = i;
      // The target is never under `keep`; a pair a later round finds where the last one left it stays.
      const float excess = m.points[deepest].depth - target(c);
      if (!(excess > kLeastMove)) continue;
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
      ++clock;
      if (ia > 0.0f) bodies.xf[k.a].p -= (share * ia) * normal, active_[k.a] = 1, movedAt_[k.a] = clock, any = true;
      if (ib > 0.0f) bodies.xf[k.b].p += (share * ib) * normal, active_[k.b] = 1, movedAt_[k.b] = clock, any = true;
      ++clock;
      ++moved;
    }
  }
  return moved;
}

}  // namespace haif
