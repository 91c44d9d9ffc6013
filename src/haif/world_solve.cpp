// The island solver: rows prepared and warm started, the main sweeps (with momentum and early
// stops), spare iterations shared, the relax sweeps after integration and the impulses stored.
#include "haif/world_internal.h"

#include "dynamics/mass_ratio.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace haif {

namespace {

// Largest velocity correction (m/s) below which a sweep takes no momentum step: the island has
// converged to float noise, and a conjugate step there only costs time.
constexpr float kMomentumFloor = 1e-5f;
/// Without gravity, nothing rests: a small island with a mass ratio is solved exactly whenever a row
/// closes faster than this (m/s).
constexpr float kLandingSpeedWithoutGravity = 0.01f;
/// Steps a small island with a mass ratio is still solved exactly after its last landing.
constexpr uint8_t kExactStepsAfterLanding = 30;
/// An island some body of which moves faster than this share of |g| dt (4 cm/s at 60 Hz) gets main
/// sweeps for its depth (World::sweepsForDepth); a nudged tower's sway starts about there.
constexpr float kDepthSweepSpeed = 0.25f;
/// Sweeps of a step whose rounds did not settle, after which a small island is swept (sweepIsland).
constexpr int kUnsettledSweepsToSweep = 2;

}  // namespace

SolverParams World::solverParams() const {
  SolverParams sp = settings_.contact;
  sp.dt = settings_.dt;
  sp.rolling = hasRolling_;
  // The anchors pull only where rest damping cannot hold a pile's creep (no gravity, or damping
  // off): both stop the creep of resting contacts, and the anchors' pull also feeds the sway of a
  // pile set sliding, which then topples (docs/solver.md, "Friction anchors").
  if (restDampingSpeed(settings_.restDamping, settings_.gravity, settings_.dt) > 0.0f) sp.frictionAnchors = false;
  return sp;
}

int World::relaxIterationsFor(int iterations) {
  // A quarter of the iterations (at least one) relax: enough to take the push-out velocity away.
  return iterations >= 2 ? std::max(1, iterations / 4) : 0;
}

float World::supportLayers(uint32_t k) const {
  const Island& isl = islands_.islands[k];
  if (isl.bodyCount == 0) return 0.0f;
  const Vec3 up = upDirection(), absUp = up.cwiseAbs();
  float top = -1e30f, bottom = 1e30f, heights = 0.0f;
  for (uint32_t j = 0; j < isl.bodyCount; ++j) {
    const Aabb& b = bounds_[islands_.bodies[isl.firstBody + j]];
    const float centre = 0.5f * up.dot(b.lo + b.hi), half = 0.5f * absUp.dot(b.hi - b.lo);
    top = std::max(top, centre + half);
    bottom = std::min(bottom, centre - half);
    heights += 2.0f * half;
  }
  return heights > 0.0f ? (top - bottom) * float(isl.bodyCount) / heights : 0.0f;
}

