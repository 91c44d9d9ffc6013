#include "haif/turn_projection.h"

#include "collision/collide.h"
#include "collision/support.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace haif {

namespace {

/// |n . up| above which a pair is one body resting on the other (within 60 degrees of vertical).
constexpr float kStacked = 0.5f;
/// A pair is collided again when its linear read of the step's end is this much (m) past its target.
constexpr float kCrushSlack = 0.005f;
/// The least excess (m) moved at any pair scale: the rounding after a pair was moved to its target.
constexpr float kLeastMove = 1e-4f;
/// Added to a depth bound before it decides that a pair need not be collided: the rounding of the
/// collision that found the depth (m).
constexpr float kBoundRounding = 1e-5f;

/// The deepest point of a pair collided at the bodies' current poses (depth -inf: no point).
void collideAt(const TurnProjectionInput& in, uint32_t a, uint32_t b, float& depth, Vec3& normal) {
  const BodyStore& bodies = *in.bodies;
  const std::vector<Shape>& shapes = *in.shapes;
  Manifold m;
  depth = -std::numeric_limits<float>::infinity();
  if (collide(shapes[a], bodies.xf[a], shapes[b], bodies.xf[b], 0.0f, m) == 0) return;
  int deepest = 0;
  for (int i = 1; i < m.count; ++i)
    if (m.points[i].depth > m.points[deepest].depth) deepest = i;
  depth = m.points[deepest].depth;
  normal = m.points[deepest].normal;  // from a to b
}

}  // namespace

// The depth a pair may keep: what it began the step with, within [keep, crushKeep], and deeper than
// that by no more than crushRecover: what the step added goes, depth it began with only by a
// bounded amount a step, as the solver's own push-out would (bodies spawned a metre into each other
// were thrown apart in one step, one of them 0.38 m into the ground).
// A small body's pair has all three scaled down with it (haif/small_bodies.h).
float TurnProjection::target(uint32_t c) const {
  const ContactEdge& e = in_.edges[c];
  const float start = e.deepest, scale = toleranceScale(e);
  return std::max(std::max(settings_.keep * scale, std::min(start, settings_.crushKeep * scale)),
                  start - settings_.crushRecover * scale);
}

float TurnProjection::leastMove(const ContactEdge& e) const {
  return std::max(kLeastMove, settings_.leastMove * toleranceScale(e));
}

bool TurnProjection::mayExceed(uint32_t c) const {
  const ContactEdge& e = in_.edges[c];
  return !withinTarget(c, known_[c] + (relativeShift(e.a, e.b) - knownShift_[c]).norm() + kBoundRounding);
}

void TurnProjection::noteDepth(uint32_t c, float depth, const Vec3& shift) {
  known_[c] = std::isfinite(depth) ? depth : 0.0f;  // no point at margin 0: apart
  knownShift_[c] = shift;
}

bool TurnProjection::jointed(uint32_t i) const { return in_.jointed != nullptr && in_.jointed[i] != 0; }

bool TurnProjection::movable(uint32_t i) const {
  return in_.bodies->isAwakeDynamic(i) && !jointed(i) && !held_[i];
}

bool TurnProjection::begin(const TurnProjectionInput& in, const TurnProjectionSettings& settings) {
  moved_ = 0;
  collisions_ = 0;
  settled_ = 0;
  toBox_.clear();
  if (settings.angle <= 0.0f) return false;
  in_ = in;
  settings_ = settings;
  const size_t n = in.bodies->size(), pairCount = in.contacts->size();
  turned_.resize(n);
  spinReach_.resize(n);
  candidate_.resize(pairCount);
  known_.resize(pairCount);
  return pairCount > 0;
}

