// Pairs the step carried into each other: by a fast turn, by a crush, by a blow within the step.
//
// A contact's rows are linear in the bodies' motion over the step, about the points the narrow
// phase found at its start. Three things carry a pair deeper than those rows can see:
// - a fast turn: a body that picks up a spin within the step (a hull landing on an edge at 14 m/s
//   spins up to 30-40 rad/s, a capsule struck off centre turns on its single point) turns 0.5-0.7
//   rad, and corners that were not among the points end up 0.2 m deep in what it landed on;
// - a crush: a heavy body landing on a light one that rests on others. Gauss-Seidel passes the
//   support up such a chain a fraction m/(m+M) a sweep, so after ten sweeps a 119 kg ball still
//   sank at 4 m/s into an 11 kg box on the ground, 0.22 m deep in three steps;
// - a blow within the step: a pair farther apart at the start than it then closed has no point (a
//   ball falling at 12 m/s was stopped by what it landed on and met by one at 13 m/s, 8 cm deep).
// So after the step, the pairs of each body that turned more than an angle, and the pairs whose
// points, read linearly with the final velocities (or, without points, whose final boxes overlap
// and which may have closed more than the margin the narrow phase found them apart by), end deeper
// than they may keep, are collided again at the poses the step ended on, and a pair
// deeper than its target is moved apart by the excess, positions only (its velocities stay the
// solver's). A pair keeps the depth it began the step with, within [keep, crushKeep]; depth it
// began with beyond that goes by crushRecover a step (bodies spawned into each other come apart
// as gently as the solver would part them). Lowest pairs first, and a pair whose normal is mostly
// along `up` moves only its upper body, so a correction is not pushed back into the support below
// (a light body under a heavy one would be driven into the ground). A body moved may now overlap
// a neighbour: its pairs at or above the pair that moved it are taken later in the same round (a
// column lifted from below in one round; a knocked tower moved a block into the one above it after
// the last round and left them 0.2 m deep), those below it in the next round, pairs collided
// earlier in the step too (a box lifted 8 cm out of the box under it was left 0.107 m deep in the
// one resting on it, a pair the first round had found apart), for up to six rounds.
// Of the candidates, a pair whose overlap along its normal (a pair without points: along the line of
// its centres) at the final poses already keeps it within its target is not collided either: two
// support queries bound the depth a collision would find (collision/support.h).
// Pairs that cannot end deeper than their target are never collided again: no point of a body
// moves farther in a step than dt (|v| + |w| reach), which bounds how much deeper a pair can go
// (a resting pile's pairs, and the pairs of a turned body with neighbours a hand's width away),
// and no point farther in this stage than the body's moves here add up to, which bounds how much
// deeper a pair can be than when it was last collided (in a jam at `swept_pit`'s bar most pairs of
// a body moved a few millimetres: 13,000 collisions a step on one thread, half of them left). A
// sphere's turn does not move its surface (its crushes are taken). A kinematic body does not give
// way, as a static one: what sinks into it moves out (a turning drum pressed the bottom of its pile
// 9 cm into its wall, the solver alone against the pile's weight). Nor does a body with a joint
// (its joints would be pulled apart): a crate dropped on a rope bridge moves out of the plank (it
// sat 0.125 m in it while its whole island was left out), two jointed bodies are left to the
// solver. A body pinched between immovable ones (haif/pinch.h) goes out of one into the other: it
// is not moved either.
#pragma once

#include "collision/shape.h"
#include "core/aabb.h"
#include "core/body_store.h"
#include "core/serial_for.h"
#include "dynamics/contact.h"
#include "haif/islands.h"
#include "haif/small_bodies.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace haif {

struct TurnProjectionSettings {
  /// A body counts as turned when |ω| dt exceeds this (rad): a linearisation about the step's
  /// first points holds to a few mm below it for bodies of a metre. A dynamic body also counts when
  /// its turn moves its surface farther than the narrow phase's margin in a step (|ω| reach dt):
  /// features that were not among its pairs' points may then meet. 0 turns the stage off.
  float angle = 0.1f;
  /// Depth (m) left in place: the solver's own push-out settles shallow overlap gently.
  float keep = 0.01f;
  /// Depth (m) a pair that began the step deeper is brought back to. 0 leaves such pairs alone.
  float crushKeep = 0.03f;
  /// Depth (m) such a pair loses a step beyond what the step added, positions only (1.2 m/s).
  float crushRecover = 0.02f;
  /// Excess over the target (m) a pair must pass to be moved, and that its depth bound must allow
  /// for it to be collided again after a move (a first collision is not gated): a move
  /// brings the body's neighbours into the round, and in a jam the same pairs came back every round
  /// by fractions of a millimetre (`swept_pit`: ~185 pairs moved in each of the six rounds, 95 % of
  /// them moved already that step). Scaled with the pair's tolerances, as the target is.
  float leastMove = 0.001f;
};