// One sweep over island k: its contacts, then its joints. Joints after contacts: the joint tree,
// solved exactly, ends each sweep intact. The other way round crates landing on a rope bridge left
// their joints open, and Baumgarte turned that into a bounce.
SweepResult World::sweepIsland(uint32_t k, bool useBias, bool restartDirection, bool measureChange) {
  const Island& isl = islands_.islands[k];
  ContactConstraint* cs = constraints_.data() + isl.firstContact;
  const float omega = settings_.contact.omega;
  SweepResult r;
  bool coupledSettled = false;  // solved through the joints, the rounds settled on the system's factor
  if (isChain_[k]) {
    // Contacts out of reach follow the chain (moveOutOfReachToTail), swept as usual.
    const uint32_t chained = isl.contactCount - tailOf(k);
    ChainLink* links = chainLinks_.data() + isl.firstContact;
    if (isChain_[k] == kChainSolve) {
      r = solveChainIteration(bodies_, cs, links, chained, omega, useBias);
    } else {
      const JointCoupling coupling = isChain_[k] == kJointCoupledSolve ? jointCouplingOf(k) : JointCoupling{};
      DenseNormalSystem& system = denseSystems_[denseOf_[k]];
      const int unsettled = system.unsettledSweeps;
      r = solveSmallIslandIteration(bodies_, cs, links, chained, omega, useBias, system,
                                    coupling.tree ? &coupling : nullptr);
      coupledSettled = coupling.tree && system.unsettledSweeps == unsettled && !system.jointsUnsound;
      if (system.jointsUnsound) isChain_[k] = 0;  // the joints cannot carry the rows: swept this step
      // Rounds that do not settle twice in a step will not: they factored the system kChainRounds
      // times a sweep only to fall back on the manifolds' passes (a 20 t ball among 250 kg bricks,
      // 63 contacts: every sweep, 80 factors and 15 ms a step). Swept for the rest of the step.
      if (isChain_[k] == kSmallIslandSolve && system.unsettledSweeps >= kUnsettledSweepsToSweep) isChain_[k] = 0;
    }
    if (chained < isl.contactCount)
      r.merge(solveIteration(bodies_, cs + chained, isl.contactCount - chained, omega, useBias, restartDirection,
                             measureChange, hasRolling_));
  } else if (isWide(k)) {
    const LaneBatches lb = lanesOf(k);
    if (restartDirection) startDirectionLanes(cs, isl.contactCount, lb);
    r = forEachStrip(k, [&](uint32_t b, uint32_t e) {
      return solveIterationLanes(bodies_, cs + b, e - b, lb.from(b), omega, useBias);
    });
  } else {
    const VelocityView velocities = velocitiesOf(k);
    r = forEachStrip(
        k,
        [&](uint32_t b, uint32_t e) {
          return solveIteration(velocities, cs + b, e - b, omega, useBias, restartDirection, measureChange,
                                hasRolling_);
        },
        [&](uint32_t b1, uint32_t e1, uint32_t b2, uint32_t e2, SweepResult& r1, SweepResult& r2) {
          solveIterationPair(velocities, cs + b1, e1 - b1, cs + b2, e2 - b2, omega, useBias, restartDirection,
                             measureChange, hasRolling_, r1, r2);
        });
  }
  if (isl.jointCount > 0) {
    JointTree* tree = settings_.joints.treeSolve ? &jointTreeOf(k) : nullptr;
    // Servos through the tree, which answers them in its solve just after (dynamics/motor_mass.h);
    // solved through the joints, through the contacts too.
    if (tree) {
      float motors = 0.0f;
      if (!coupledSettled || !solveMotorsThroughContacts(bodies_, jointCouplingOf(k), cs, chainLinks_.data() + isl.firstContact,
                                                         denseSystems_[denseOf_[k]], useBias, motors))
        motors = solveTreeMotors(bodies_, jointConstraints_.data() + isl.firstJoint, treeMotorsOf(k), useBias);
      r.residual = std::max(r.residual, motors);
    }
    r.residual = std::max(r.residual, solveJointIteration(bodies_, jointConstraints_.data() + isl.firstJoint,
                                                          isl.jointCount, tree, omega, useBias));
  }
  return r;
}

VelocityView World::velocitiesOf(uint32_t k) {
  if (!slotted(k)) return VelocityView(bodies_);
  StripVelocities& sv = stripVelocities_[layoutOf_[k]];
  return VelocityView(sv.v.data(), sv.w.data());
}

void World::toSlots(uint32_t k, ContactConstraint& c) const {
  const StripVelocities& sv = stripVelocities_[layoutOf_[k]];
  auto slot = [&](uint32_t body, bool dynamic) {
    if (dynamic) return slotOf_[body];
    const auto at = std::lower_bound(sv.immovable.begin(), sv.immovable.end(), body);
    assert(at != sv.immovable.end() && *at == body);  // the splitter noted every one
    return sv.immovableSlot + uint32_t(at - sv.immovable.begin());
  };
  c.a = slot(c.a, c.dynA);
  c.b = slot(c.b, c.dynB);
}

void World::copyVelocitiesIn(uint32_t k) {
  StripVelocities& sv = stripVelocities_[layoutOf_[k]];
  const uint32_t slots = uint32_t(sv.bodyOf.size());
  for (uint32_t s = 0; s < slots; ++s) {
    sv.v[s] = bodies_.v[sv.bodyOf[s]];
    sv.w[s] = bodies_.w[sv.bodyOf[s]];
  }
}

void World::copyVelocitiesOut(uint32_t k) {
  const StripVelocities& sv = stripVelocities_[layoutOf_[k]];
  for (uint32_t s = 0; s < sv.dynamic; ++s) {
    bodies_.v[sv.bodyOf[s]] = sv.v[s];
    bodies_.w[sv.bodyOf[s]] = sv.w[s];
  }
}

LaneBatches World::lanesOf(uint32_t k) {
  const uint32_t first = islands_.islands[k].firstContact;
  return {laneRun_.data() + first, wideOf_.data() + first, wide_.data()};
}

// The lanes hold no rolling row: a world with rolling resistance sweeps every island as one.
bool World::isWide(uint32_t k) const { return settings_.wideSolve && !isChain_[k] && !hasRolling_; }