void TurnProjection::scanBodies(uint32_t begin, uint32_t end) {
  const BodyStore& bodies = *in_.bodies;
  const float limit = settings_.angle / in_.dt;
  for (uint32_t i = begin; i < end; ++i) {
    const float spin = bodies.w[i].norm();  // the velocities are packed; shapes are not
    // A sphere's turn does not move its surface.
    const bool sphere = (*in_.shapes)[i].type == ShapeType::Sphere;
    // A body without a reach (a mesh) that turns, a kinematic one, is bounded by nothing.
    const bool unbounded = in_.reach[i] <= 0.0f && spin > 0.0f && !sphere;
    spinReach_[i] = sphere ? 0.0f : unbounded ? std::numeric_limits<float>::infinity() : spin * in_.reach[i];
    // Or its turn moves its surface farther than the narrow phase's margin: features of a pair that
    // were apart by more than that at the start (not among its points) may meet within the step (a
    // 1080 kg block of `tower_collapse` turning at 4 rad/s, 0.07 rad a step, went 13 cm into the
    // next while their one point, read linearly, said they would part).
    const bool sweeps = bodies.isDynamic(i) && !unbounded && spinReach_[i] * in_.dt > in_.contactMargin;
    turned_[i] = (spin > limit || sweeps) && !sphere;
  }
}

// A contact is a candidate when it may end the step deeper than its target: no point of a body moves
// farther than dt (|v| + |w| reach) in a step, and a pair whose depth plus their relative bound stays
// under the target is left (most pairs of most steps, read from the packed edges only). Of the rest, a
// pair with a turned body is taken (its points, linear in the turn, no longer say where it ends); the
// others' points are read with the final velocities; a pair without points is taken where the
// bodies' final boxes overlap (a pair farther apart at the start than it then closed: a ball falling
// at 12 m/s onto one at 13, stopped by what it landed on, was met 8 cm deep).
void TurnProjection::scanPairs(uint32_t begin, uint32_t end) {
  const BodyStore& bodies = *in_.bodies;
  const float dt = in_.dt;
  for (uint32_t c = begin; c < end; ++c) {
    candidate_[c] = 0;
    const ContactEdge& e = in_.edges[c];
    if (!takeable(e)) continue;
    const float spin = spinReach_[e.a] + spinReach_[e.b];
    const float closing = dt * ((bodies.v[e.b] - bodies.v[e.a]).norm() + spin);
    // The bound at the step's end: the start depth and how far the pair may close (a pair without
    // points began farther apart than the margin the narrow phase collided it with: its deepest is
    // minus that, ContactEdge).
    known_[c] = e.deepest + closing;
    if (e.count == 0 ? known_[c] <= 0.0f : known_[c] <= target(c) + kCrushSlack) continue;
    if (settings_.crushKeep <= 0.0f && !turned_[e.a] && !turned_[e.b]) continue;  // crushes left to the solver
    if (e.count == 0) {
      // Boxes from the start, each widened by how far its body may go: cheap, and most pairs stop here.
      const float da = dt * (bodies.v[e.a].norm() + spinReach_[e.a]), db = dt * (bodies.v[e.b].norm() + spinReach_[e.b]);
      if (!in_.startBounds[e.a].expanded(da + db).overlaps(in_.startBounds[e.b])) {
        known_[c] = 0.0f;  // the boxes stay apart
        continue;
      }
      candidate_[c] = 2;
      settleByReach(c);
      continue;
    }
    const Contact& k = (*in_.contacts)[c];
    if (turned_[e.a] || turned_[e.b]) {
      candidate_[c] = 1;
    } else {
      float predicted = -std::numeric_limits<float>::infinity();
      for (int i = 0; i < k.manifold.count; ++i) {
        const ContactPoint& p = k.manifold.points[i];
        const Vec3 rel = bodies.velocityAt(k.b, p.position) - bodies.velocityAt(k.a, p.position);
        predicted = std::max(predicted, p.depth + dt * rel.norm());
      }
      if (predicted > target(c) + kCrushSlack) candidate_[c] = 1;
    }
    if (candidate_[c] == 1) settleByReach(c);
  }
}