/// What the stage reads of the step: all narrow-phase pairs of this step with their manifolds from
/// the step's start and their packed `edges`, and the bodies at their final poses.
struct TurnProjectionInput {
  BodyStore* bodies = nullptr;
  const std::vector<Shape>* shapes = nullptr;
  const ContactList* contacts = nullptr;
  const ContactEdge* edges = nullptr;
  const uint8_t* jointed = nullptr;   ///< per body: it has a joint (it is not moved); null: none has
  const std::vector<uint32_t>* pinched = nullptr;  ///< the contacts marked pinched (haif/pinch.h); null: none
  Vec3 up = Vec3::UnitY();
  const float* reach = nullptr;       ///< per body: bounding radius about its centre (m)
  /// Per body: its factor on the contact tolerances (haif/small_bodies.h); a pair's comes from its
  /// bodies' by pairToleranceScale (as Contact::toleranceScale). Null: 1 for every body.
  const float* toleranceScale = nullptr;
  const Aabb* startBounds = nullptr;  ///< per body: tight box at the step's start
  float dt = 0.0f;
  float contactMargin = 0.0f;  ///< the narrow phase's base margin (m)
};

class TurnProjection {
 public:
  /// Applies the stage; returns the number of pairs moved apart. `parallelFor(n, grain, f)` runs
  /// f(begin, end) over [0, n) in chunks of at least `grain`, on any threads: the per-body and
  /// per-pair scans and each round's collisions run through it. Bodies are read in index order and
  /// pairs moved in height order, so the result does not depend on the threads.
  template <class ParallelFor>
  uint32_t apply(const TurnProjectionInput& in, const TurnProjectionSettings& settings, ParallelFor&& parallelFor);
  /// The same on the calling thread.
  uint32_t apply(const TurnProjectionInput& in, const TurnProjectionSettings& settings) {
    return apply(in, settings, serialFor);
  }
  /// Pairs the last apply collided again (a pair counts each time; not those its boxes told apart).
  uint32_t collisions() const { return collisions_; }
  /// Pairs the last apply left without a collision where their boxes overlap: their overlap along
  /// their normal (or the line of their centres) kept them within their target (reachBound).
  uint32_t settledByReach() const { return settled_; }

 private:
  /// Bodies a chunk of the per-body scan takes (a few loads each).
  static constexpr uint32_t kBodyChunk = 4096;
  /// Pairs a chunk of the candidate scan takes (a bound from packed data, most pairs stop there).
  static constexpr uint32_t kPairChunk = 1024;
  /// Pairs a task of a round's collisions takes: 0.1 to 10 microseconds each, very uneven.
  static constexpr uint32_t kCollideChunk = 16;
  /// Bodies a task of a round's boxes takes (a hull's box reads its vertices).
  static constexpr uint32_t kBoxChunk = 64;
  /// Rounds of pairs: the candidates, then those of the bodies each round moved.
  static constexpr int kRounds = 6;

  // The stages of apply, in order; each `(begin, end)` one runs on any thread over its range.
  bool begin(const TurnProjectionInput& in, const TurnProjectionSettings& settings);
  void scanBodies(uint32_t begin, uint32_t end);
  void scanPairs(uint32_t begin, uint32_t end);
  void settleByReach(uint32_t contact);  // scanPairs' last word on a candidate
  /// A bound on the depth a collision of the pair would find at the current poses (settleByReach).
  float reachBound(uint32_t contact) const;
  /// `depth` keeps the pair within its target and the least move: it is not moved.
  bool withinTarget(uint32_t contact, float depth) const;
  bool collectCandidates();  // also notes which bodies need a final box, and the held bodies
  void boxBodies(uint32_t begin, uint32_t end);  // the bodies listed in toBox_
  void boxPairs();
  bool gatherRound(int round);  // also lists the bodies its pairs need boxes of
  void collideAhead(uint32_t begin, uint32_t end);
  bool resolveRound();

  float target(uint32_t contact) const;
  /// The excess the pair must pass to be moved: settings' leastMove scaled, never under the rounding.
  float leastMove(const ContactEdge& pair) const;
  /// The pair's tolerance factor, read from its bodies: the contacts are large, and the bound below
  /// runs on many pairs of a churning pile (reading it from the contact was most of its time).
  float toleranceScale(const ContactEdge& pair) const {
    return in_.toleranceScale ? pairToleranceScale(in_.toleranceScale[pair.a], in_.toleranceScale[pair.b]) : 1.0f;
  }
  /// The stage only translates bodies, and a pair's depth depends on where one body is relative to
  /// the other: translated relative to each other by t, it deepens by at most |t|. A pair whose depth
  /// was at most `known_` when one body was shifted `knownShift_` relative to the other is at most
  /// that plus how far that relative shift has changed since. Pairs this bound keeps under their
  /// target are not collided again (most pairs of a moved body in a churning pile, and the pairs of
  /// bodies a jam pushed the same way).
  bool mayExceed(uint32_t contact) const;
  /// Lists `body` for a box (boxBodies) unless it has one.
  void needBox(uint32_t body);
  void boxNow(uint32_t body);  // boxes `body` here unless it has a box (a serial stage's needBox)
  Aabb solvedBox(uint32_t body) const;  // its box at the pose the solver left it
  /// How far apart (m) the pair's boxes are at the bodies' current poses; negative: they overlap.
  float boxGap(const ContactEdge& pair) const;
  /// The depth of the pair's deepest point at the current poses (and its normal, from a to b). Boxes
  /// apart: minus their gap, without a collision (most pairs of a churning pile that find no point:
  /// a pair that far apart is no deeper than that). With `tryReach`, a reach bound within the target
  /// (reachBound) is returned instead of colliding. No point: -inf.
  enum class Probe : uint8_t { kBoxesApart, kBounded, kCollided };  // how depthNow found the depth
  float depthNow(uint32_t contact, Vec3& normal, bool tryReach, Probe& how) const;
  void count(Probe how) {
    collisions_ += how == Probe::kCollided;
    settled_ += how == Probe::kBounded;
  }
  void noteDepth(uint32_t contact, float depth, const Vec3& shift);
  Vec3 relativeShift(uint32_t a, uint32_t b) const { return shift_[a] - shift_[b]; }
  bool takeable(const ContactEdge& pair) const;  // a round may collide it again
  bool jointed(uint32_t body) const;
  bool movable(uint32_t body) const;