// The velocity at which point p of contact c's body b moves relative to its body a.
static Vec3 closingVelocity(const BodyStore& bodies, const Contact& c, const ContactPoint& p) {
  return bodies.velocityAt(c.b, p.position) - bodies.velocityAt(c.a, p.position);
}

// A contact out of reach by distance (the tail, moveOutOfReachToTail) that its bodies close within
// the step: a 100 kg box 3.2 cm above a stack of five 4 mm plates, landing at 2.1 m/s. Swept after
// the plates' chain, at a mass ratio of 100 it took a fraction of the box's momentum a sweep: the box
// pressed the top plate 4.6 mm into the next at 10 sweeps and, at 48-64, drove the plates through
// each other to the ground. Counting such contacts in reach for every island instead made pours rest
// deeper (landing islands that were chains were then swept); only an island with a small-island
// system (a mass ratio, or deep) takes them, into that system.
static bool anyClosesWithinStep(const Contact* contacts, const BodyStore& bodies, const uint32_t* ids, uint32_t n,
                                float dt, float slop, float fall) {
  for (uint32_t j = 0; j < n; ++j) {
    const Contact& c = contacts[ids[j]];
    const float reach = contactReach(slop, c.toleranceScale, fall);
    for (int i = 0; i < c.manifold.count; ++i) {
      const ContactPoint& p = c.manifold.points[i];
      if (p.depth - p.normal.dot(closingVelocity(bodies, c, p)) * dt >= -reach) return true;
    }
  }
  return false;
}

// A landing solved together whose island is swept before it has rested (it grew past the system's
// size, or a joint joined it): the landing's impulses, met by every body at once, are no warm start
// for sweeps, which pass them through the light bodies a fraction at a time. Without this, a 20 t
// ball thrown onto a bed of 250 kg bricks was thrown up at 8-9 m/s, its landing's ~100 kN s on one
// brick warm-started into an island of 86 contacts (ApartContacts.ALandingSolvedTogether...).
static void forgetLandingImpulses(Contact& c) {
  std::fill(std::begin(c.normalImpulse), std::end(c.normalImpulse), 0.0f);
  c.frictionImpulse.setZero();
  c.twistImpulse = 0.0f;
  c.rollingImpulse.setZero();
  c.exactSteps = 0;
}