// The overlap along one direction bounds the depth collide would report (collision/support.h):
// along the normal the pair's points had at the step's start, or for a pair without points along
// the line of its centres. Two support queries: a few dozen dot products against a collision's
// microseconds.
float TurnProjection::reachBound(uint32_t c) const {
  const ContactEdge& e = in_.edges[c];
  const BodyStore& bodies = *in_.bodies;
  const std::vector<Shape>& shapes = *in_.shapes;
  Vec3 n;
  if (e.count > 0) {
    n = (*in_.contacts)[c].manifold.points[0].normal;
  } else {
    n = bodies.xf[e.b].p - bodies.xf[e.a].p;
    if (!(n.squaredNorm() > 0.0f)) return std::numeric_limits<float>::infinity();
    n.normalize();
  }
  return depthBoundFromOverlap(overlapAlong(shapes[e.a], bodies.xf[e.a], shapes[e.b], bodies.xf[e.b], n)) + kBoundRounding;
}

bool TurnProjection::withinTarget(uint32_t c, float depth) const {
  return depth <= target(c) + leastMove(in_.edges[c]);
}

// A candidate that its reach keeps within its target and the least move is not collided: it could
// not be moved. Its bound is noted as its depth. Most of a landing's candidates end that shallow
// (a pour of 1,500 hulls: ~4,500 of ~5,500 a step).
void TurnProjection::settleByReach(uint32_t c) {
  const float bound = reachBound(c);
  if (!withinTarget(c, bound)) return;
  candidate_[c] = kSettled;
  known_[c] = bound;
}

bool TurnProjection::collectCandidates() {
  const BodyStore& bodies = *in_.bodies;
  const uint32_t n = uint32_t(bodies.size()), pairCount = uint32_t(in_.contacts->size());
  bool any = false;
  boxPairs_.clear();
  for (uint32_t c = 0; c < pairCount; ++c) {
    if (candidate_[c] == kSettled) {
      candidate_[c] = 0;
      ++settled_;
    }
    if (candidate_[c] == 0) continue;
    any = true;
    if (candidate_[c] == 2) boxPairs_.push_back(c);
  }
  if (!any) return false;
  boxed_.assign(n, 0);
  box_.resize(n);
  for (uint32_t c : boxPairs_) {
    needBox(in_.edges[c].a);
    needBox(in_.edges[c].b);
  }
  // A body pressed from both sides by what cannot move (haif/pinch.h) is left where the solver put
  // it: out of one is into the other. A kinematic body is as immovable as a static one here: the
  // body in it moves out (into the pile, whose pairs the next round takes).
  held_.assign(n, 0);
  if (in_.pinched)
    for (const uint32_t c : *in_.pinched) {  // the list, not every contact: the contacts are large
      const ContactEdge& k = in_.edges[c];
      if (k.count > 0) held_[k.a] = held_[k.b] = 1;
    }
  // Each body's pairs that a round may take (CSR), so a round gathers the pairs of the bodies that
  // moved without reading every pair, and a move brings its body's higher pairs into the same round.
  pairStart_.assign(n + 1, 0);
  for (uint32_t c = 0; c < pairCount; ++c) {
    const ContactEdge& k = in_.edges[c];
    if (!takeable(k)) continue;
    ++pairStart_[k.a + 1];
    ++pairStart_[k.b + 1];
  }
  for (uint32_t i = 0; i < n; ++i) pairStart_[i + 1] += pairStart_[i];
  pairOf_.resize(pairStart_[n]);
  fill_.assign(pairStart_.begin(), pairStart_.end() - 1);
  for (uint32_t c = 0; c < pairCount; ++c) {
    const ContactEdge& k = in_.edges[c];
    if (!takeable(k)) continue;
    pairOf_[fill_[k.a]++] = c;
    pairOf_[fill_[k.b]++] = c;
  }
  active_.assign(n, 0);
  movedAt_.assign(n, 0);
  shift_.assign(n, Vec3::Zero());
  knownShift_.assign(pairCount, Vec3::Zero());
  collidedAt_.assign(pairCount, 0);
  queuedIn_.assign(pairCount, 0);
  clock_ = 1;
  return true;
}

bool TurnProjection::takeable(const ContactEdge& k) const {
  const BodyStore& bodies = *in_.bodies;
  if (!bodies.isAwakeDynamic(k.a) && !bodies.isAwakeDynamic(k.b)) return false;
  return !jointed(k.a) || !jointed(k.b);  // a jointed body does not move: its joints would be pulled apart
}