  // What the stage reads (set by begin).
  TurnProjectionInput in_;
  TurnProjectionSettings settings_;
  uint32_t moved_ = 0;
  uint32_t collisions_ = 0;
  uint32_t settled_ = 0;
  uint32_t clock_ = 0;   // moves are numbered: a pair is collided again only if a body moved since
  uint32_t roundStart_ = 0;
  int round_ = 0;

  /// A round's collision of one pair, made at the round's start poses.
  struct Ahead {
    float depth = 0.0f;  // of the deepest point (-inf: no point; depthNow)
    Vec3 shift = Vec3::Zero();  // the pair's relative shift at the round's start
    Vec3 normal = Vec3::UnitY();
    Probe how = Probe::kBoxesApart;
  };

  std::vector<uint8_t> turned_;     // per body: |w| dt above the angle
  std::vector<uint8_t> active_;     // per body: moved by the last round
  std::vector<float> spinReach_;    // per body: |w| reach, the fastest any point of it moves about its centre
  // Per contact: 1 collide again, 2 if the final boxes overlap; kSettled (scanPairs only): the
  // support bound keeps it within its target.
  std::vector<uint8_t> candidate_;
  static constexpr uint8_t kSettled = 3;
  // Per body: its tight box at the pose the solver left it (where boxed_): the stage only translates
  // bodies, so at any later pose it is this box moved by shift_.
  std::vector<uint8_t> boxed_;
  std::vector<Aabb> box_;
  std::vector<uint32_t> toBox_;     // bodies to box next (boxBodies)
  std::vector<uint32_t> boxPairs_;  // contacts whose final boxes decide
  std::vector<uint8_t> held_;       // per body: pinched between immovable ones: not moved
  std::vector<uint32_t> movedAt_;     // per body: the move clock when it last moved (0: not this step)
  std::vector<uint32_t> collidedAt_;  // per contact: the move clock when it was last collided again
  std::vector<Vec3> shift_;           // per body: the translation this stage has given it this step (m)
  std::vector<float> known_;          // per contact: a bound on its depth (m) ...
  std::vector<Vec3> knownShift_;      // ... when its bodies' relative shift was this
  std::vector<uint32_t> pairStart_, pairOf_, fill_;  // per body: its takeable pairs (CSR)
  std::vector<uint32_t> queuedIn_;  // per contact: the round it was last queued in, + 1
  std::vector<std::pair<float, uint32_t>> pairs_;  // (height, contact) of this round, lowest first
  std::vector<std::pair<float, uint32_t>> later_;  // min-heap: pairs a move of this round brought in
  std::vector<Ahead> ahead_;                       // per entry of pairs_
};

template <class ParallelFor>
uint32_t TurnProjection::apply(const TurnProjectionInput& in, const TurnProjectionSettings& settings,
                               ParallelFor&& parallelFor) {
  if (!begin(in, settings)) return 0;
  const uint32_t n = uint32_t(in.bodies->size());
  parallelFor(n, kBodyChunk, [&](uint32_t b, uint32_t e) { scanBodies(b, e); });
  parallelFor(uint32_t(in.contacts->size()), kPairChunk, [&](uint32_t b, uint32_t e) { scanPairs(b, e); });
  if (!collectCandidates()) return 0;  // most steps of most scenes: nothing more to read
  auto boxListed = [&] { parallelFor(uint32_t(toBox_.size()), kBoxChunk, [&](uint32_t b, uint32_t e) { boxBodies(b, e); }); };
  if (!boxPairs_.empty()) {
    boxListed();
    boxPairs();
  }
  // Each round's pairs are collided ahead, in parallel, at the poses the round starts from; then
  // taken in height order, where a pair whose body an earlier pair of the round moved is collided
  // again on the spot (as taking them one by one would).
  for (int round = 0; round < kRounds && gatherRound(round); ++round) {
    boxListed();
    parallelFor(uint32_t(pairs_.size()), kCollideChunk, [&](uint32_t b, uint32_t e) { collideAhead(b, e); });
    if (!resolveRound()) break;
  }
  return moved_;
}

}  // namespace haif