void World::solveIslands(int iterations) {
  const SolverParams sp = solverParams();
  const float tol = settings_.residualTolerance;
  const int iMin = std::min(controller_->iMin, iterations);
  for (uint32_t k = 0; k < denseOf_.size(); ++k)
    if (denseOf_[k] >= 0) denseSystems_[denseOf_[k]].startSolve();
  auto prepareIsland = [&](uint32_t k) {
    const Island& isl = islands_.islands[k];
    ContactConstraint* cs = constraints_.data() + isl.firstContact;
    const uint32_t* ids = islands_.contacts.data() + isl.firstContact;
    const bool slots = slotted(k);
    const bool swept = denseOf_[k] < 0;
    forEachContactChunk(k, kPrepareChunk, [&](uint32_t begin, uint32_t end) {
      for (uint32_t j = begin; j < end; ++j) {
        // Contacts are visited in solve order, scattered through memory: the one a few ahead is
        // fetched while this one is prepared (the waits were a fifth of prepare in many_pyramids).
        if (j + kPrefetchAhead < end) prefetchContact(contacts_[ids[j + kPrefetchAhead]]);
        if (swept && contacts_[ids[j]].exactSteps > 0) forgetLandingImpulses(contacts_[ids[j]]);
        prepareContact(bodies_, contacts_[ids[j]], ids[j], sp, cs[j]);
        if (slots) toSlots(k, cs[j]);
      }
    });
    if (slots) copyVelocitiesIn(k);
    // A landing through the tail (a contact out of reach by distance that its bodies close within the
    // step): the whole island goes into its small-island system, the tail no longer behind a chain.
    const bool landsThroughTail = denseOf_[k] >= 0 && tailOf(k) > 0 && isl.jointCount == 0 &&
                                  anyClosesWithinStep(contacts_.data(), bodies_, ids + isl.contactCount - tailOf(k),
                                                      tailOf(k), settings_.dt, settings_.contact.slop, fallOfAStep()) &&
                                  prepareSmallIsland(contacts_.data(), cs, isl.contactCount,
                                                     chainLinks_.data() + isl.firstContact, denseRows_[k]);
    if (landsThroughTail) {
      order_.tail[k] = 0;
      isChain_[k] = kSmallIslandSolve;
    } else {
      isChain_[k] = settings_.chainSolve && layoutOf_[k] < 0 && isl.jointCount == 0 &&
                    prepareChain(contacts_.data(), cs, isl.contactCount - tailOf(k), chainMark_.data(),
                                 chainLinks_.data() + isl.firstContact);
      if (!isChain_[k] && denseOf_[k] >= 0 && isl.jointCount == 0 &&
          prepareSmallIsland(contacts_.data(), cs, isl.contactCount - tailOf(k),
                             chainLinks_.data() + isl.firstContact, denseRows_[k]))
        isChain_[k] = kSmallIslandSolve;
    }
    const VelocityView velocities = velocitiesOf(k);
    if (sp.warmStart) forEachStrip(k, [&](uint32_t b, uint32_t e) {
      warmStart(velocities, cs + b, e - b);
      return SweepResult{};
    });
    if (isWide(k)) forEachLaneRange(k, packLanes);
    if (isl.jointCount > 0) prepareJoints(k, sp);
    // Contacts whose push the joints carry away are solved through them (its rows need the tree).
    if (denseOf_[k] >= 0 && isl.jointCount > 0 && jointTreeOf(k).size() == isl.jointCount) {
      ChainLink* links = chainLinks_.data() + isl.firstContact;
      const uint32_t n = isl.contactCount - tailOf(k);
      const float ratio = settings_.exactMassRatio * kJointCoupledRatioFactor;
      if (prepareSmallIsland(contacts_.data(), cs, n, links, denseRows_[k], 1) &&
          jointsCarryContacts(bodies_, jointCouplingOf(k), cs, links, n, ratio)) {
        isChain_[k] = kJointCoupledSolve;
        denseSystems_[denseOf_[k]].jointsHeld = denseSystems_[denseOf_[k]].jointsUnsound = false;
      }
    }
  };
  auto sweepIslandMain = [&](uint32_t k) {
    const Island& isl = islands_.islands[k];
    ContactConstraint* cs = constraints_.data() + isl.firstContact;
    // Momentum on the contacts of deep joint-free islands. A joint tree is solved exactly every
    // sweep, and so is a chain: nothing for momentum to carry. Momentum carries the weight of a
    // deep pile down faster than sweeps alone (a 30-box column stands on it), but a low pile in
    // top-down order converges as fast without it, and there it only adds overshoot. Box pyramids
    // at 10 iterations, 300 steps, solve error without / with momentum: base 10 0.028 / 0.059,
    // base 15 0.117 / 0.160, base 20 0.27 / 0.33 but at 5 iterations 0.84 / 0.70 and a third less
    // drop, base 30 0.79 / 0.66 with half the drop.
    const bool cg = settings_.accelerate && isl.jointCount == 0 && !isChain_[k] &&
                    supportLayers(k) >= settings_.momentumLayers;
    const bool wide = isWide(k);
    const LaneBatches lb = wide ? lanesOf(k) : LaneBatches{};
    const VelocityView velocities = velocitiesOf(k);
    double lastChange = 0.0;
    int it = 0;
    float residual = 0.0f;
    bool restart = false;  // the next sweep starts the direction from this sweep's change
    depthSweeps_[k] = isChain_[k] ? 0 : sweepsForDepth(k, iterations);
    const int sweeps = iterations + depthSweeps_[k];
    while (it < sweeps) {
      const SweepResult sweep = sweepIsland(k, true, restart, cg);
      restart = false;
      residual = sweep.residual;
      ++it;
      // Converged islands stop: precision nobody can see is not paid for. A chain stops as soon as
      // a sweep changes nothing: its sweeps solve it exactly, so I_min's guard against a sweep that
      // only looks converged is not needed there.
      if (tol > 0.0f && (it >= iMin || isChain_[k]) && residual < tol) break;
      if (!cg || it == sweeps) continue;  // the main sweeps end on a sweep, not a momentum step
      if (residual < kMomentumFloor) {
        lastChange = 0.0;  // converged: no momentum to carry; a later sweep starts a new direction
        continue;
      }
      const double change = sweep.change;
      if (it == 1 || lastChange <= 0.0 || change > lastChange) {
        // First direction, or a restart: the last step overshot. The next sweep copies it, before
        // it overwrites the changes, and no momentum step comes before that sweep.
        restart = true;
      } else {
        const float beta = float(change / lastChange);
        forEachStrip(k, [&](uint32_t b, uint32_t e) {
          if (wide) accelerateLanes(bodies_, cs + b, e - b, lb.from(b), beta);
          else accelerate(velocities, cs + b, e - b, beta);
          return SweepResult{};
        });
      }
      lastChange = change;
    }
    spare_.iterations[k] = isl.contactCount + isl.jointCount > 0 ? it : 0;
    spare_.residual[k] = residual;
  };
  forEachIslandTimed(prepareIsland, sweepIslandMain);
  if (tol > 0.0f && iterations > 0) shareSpareIterations(iterations);
  // Integration reads the bodies' own velocities; the rows keep naming slots until they are stored.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  for (uint32_t k = 0; k < m; ++k)
    if (slotted(k)) copyVelocitiesOut(k);
}