void TurnProjection::needBox(uint32_t body) {
  if (boxed_[body]) return;
  boxed_[body] = 1;
  toBox_.push_back(body);
}

void TurnProjection::boxNow(uint32_t body) {
  if (boxed_[body]) return;
  boxed_[body] = 1;
  box_[body] = solvedBox(body);
}

Aabb TurnProjection::solvedBox(uint32_t body) const {
  Transform solved = in_.bodies->xf[body];
  solved.p -= shift_[body];
  return computeAabb((*in_.shapes)[body], solved);
}

void TurnProjection::boxBodies(uint32_t begin, uint32_t end) {
  for (uint32_t j = begin; j < end; ++j) box_[toBox_[j]] = solvedBox(toBox_[j]);
}

float TurnProjection::boxGap(const ContactEdge& e) const {
  const Vec3 d = shift_[e.b] - shift_[e.a];  // b's box relative to a's
  const Aabb &a = box_[e.a], &b = box_[e.b];
  return std::max((b.lo + d - a.hi).maxCoeff(), (a.lo - b.hi - d).maxCoeff());
}

float TurnProjection::depthNow(uint32_t c, Vec3& normal, bool tryReach, Probe& how) const {
  const ContactEdge& e = in_.edges[c];
  // Above the rounding of the boxes: pairs the stage moved to touch have boxes a hair apart and a
  // point at depth 0.
  const float gap = boxGap(e);
  how = Probe::kBoxesApart;
  if (gap > kBoundRounding) return -gap;
  how = Probe::kBounded;
  if (tryReach) {
    const float bound = reachBound(c);
    if (withinTarget(c, bound)) return bound;  // a bound, not a depth: not moved, and read as a bound later
  }
  how = Probe::kCollided;
  float depth;
  collideAt(in_, e.a, e.b, depth, normal);
  return depth;
}

void TurnProjection::boxPairs() {
  for (uint32_t c : boxPairs_) {
    const ContactEdge& e = in_.edges[c];
    const float gap = boxGap(e);  // nothing has moved yet
    candidate_[c] = gap > 0.0f ? 0 : 1;
    if (candidate_[c] == 0) known_[c] = -gap;  // the final boxes are apart: the pair is that far
  }
}

// Round 0 takes the candidates; each later round the pairs of the bodies the round before moved (a
// box lifted out of a ball under it may now sit in the ball above it), those collided earlier in
// the step too, unless neither body moved since.
bool TurnProjection::gatherRound(int round) {
  const BodyStore& bodies = *in_.bodies;
  const uint32_t stamp = uint32_t(round) + 1;  // queuedIn_: the round a pair was last queued in, + 1
  pairs_.clear();
  auto take = [&](uint32_t c) {
    const ContactEdge& k = in_.edges[c];
    if (queuedIn_[c] == stamp) return;
    if (collidedAt_[c] != 0 && std::max(movedAt_[k.a], movedAt_[k.b]) < collidedAt_[c]) return;
    if (round > 0 && !mayExceed(c)) return;
    queuedIn_[c] = stamp;
    pairs_.emplace_back(in_.up.dot(bodies.xf[k.a].p + bodies.xf[k.b].p), c);
  };
  if (round == 0) {
    const uint32_t pairCount = uint32_t(in_.contacts->size());
    for (uint32_t c = 0; c < pairCount; ++c)
      if (candidate_[c] == 1) take(c);  // the scan took only takeable pairs
  } else {
    for (uint32_t i = 0; i < uint32_t(active_.size()); ++i)
      if (active_[i])
        for (uint32_t j = pairStart_[i]; j < pairStart_[i + 1]; ++j) take(pairOf_[j]);
  }
  std::sort(pairs_.begin(), pairs_.end());  // lowest first; ties by contact index
  toBox_.clear();
  for (const auto& [height, c] : pairs_) {
    needBox(in_.edges[c].a);
    needBox(in_.edges[c].b);
  }
  std::fill(active_.begin(), active_.end(), 0);
  ahead_.resize(pairs_.size());
  roundStart_ = clock_;
  round_ = round;
  return !pairs_.empty();
}