// Islands that converged early leave part of the step's work unspent: Σ (I − run) × rows. That
// budget goes to islands still above the tolerance, the largest residual first (where a sweep
// buys the most accuracy), each at most doubling its count (a bound that depends only on I, so
// replaying the counts reproduces the run).
void World::shareSpareIterations(int iterations) {
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  uint64_t spare = 0;
  for (uint32_t k = 0; k < m; ++k)
    spare += uint64_t(iterations - std::min(iterations, spare_.iterations[k])) * islands_.islands[k].rows;
  spare_.extra.assign(m, 0);
  bool any = false;
  const float tol = settings_.residualTolerance;
  spare_.order.clear();
  for (uint32_t k = 0; k < m; ++k)
    if (islands_.islands[k].rows > 0 && spare_.residual[k] >= tol) spare_.order.push_back(k);
  // Ties broken by index: the order, and so the state, does not depend on the thread count.
  std::sort(spare_.order.begin(), spare_.order.end(), [&](uint32_t x, uint32_t y) {
    return spare_.residual[x] != spare_.residual[y] ? spare_.residual[x] > spare_.residual[y] : x < y;
  });
  for (const uint32_t k : spare_.order) {
    if (spare == 0) break;
    const uint32_t rows = islands_.islands[k].rows;
    const int extra = int(std::min<uint64_t>(uint64_t(iterations), spare / rows));
    if (extra == 0) continue;
    spare_.extra[k] = extra;
    spare -= uint64_t(extra) * rows;
    any = true;
  }
  if (!any) return;
  forEachIslandTimed([](uint32_t) {}, [&](uint32_t k) {  // sweeps only
    int it = 0;
    float residual = spare_.residual[k];
    while (it < spare_.extra[k] && residual >= tol) {
      residual = sweepIsland(k, true).residual;
      ++it;
    }
    spare_.iterations[k] += it;
    spare_.residual[k] = residual;
  });
}

// A small island (up to kCheapLinks contacts) deeper than this step's main sweeps reach is solved
// together, as a chain is: a sweep passes a landing down about one layer, and a column of 20 boxes
// landing through its gaps with a box beside its foot (no chain: the box touches two of them)
// bounced at 3 main sweeps, leaned and fell. Larger islands cost too much to factor every step (a
// 12-layer tower of 2-block layers, 46 contacts: 0.8 ms a step, and 30 of them beside a pour took an
// adaptive run's 95th-percentile step from 5.8 to 24.9 ms). Judged by this step's sweeps, not the
// controller's fewest: an adaptive run that gives many sweeps keeps them (30 columns of 20 boxes:
// 0.75 ms a step swept at ~60 sweeps, 2.4-2.9 ms solved together at the floor's 9 layers).
bool World::tooDeepForSweeps(uint32_t k, int mainSweeps) const {
  const Island& isl = islands_.islands[k];
  const float deep = settings_.deepLayersPerSweep * float(mainSweeps);
  // More contacts than bodies: no lone column, which the chain solve takes (stacks_N's 200 columns
  // would each hold a dense system's storage for nothing). Those out of reach count: landing
  // through its gaps, a column beside a box has few in reach, and it is then that it needs this.
  return settings_.chainSolve && deep > 0.0f && isl.jointCount == 0 && layoutOf_[k] < 0 &&
         isl.contactCount > isl.bodyCount && isl.contactCount <= uint32_t(DenseNormalSystem::kCheapLinks) &&
         supportLayers(k) > deep;
}

// Swept, a tower of loose blocks (no chain: each block stands on two) settles its sway about half a
// layer a sweep; the part left over each step grows, and push-out and the turn projection feed it,
// until the tower falls: towers of crossed 2-block layers nudged at 5 cm/s fell from 8 layers at 4
// iterations and from 12 at 10, and stood with one main sweep per half layer (at 30 iterations a
// 12-layer tower nudged at 0.3 m/s stood; at 20 it fell). Only while a body moves: at rest the warm
// start holds the same towers at 4 iterations, and a resting pile pays nothing (many_pyramids' 196
// ten-layer pyramids keep their count). Split islands are the giant ones; chains and islands solved
// together are solved exactly.
int World::sweepsForDepth(uint32_t k, int mainSweeps) const {
  const Island& isl = islands_.islands[k];
  const float perSweep = settings_.movingLayersPerSweep;
  const float g = settings_.gravity.norm();
  // Under a frame budget the controller's count stands: it plans the step's sweeps over every row,
  // and sweeps it did not plan for (a drum's churning pile, deep and never at rest) took drum_fast's
  // missed steps from 1.0 % to 6.9 % at 4 ms. Where the budget allows, its counts are the towers' own.
  if (!(perSweep > 0.0f) || !(g > 0.0f) || settings_.budgetMs > 0.0 || isl.jointCount > 0 || layoutOf_[k] >= 0 ||
      isl.contactCount == 0)
    return 0;
  const float moving = kDepthSweepSpeed * g * settings_.dt;
  bool moves = false;
  for (uint32_t j = 0; j < isl.bodyCount && !moves; ++j) {
    const uint32_t b = islands_.bodies[isl.firstBody + j];
    const float reach = 0.5f * (bounds_[b].hi - bounds_[b].lo).norm();
    moves = bodies_.v[b].norm() + bodies_.w[b].norm() * reach > moving;
  }
  if (!moves) return 0;
  return std::max(0, int(std::ceil(supportLayers(k) / perSweep)) - mainSweeps);
}

// A small island with a mass ratio is solved together from a landing in it (a point closing faster
// than a body at rest does: 2 g dt, the cold start's rule) until it has rested for
// kExactStepsAfterLanding: the landing's impulses are no warm start for sweeps, which at a mass ratio
// pass a change through a light body a fraction per sweep. At rest the warm start holds the island,
// and sweeps cost less than factoring its system every step (tower_collapse's debris, solved so every
// step: 0.25 → 0.41 ms a step).
bool World::wantsSmallIslandSolve(uint32_t k) {
  const Island& isl = islands_.islands[k];
  if (!(settings_.exactMassRatio > 0.0f) || isl.jointCount > 0 || layoutOf_[k] >= 0 || isl.contactCount < 2 ||
      isl.contactCount > uint32_t(DenseNormalSystem::kMaxLinks))
    return false;
  // Islands past kCheapLinks contacts only where sweeps are hopeless: their factor costs the cube of
  // their rows and is made again whenever a round lets a link go (tower_collapse's debris, a ratio of
  // 4.3, solved so up to 64 contacts: 1.2 → 3.5 ms at the 95th percentile of its step).
  const float needed = isl.contactCount > uint32_t(DenseNormalSystem::kCheapLinks)
                           ? settings_.exactMassRatio * DenseNormalSystem::kLargeIslandRatioFactor
                           : settings_.exactMassRatio;
  const uint32_t* ids = islands_.contacts.data() + isl.firstContact;
  bool ratio = false;
  for (uint32_t j = 0; j < isl.contactCount && !ratio; ++j) {
    const ContactEdge& c = contactEdges_[ids[j]];
    const float ma = bodies_.mass[c.a], mb = bodies_.mass[c.b];
    ratio = ma > 0.0f && mb > 0.0f && massesDiffer(ma, mb, needed);
  }
  if (!ratio) return false;
  const float g = settings_.gravity.norm();
  const float landingSpeed = g > 0.0f ? 2.0f * g * settings_.dt : kLandingSpeedWithoutGravity;
  const float slop = settings_.contact.slop;
  bool landing = false, settling = false;
  for (uint32_t j = 0; j < isl.contactCount && !landing; ++j) {
    const Contact& c = contacts_[ids[j]];
    for (int i = 0; i < c.manifold.count; ++i) {
      const ContactPoint& p = c.manifold.points[i];
      landing |= p.depth <= slop * c.toleranceScale && p.normal.dot(closingVelocity(bodies_, c, p)) < -landingSpeed;
    }
  }
  for (uint32_t j = 0; j < isl.contactCount; ++j) {
    uint8_t& left = contacts_[ids[j]].exactSteps;
    settling |= left > 0;
    left = landing ? kExactStepsAfterLanding : uint8_t(left > 0 ? left - 1 : 0);
  }
  return landing || settling;
}

bool World::mayCoupleJoints(uint32_t k) const {
  const Island& isl = islands_.islands[k];
  return settings_.exactMassRatio > 0.0f && settings_.joints.treeSolve && isl.jointCount > 0 &&
         isl.contactCount > 0 && isl.contactCount <= uint32_t(DenseNormalSystem::kCheapLinks) && layoutOf_[k] < 0;
}