void TurnProjection::collideAhead(uint32_t begin, uint32_t end) {
  for (uint32_t j = begin; j < end; ++j) {
    const ContactEdge& k = in_.edges[pairs_[j].second];
    // Round 0's pairs were bounded at these poses by the scan already.
    ahead_[j].depth = depthNow(pairs_[j].second, ahead_[j].normal, round_ > 0, ahead_[j].how);
    ahead_[j].shift = relativeShift(k.a, k.b);
  }
}

bool TurnProjection::resolveRound() {
  BodyStore& bodies = *in_.bodies;
  const uint32_t stamp = uint32_t(round_) + 1;
  bool any = false;
  later_.clear();
  // Pairs come from the round's sorted list and, merged by height, from later_: the higher pairs of
  // a body this round moved, taken in this round (a tower knocked over moved a block up into the
  // one above it, which waited for the next round and was left 0.2 m deep after the last).
  size_t j = 0;
  while (j < pairs_.size() || !later_.empty()) {
    const bool fromList = later_.empty() || (j < pairs_.size() && pairs_[j] < later_.front());
    std::pair<float, uint32_t> entry;
    float depth;
    Vec3 normal;
    if (fromList) {
      entry = pairs_[j];
      depth = ahead_[j].depth;
      normal = ahead_[j].normal;
      count(ahead_[j].how);
      ++j;
    } else {
      std::pop_heap(later_.begin(), later_.end(), std::greater<>());
      entry = later_.back();
      later_.pop_back();
    }
    const uint32_t c = entry.second;
    const ContactEdge& k = in_.edges[c];
    if (fromList) noteDepth(c, depth, ahead_[j - 1].shift);
    // A body an earlier pair of this round moved: the collision made ahead is stale, unless the
    // bound says that it still cannot be deep enough to move.
    if (!fromList || std::max(movedAt_[k.a], movedAt_[k.b]) > roundStart_) {
      if (!mayExceed(c)) continue;
      boxNow(k.a);  // a pair a move brought in: its bodies may have no box yet
      boxNow(k.b);
      Probe how;
      depth = depthNow(c, normal, true, how);
      count(how);
      noteDepth(c, depth, relativeShift(k.a, k.b));
    }
    collidedAt_[c] = clock_;
    // The target is never under `keep`; a pair a later round finds where the last one left it stays.
    const float excess = depth - target(c);
    if (!(excess > leastMove(k))) continue;
    float ia = movable(k.a) ? bodies.invMass[k.a] : 0.0f;
    float ib = movable(k.b) ? bodies.invMass[k.b] : 0.0f;
    // One on top of the other: the lower one was settled already (its pairs came first), and only
    // the upper one moves.
    const float along = normal.dot(in_.up);
    if (along > kStacked && ib > 0.0f) ia = 0.0f;
    if (along < -kStacked && ia > 0.0f) ib = 0.0f;
    if (ia + ib <= 0.0f) continue;
    const float share = excess / (ia + ib);
    ++clock_;
    for (const uint32_t body : {k.a, k.b}) {
      const float inv = body == k.a ? ia : ib;
      if (inv <= 0.0f) continue;
      const Vec3 move = (body == k.a ? -share * inv : share * inv) * normal;
      bodies.xf[body].p += move;
      shift_[body] += move;
      active_[body] = 1;
      movedAt_[body] = clock_;
      any = true;
      // Its pairs at or above this one, not yet queued in this round, follow in this round.
      for (uint32_t e = pairStart_[body]; e < pairStart_[body + 1]; ++e) {
        const uint32_t p = pairOf_[e];
        if (queuedIn_[p] == stamp || !mayExceed(p)) continue;  // a later move may still bring it in
        const float height = in_.up.dot(bodies.xf[in_.edges[p].a].p + bodies.xf[in_.edges[p].b].p);
        if (std::make_pair(height, p) < entry) continue;  // below: the next round takes it
        queuedIn_[p] = stamp;
        later_.emplace_back(height, p);
        std::push_heap(later_.begin(), later_.end(), std::greater<>());
      }
    }
    ++clock_;
    ++moved_;
  }
  return any;
}

}  // namespace haif