JointCoupling World::jointCouplingOf(uint32_t k) {
  const Island& isl = islands_.islands[k];
  JointCoupling c;
  c.tree = &jointTreeOf(k);
  c.joints = jointConstraints_.data() + isl.firstJoint;
  c.jointCount = isl.jointCount;
  c.dv = couplingDv_.data();
  c.dw = couplingDw_.data();
  c.changeV = couplingChangeV_.data();
  c.changeW = couplingChangeW_.data();
  c.contacts = constraints_.data() + isl.firstContact;
  c.contactCount = isl.contactCount - tailOf(k);
  c.motors = &treeMotorsOf(k);
  return c;
}

bool World::onlyPinned(uint32_t k) const {
  const Island& isl = islands_.islands[k];
  for (uint32_t j = 0; j < isl.bodyCount; ++j)
    if (!bodies_.pinned[islands_.bodies[isl.firstBody + j]]) return false;
  return isl.bodyCount > 0;
}

void World::relaxIslands(int relaxIterations) {
  const SolverParams sp = solverParams();
  // An island given main sweeps for its depth relaxes a third as many more: the push-out its sweeps
  // added is taken away as far as they reached (without, a nudged 20-layer tower fell at 4 iterations).
  auto relaxSweepsOf = [&](uint32_t k) { return relaxIterations > 0 ? relaxIterations + depthSweeps_[k] / 3 : 0; };
  auto relax = [&](uint32_t k) {
    const bool slots = slotted(k);
    if (slots) copyVelocitiesIn(k);  // as integration, damping and the speed bound left them
    // A chain keeps the factors of its rows from the main sweeps, and a jointed island's joint rows
    // were built with the stiffened inertia that integration has since reset (stiffenJointedBodies;
    // re-aimed contact rows next to them gained energy in random mixed worlds): their rows stay as
    // they were. Lanes hold packed copies: a batch with a row to re-aim is packed again (left
    // out, a wide large_pyramid collapsed in 3600 steps at 4 iterations).
    if (relaxIterations > 0 && !isChain_[k] && islands_.islands[k].jointCount == 0) {
      const Island& isl = islands_.islands[k];
      ContactConstraint* cs = constraints_.data() + isl.firstContact;
      if (isWide(k)) {
        forEachLaneRange(k, [&](ContactConstraint* rows, size_t n, const LaneBatches& lanes) {
          reaimLanesForRelax(bodies_, contacts_.data(), sp, rows, n, lanes);
        });
      } else {
        const Vec3* linear = velocitiesOf(k).v;
        forEachContactChunk(k, kContactChunk, [&](uint32_t b, uint32_t e) {
          for (uint32_t j = b; j < e; ++j)
            if (reaimForRelax(bodies_, linear, contacts_[cs[j].contact], sp, cs[j]) && slots) toSlots(k, cs[j]);
        });
      }
    }
    // An island of pinned bodies without contacts holds its joints exactly after integration
    // (integratePinned); its rows are the step start's, and sweeping them there took a spinning
    // top's spin down by 7 % in 5 s.
    if (islands_.islands[k].contactCount == 0 && onlyPinned(k)) return;
    for (int it = 0; it < relaxSweepsOf(k); ++it) sweepIsland(k, false);
  };
  auto store = [&](uint32_t k) {
    if (slotted(k)) copyVelocitiesOut(k);
    const Island& isl = islands_.islands[k];
    ContactConstraint* cs = constraints_.data() + isl.firstContact;
    if (isWide(k)) forEachLaneRange(k, unpackLanes);
    forEachContactChunk(k, kContactChunk, [&](uint32_t b, uint32_t e) { storeImpulses(cs + b, e - b, contacts_.data()); });
    if (isl.jointCount > 0) finishJoints(k);
    if (isl.contactCount + isl.jointCount > 0) spare_.iterations[k] += relaxSweepsOf(k);
  };
  forEachIslandTimed(relax, store, /*firstIsSweeps=*/true);
}

void World::solve(int iterations) {
  // Iterations with position correction now; the relax iterations run after integration.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  jointMainSweeps_ = iterations;  // the reference solve of measureSolveError keeps the step's rows
  constraints_.resize(islands_.contacts.size());
  chainLinks_.resize(constraints_.size());
  chainMark_.resize(bodyCount());
  isChain_.assign(m, 0);
  denseOf_.assign(m, -1);
  depthSweeps_.assign(m, 0);
  int32_t dense = 0;
  size_t storage = 0;
  bool coupling = false;
  denseRows_.assign(m, 0);
  for (uint32_t k = 0; k < m; ++k) {
    // A deep island has room for all of its rows (up to 96); one with a mass ratio, denseRowsOf's.
    const bool deep = tooDeepForSweeps(k, iterations);
    if (deep || wantsSmallIslandSolve(k) || mayCoupleJoints(k)) {
      coupling |= islands_.islands[k].jointCount > 0;
      denseOf_[k] = dense++;
      // A tail may land (solveIslands): room for the whole island's rows, as a deep island has.
      const bool roomForAll = deep || tailOf(k) > 0;
      denseRows_[k] = roomForAll ? std::min(int(3 * islands_.islands[k].contactCount), int(DenseNormalSystem::kMaxRows))
                                 : denseRowsOf(k);
      storage += DenseNormalSystem::doublesFor(denseRows_[k]);
    }
  }
  if (denseSystems_.size() < size_t(dense)) denseSystems_.resize(dense);  // both grow, then are reused
  if (coupling && couplingDv_.size() != bodyCount()) {
    couplingDv_.assign(bodyCount(), Eigen::Vector3d::Zero());
    couplingDw_.assign(bodyCount(), Eigen::Vector3d::Zero());
    couplingChangeV_.assign(bodyCount(), Eigen::Vector3d::Zero());
    couplingChangeW_.assign(bodyCount(), Eigen::Vector3d::Zero());
  }
  if (denseStorage_.size() < storage) denseStorage_.resize(storage);
  storage = 0;
  for (uint32_t k = 0; k < m; ++k)
    if (denseOf_[k] >= 0) {
      denseSystems_[denseOf_[k]].attach(denseStorage_.data() + storage, denseRows_[k]);
      storage += DenseNormalSystem::doublesFor(denseRows_[k]);
    }
  jointConstraints_.resize(islands_.joints.size());
  jointSlot_.assign(m, -1);
  int32_t slots = 0;
  for (uint32_t k = 0; k < m; ++k)
    if (islands_.islands[k].jointCount > 0) jointSlot_[k] = slots++;
  if (jointTrees_.size() < size_t(slots)) {  // both grow to the most jointed islands seen, then are reused
    jointTrees_.resize(size_t(slots));
    treeMotors_.resize(size_t(slots));
  }
  if (!joints_.empty()) stiffenJointedBodies();
  spare_.iterations.assign(m, 0);
  spare_.residual.assign(m, 0.0f);
  // Islands come largest first: big ones get a task each, small ones are batched. Those of one body
  // and no constraint come last and have nothing to prepare, sweep or store: the batches end before
  // them (30,000 bodies in flight: the solve stage 4.6 -> 0.3 ms a step at 2 threads).
  uint32_t solved = m;
  while (solved > 0 && islands_.islands[solved - 1].unconstrained()) --solved;
  batchStart_.clear();
  batchStart_.push_back(0);
  uint32_t acc = 0;
  for (uint32_t k = 0; k < solved; ++k) {
    acc += islands_.islands[k].rows;
    if (acc >= kBatchRows || k + 1 == solved) {
      batchStart_.push_back(k + 1);
      acc = 0;
    }
  }
  if (solved == 0) batchStart_.push_back(0);

  resetPhaseClocks();
  const bool measure = solveErrorEvery_ > 0 && stepCount_ % uint64_t(solveErrorEvery_) == 0 && m > 0;
  if (measure) stats_.solveError = measureSolveError(iterations);
  else solveIslands(iterations);
}

void World::summariseIterations() {
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  int lo = 1 << 30, hi = 0;
  double sum = 0.0;
  uint32_t counted = 0;
  float residual = 0.0f;
  uint64_t rowIt = 0;
  uint32_t factors = 0, unsettled = 0;
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    if (k < denseOf_.size() && denseOf_[k] >= 0) {
      factors += uint32_t(denseSystems_[denseOf_[k]].factors);
      unsettled = std::max(unsettled, uint32_t(denseSystems_[denseOf_[k]].unsettledSweeps));
    }
    if (isl.unconstrained()) continue;
    lo = std::min(lo, spare_.iterations[k]);
    hi = std::max(hi, spare_.iterations[k]);
    sum += spare_.iterations[k];
    ++counted;
    residual = std::max(residual, spare_.residual[k]);
    rowIt += uint64_t(isl.rows) * uint64_t(spare_.iterations[k]);
  }
  stats_.iterationsMin = counted ? lo : 0;
  stats_.iterationsMax = counted ? hi : 0;
  stats_.iterationsMean = counted ? sum / counted : 0.0;
  stats_.residual = residual;
  stats_.rowIterations = rowIt;
  stats_.exactFactors = factors;
  stats_.mostUnsettledSweeps = unsettled;
}

}  // namespace haif
