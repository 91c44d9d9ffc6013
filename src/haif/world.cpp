#include "haif/world.h"

#include "collision/collide.h"
#include "core/pose_hash.h"
#include "core/sort_key.h"
#include "dynamics/integrator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <cmath>
#include <algorithm>
#include <stdexcept>

namespace haif {

#ifdef HAIF_TSAN
constexpr bool kTsan = true;
#else
constexpr bool kTsan = false;
#endif

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Rows of an island whose total is below this are batched with their neighbours into one task,
/// so thousands of tiny islands do not each pay a task's overhead.
constexpr uint32_t kBatchRows = 1024;
// Islands with at least this many contacts have their top-down order sorted in parallel.
constexpr uint32_t kParallelSortContacts = 8192;
// Moved bodies whose broad-phase queries one task runs: a query is a few microseconds.
constexpr uint32_t kPairQueryGrain = 64;

/// An old contact point this close (m) to a new one passes on its impulse when ids do not match.
constexpr float kWarmStartMatchDistance = 0.02f;

/// Mass-weighted RMS velocity error (m/s) below which a solve's starting point counts as exact.
constexpr float kSolveErrorFloor = 1e-4f;
// Largest velocity correction (m/s) below which a sweep takes no momentum step: the island has
// converged to float noise, and a conjugate step there only costs time.
constexpr float kMomentumFloor = 1e-5f;

}  // namespace

World::World(const WorldSettings& settings) : settings_(settings) {
  controller_ = std::make_unique<FixedController>(settings_.iterations);
  setThreads(settings_.threads);
}

World::~World() = default;

void World::setController(std::unique_ptr<IterationController> c) { controller_ = std::move(c); }

void World::setThreads(int threads) {
  settings_.threads = std::max(1, threads);
  // The arena's worker threads are created once and reused by every step.
  arena_ = settings_.threads > 1 ? std::make_unique<tbb::task_arena>(settings_.threads) : nullptr;
#ifdef HAIF_TSAN
  pool_ = settings_.threads > 1 ? std::make_unique<TsanPool>(settings_.threads) : nullptr;
#endif
  phaseClocks_.assign(size_t(settings_.threads), PhaseClock{});
}

World::PhaseClock& World::phaseClock() {
#ifdef HAIF_TSAN
  const int slot = TsanPool::threadIndex();
#else
  const int slot = arena_ ? tbb::this_task_arena::current_thread_index() : 0;
#endif
  return phaseClocks_[slot >= 0 && size_t(slot) < phaseClocks_.size() ? size_t(slot) : 0];
}

void World::resetPhaseClocks() { std::fill(phaseClocks_.begin(), phaseClocks_.end(), PhaseClock{}); }

template <class F>
void World::parallelFor(uint32_t n, uint32_t grain, F&& f) {
  if (!arena_ || n <= grain) {
    if (n > 0) f(0u, n);
    return;
  }
#ifdef HAIF_TSAN
  pool_->run(n, grain, [&](uint32_t b, uint32_t e) { f(b, e); });
#else
  arena_->execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, grain),
                      [&](const tbb::blocked_range<uint32_t>& r) { f(r.begin(), r.end()); });
  });
#endif
}

uint32_t World::addBody(const BodyDef& def) {
  float mass = 0.0f;
  Mat3 inertia = Mat3::Zero();
  const MassProperties unit = computeMassProperties(def.shape, 1.0f);
  if (def.kind == BodyKind::Dynamic) {
    const MassProperties mp = bodyMassProperties(def.shape, def.density, def.mass);
    mass = mp.mass;
    inertia = mp.inertia;
  }
  const uint32_t id = bodies_.add(def.kind, def.xf, mass, inertia);
  bodies_.v[id] = def.linearVelocity;
  bodies_.w[id] = def.angularVelocity;
  bodies_.friction[id] = def.friction;
  bodies_.restitution[id] = def.restitution;
  bodies_.linearDamping[id] = def.linearDamping;
  bodies_.angularDamping[id] = def.angularDamping;
  shapes_.push_back(def.shape);
  volume_.push_back(unit.mass);
  bounds_.push_back(computeAabb(def.shape, def.xf));
  speedBound_.addBody(def.shape);
  if (def.kind == BodyKind::Static && def.shape.type != ShapeType::Plane) {
    // The static geometry's lowest point along up, for the speed bound (planes are unbounded).
    const Vec3 up = upDirection(), lo = bounds_[id].lo, hi = bounds_[id].hi;
    const float low = std::min(up.x() * lo.x(), up.x() * hi.x()) + std::min(up.y() * lo.y(), up.y() * hi.y()) +
                      std::min(up.z() * lo.z(), up.z() * hi.z());
    staticFloor_ = std::min(staticFloor_, low);
  }
  if (def.shape.type == ShapeType::TriangleMesh) hasMesh_ = true;
  islandOfBody_.push_back(-1);
  broadPhase_.addBody(id, bounds_[id], def.kind == BodyKind::Static);
  return id;
}

void World::wake(uint32_t body) {
  if (!bodies_.asleep[body]) return;
  const int32_t set = bodies_.sleepSet[body];
  auto wakeOne = [&](uint32_t i) {
    bodies_.asleep[i] = 0;
    bodies_.sleepSet[i] = -1;
    bodies_.restTime[i] = 0.0f;
  };
  if (set < 0) {
    wakeOne(body);
    return;
  }
  for (uint32_t i : sleepSets_[set]) wakeOne(i);
  sleepSets_[set].clear();
  freeSleepSets_.push_back(set);
}

// ---- joints ------------------------------------------------------------------------------

uint32_t World::addJoint(const JointDef& def) {
  auto valid = [&](uint32_t b) { return b == kWorldBody || b < bodyCount(); };
  if (!valid(def.bodyA) || !valid(def.bodyB)) throw std::invalid_argument("addJoint: unknown body");
  if (def.bodyA == def.bodyB) throw std::invalid_argument("addJoint: a joint needs two different bodies");
  Joint j;
  j.def = def;
  joints_.push_back(j);
  for (uint32_t b : {def.bodyA, def.bodyB})
    if (b != kWorldBody) bodies_.implicitGyro[b] = 1;  // see integratePositions
  if (!def.collideConnected && def.bodyA != kWorldBody && def.bodyB != kWorldBody) {
    // Jointed bodies usually overlap at the joint: keep the pair out of the contact list.
    const uint64_t key = PairMap::key(def.bodyA, def.bodyB);
    const uint32_t n = jointPairs_.find(key);
    jointPairs_.set(key, n == PairMap::kNotFound ? 1u : n + 1u);
    const uint32_t ci = pairs_.find(key);
    if (ci != PairMap::kNotFound) {  // a contact made before the joint: remove it as the narrow phase does
      pairs_.erase(key);
      if (ci + 1 != contacts_.size()) {
        contacts_[ci] = contacts_.back();
        pairs_.set(PairMap::key(contacts_[ci].a, contacts_[ci].b), ci);
      }
      contacts_.pop_back();
    }
  }
  return static_cast<uint32_t>(joints_.size() - 1);
}

JointError World::jointError(uint32_t id) const {
  return joints_[id].broken ? JointError{} : measureJointError(bodies_, joints_[id]);
}

// A joint carries its bodies' motion across: a sleeping body joined to an awake one wakes up.
void World::wakeJointedBodies() {
  auto awake = [&](uint32_t i) {
    return i != kWorldBody && bodies_.kind[i] == BodyKind::Dynamic && !bodies_.asleep[i];
  };
  auto sleeping = [&](uint32_t i) { return i != kWorldBody && bodies_.asleep[i]; };
  for (const Joint& j : joints_) {
    if (j.broken) continue;
    if (awake(j.def.bodyA) && sleeping(j.def.bodyB)) wake(j.def.bodyB);
    else if (awake(j.def.bodyB) && sleeping(j.def.bodyA)) wake(j.def.bodyA);
  }
}

// After the solve: joints whose force or torque went over their threshold break (in index order, so
// the outcome does not depend on threads). Their bodies collide again from the next step.
void World::breakJoints() {
  for (Joint& j : joints_) {
    const JointDef& d = j.def;
    if (j.broken || (j.lastForce.norm() <= d.breakForce && j.lastTorque.norm() <= d.breakTorque)) continue;
    j.broken = true;
    j.lastForce.setZero();
    j.lastTorque.setZero();
    if (d.collideConnected || d.bodyA == kWorldBody || d.bodyB == kWorldBody) continue;
    const uint64_t key = PairMap::key(d.bodyA, d.bodyB);
    const uint32_t n = jointPairs_.find(key);
    if (n > 1) {
      jointPairs_.set(key, n - 1);
      continue;
    }
    jointPairs_.erase(key);
    // The broad phase reports only new overlaps: a pair that already overlaps gets its contact here.
    if (pairs_.find(key) == PairMap::kNotFound && broadPhase_.fatOverlap(d.bodyA, d.bodyB)) {
      Contact c;
      c.a = std::min(d.bodyA, d.bodyB);
      c.b = std::max(d.bodyA, d.bodyB);
      c.friction = std::sqrt(bodies_.friction[c.a] * bodies_.friction[c.b]);
      c.restitution = std::max(bodies_.restitution[c.a], bodies_.restitution[c.b]);
      pairs_.set(key, static_cast<uint32_t>(contacts_.size()));
      contacts_.push_back(c);
    }
  }
}

// Geometric stiffness of loaded joints, added to their bodies' inertia for this step's solve (contacts
// and joints alike); integration puts the true inertia back.
void World::stiffenJointedBodies() {
  if (!settings_.joints.geometricStiffness) return;
  jointStiffness_.assign(bodyCount(), 0.0f);
  for (uint32_t ji : islands_.joints) accumulateJointStiffness(bodies_, joints_[ji], jointStiffness_.data());
  for (uint32_t i : islands_.bodies) stiffenInertia(bodies_, i, jointStiffness_[i], settings_.dt);
}

// Rows of island k's joints, warm started, and its joint tree factorised (when joints are solved as a tree).
void World::prepareJoints(uint32_t k, const SolverParams& sp) {
  const Island& isl = islands_.islands[k];
  JointConstraint* js = jointConstraints_.data() + isl.firstJoint;
  const uint32_t nj = isl.jointCount;
  const uint32_t* ids = islands_.joints.data() + isl.firstJoint;
  const float time = float(stepCount_ + 1) * sp.dt;
  for (uint32_t j = 0; j < nj; ++j) prepareJoint(bodies_, joints_[ids[j]], ids[j], sp, settings_.joints, time, js[j]);
  if (sp.warmStart) warmStartJoints(bodies_, js, nj);
  if (settings_.joints.treeSolve) jointTrees_[k].build(js, nj);
}

// After the relax sweeps: keep the impulses for the next step, then (the rows being free now) project the
// tree joints back onto their constraints at the integrated positions.
void World::finishJoints(uint32_t k) {
  const Island& isl = islands_.islands[k];
  JointConstraint* js = jointConstraints_.data() + isl.firstJoint;
  const uint32_t nj = isl.jointCount;
  storeJointImpulses(js, nj, settings_.dt, joints_.data());
  if (!settings_.joints.treeSolve || !settings_.joints.postProjection) return;
  // The projection moves bodies in the same metric as the solve: light loaded links mostly translate.
  const bool stiff = settings_.joints.geometricStiffness;
  const uint32_t* bodies = islands_.bodies.data() + isl.firstBody;
  if (stiff)
    for (uint32_t j = 0; j < isl.bodyCount; ++j)
      stiffenInertia(bodies_, bodies[j], jointStiffness_[bodies[j]], settings_.dt);
  projectJointPositions(bodies_, joints_.data(), islands_.joints.data() + isl.firstJoint, nj, solverParams(),
                        settings_.joints, js, jointTrees_[k]);
  if (stiff)
    for (uint32_t j = 0; j < isl.bodyCount; ++j) bodies_.updateWorldInertia(bodies[j]);
}

void World::measureJointErrors() {
  for (uint32_t i = 0; i < jointCount(); ++i) {
    const JointError e = jointError(i);
    stats_.jointErrorM = std::max(stats_.jointErrorM, e.linear);
    stats_.jointErrorRad = std::max(stats_.jointErrorRad, e.angular);
  }
}

// ---- collision ---------------------------------------------------------------------------

void World::updateBroadPhase() {
  const uint32_t n = bodyCount();
  const float dt = settings_.dt;
  // Tight boxes (kept for buoyancy and metrics), then each swept by this step's motion so fast
  // bodies find their pairs before they pass through them.
  parallelFor(n, 1024, [&](uint32_t begin, uint32_t end) {
    for (uint32_t i = begin; i < end; ++i)
      if (bodies_.kind[i] != BodyKind::Static && !bodies_.asleep[i]) bounds_[i] = computeAabb(shapes_[i], bodies_.xf[i]);
  });
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies_.kind[i] == BodyKind::Static || bodies_.asleep[i]) continue;
    const Vec3 d = dt * bodies_.v[i];
    broadPhase_.update(i, bounds_[i].merged({bounds_[i].lo + d, bounds_[i].hi + d}));
  }
  // New pairs: the moved bodies' queries run in parallel, a list per run of kPairQueryGrain of
  // them (a churning pile re-inserts most of its bodies every step, and the queries were a sixth
  // of a swept pit's step, serial); the lists are then joined in order, so the contacts are made
  // in the same order whatever the threads.
  auto wanted = [&](uint32_t a, uint32_t b) {
    const bool dynA = bodies_.kind[a] == BodyKind::Dynamic, dynB = bodies_.kind[b] == BodyKind::Dynamic;
    if (!dynA && !dynB) return false;  // static/kinematic pairs need no contact
    const uint64_t key = PairMap::key(a, b);
    if (jointPairs_.find(key) != PairMap::kNotFound) return false;  // jointed bodies do not collide
    return pairs_.find(key) == PairMap::kNotFound;
  };
  const std::vector<uint32_t>& moved = broadPhase_.moved();
  const uint32_t movedCount = uint32_t(moved.size());
  const uint32_t runs = (movedCount + kPairQueryGrain - 1) / kPairQueryGrain;
  if (newPairRuns_.size() < runs) newPairRuns_.resize(runs);
  parallelFor(runs, 1, [&](uint32_t begin, uint32_t end) {
    for (uint32_t r = begin; r < end; ++r) {
      std::vector<std::pair<uint32_t, uint32_t>>& found = newPairRuns_[r];
      found.clear();
      const uint32_t last = std::min(movedCount, (r + 1) * kPairQueryGrain);
      for (uint32_t i = r * kPairQueryGrain; i < last; ++i)
        broadPhase_.queryMoved(moved[i], [&](uint32_t a, uint32_t b) {
          if (wanted(a, b)) found.emplace_back(a, b);
        });
    }
  });
  uint32_t created = 0;
  for (uint32_t r = 0; r < runs; ++r) {
    for (const auto& [a, b] : newPairRuns_[r]) {
      Contact c;
      c.a = std::min(a, b);
      c.b = std::max(a, b);
      c.friction = std::sqrt(bodies_.friction[a] * bodies_.friction[b]);
      c.restitution = std::max(bodies_.restitution[a], bodies_.restitution[b]);
      pairs_.set(PairMap::key(a, b), static_cast<uint32_t>(contacts_.size()));
      contacts_.push_back(c);
      ++created;
    }
  }
  broadPhase_.clearMoved();
  stats_.newPairs = created;
}

namespace {

// What the stages after the narrow phase need of a contact, copied while it is in cache.
inline void noteEdge(const Contact& c, ContactEdge& edge, bool againstImmovable) {
  edge.count = uint32_t(c.manifold.count);
  edge.pressedByImmovable = againstImmovable && c.manifold.deepest() > 0.0f;
  bool unloaded = true;
  for (int i = 0; i < c.manifold.count; ++i) unloaded &= c.normalImpulse[i] == 0.0f;
  edge.unloaded = unloaded;
}

// Sets a touching contact's static friction anchor where its points are now, unless it holds one
// that has drifted less than kAnchorSlip along the contact; a contact without points lets go.
constexpr float kAnchorSlip = 0.02f;  // m: more is a slide, not a drift to pull back
inline void updateAnchor(Contact& c, const Transform& xa, const Transform& xb) {
  const int m = c.manifold.count;
  if (m == 0) {
    c.anchored = false;
    return;
  }
  Vec3 centre = Vec3::Zero(), n = Vec3::Zero();
  for (int i = 0; i < m; ++i) {
    centre += c.manifold.points[i].position;
    n += c.manifold.points[i].normal;
  }
  centre /= float(m);
  if (c.anchored) {
    const Vec3 drift = xb.apply(c.anchorB) - xa.apply(c.anchorA);
    const float along = n.squaredNorm() > 0.0f ? drift.dot(n) / n.norm() : 0.0f;
    if (drift.squaredNorm() - along * along <= kAnchorSlip * kAnchorSlip) return;
  }
  c.anchorA = xa.applyInverse(centre);
  c.anchorB = xb.applyInverse(centre);
  c.anchored = true;
}

bool rolls(const Shape& s) { return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule; }

}  // namespace

void World::narrowPhase() {
  const uint32_t n = static_cast<uint32_t>(contacts_.size());
  wakeFlag_.resize(n);
  reusedFlag_.assign(n, 0);
  contactEdges_.resize(n);
  auto active = [&](uint32_t i) {
    return bodies_.kind[i] == BodyKind::Kinematic || (bodies_.kind[i] == BodyKind::Dynamic && !bodies_.asleep[i]);
  };
  ManifoldReuseLimits reuseLimits;
  reuseLimits.margin = settings_.contactMargin;
  const float restingClosing = reuseLimits.slide + settings_.gravity.norm() * settings_.dt * settings_.dt;
  parallelFor(n, 64, [&](uint32_t begin, uint32_t end) {
    for (uint32_t ci = begin; ci < end; ++ci) {
      Contact& c = contacts_[ci];
      wakeFlag_[ci] = 0;
      c.pinched = false;  // PinchDetector::mark sets it again
      ContactEdge& edge = contactEdges_[ci];
      edge.a = c.a;
      edge.b = c.b;
      if (!active(c.a) && !active(c.b)) {  // sleeping or static on both sides: keep the manifold
        noteEdge(c, edge, false);
        continue;
      }
      // One side solved, the other static or kinematic: what pinches are made of (haif/pinch.h).
      const bool solvedA = bodies_.isAwakeDynamic(c.a), solvedB = bodies_.isAwakeDynamic(c.b);
      const bool againstImmovable = solvedA != solvedB && !bodies_.isDynamic(solvedA ? c.b : c.a);
      const Transform &xa = bodies_.xf[c.a], &xb = bodies_.xf[c.b];
      // Speculative margin: as far as the pair closes in one step, uncapped, so a small fast body meets a
      // thin wall the step before it would pass it (a 1 m cap let 5 cm bodies through above 60 m/s). It
      // only widens pairs the swept broad-phase boxes already found, and resting pairs keep the base margin.
      const float rel = (bodies_.v[c.b] - bodies_.v[c.a]).norm() * settings_.dt;
      // A pair that barely moves against each other keeps its manifold (a landing one may need points
      // it does not have yet, so it is made again). Gravity has just been added to the velocities, so
      // a body resting on a static one closes by g dt² a step before the solver stops it.
      // A sphere or capsule rolls: its contact stays under its centre while a point fixed in it turns
      // away, and the turned normal pushed a ball rolling at 1 cm/s up to 14 cm/s in 5 s. Those
      // pairs are cheap to collide and always made again (nor remembered).
      const bool reusable = settings_.reuseManifolds && !rolls(shapes_[c.a]) && !rolls(shapes_[c.b]);
      if (reusable && rel < restingClosing && refreshManifold(c.cache, xa, xb, reuseLimits, c.manifold)) {
        reusedFlag_[ci] = 1;
        updateAnchor(c, xa, xb);
        noteEdge(c, edge, againstImmovable);
        continue;  // same points and ids: the impulses stay where they are
      }
      const Manifold old = c.manifold;
      // A pair stays while its fat boxes overlap, but two in three of a churning pile's pairs are
      // farther apart than the margin: their tight boxes, widened by it, already say no point can be.
      const float reach = settings_.contactMargin + rel;
      if (bounds_[c.a].expanded(reach).overlaps(bounds_[c.b])) collide(shapes_[c.a], xa, shapes_[c.b], xb, reach, c.manifold);
      else c.manifold.count = 0;
      if (reusable) rememberManifold(c.manifold, xa, xb, c.cache);
      // Carry accumulated normal impulses over to the points that touch the same features; when
      // the feature ids changed (a reference face switched), fall back to the nearest old point.
      // Friction lives at the manifold's centre and carries over as it is.
      float normal[kMaxManifoldPoints];
      for (int i = 0; i < c.manifold.count; ++i) {
        const ContactPoint& np = c.manifold.points[i];
        int match = -1;
        float best = kWarmStartMatchDistance * kWarmStartMatchDistance;
        for (int j = 0; j < old.count; ++j) {
          if (old.points[j].id == np.id) {
            match = j;
            break;
          }
          const float d2 = (old.points[j].position - np.position).squaredNorm();
          if (d2 < best) {
            best = d2;
            match = j;
          }
        }
        normal[i] = match >= 0 ? c.normalImpulse[match] : 0.0f;
      }
      for (int i = 0; i < c.manifold.count; ++i) c.normalImpulse[i] = normal[i];
      if (c.manifold.count == 0) {
        c.frictionImpulse.setZero();
        c.twistImpulse = 0.0f;
      }
      if ((old.count > 0) != (c.manifold.count > 0)) wakeFlag_[ci] = 1;
      updateAnchor(c, xa, xb);
      noteEdge(c, edge, againstImmovable);
    }
  });

  for (const uint8_t reused : reusedFlag_) stats_.manifoldsReused += reused;
  // Destroy contacts whose fat boxes separated; wake sleeping bodies whose contacts changed.
  // It reads the flat edges, not the contacts (a pass over those took ~0.4 ms in many_pyramids).
  for (uint32_t ci = 0; ci < contacts_.size();) {
    const ContactEdge c = contactEdges_[ci];
    if (wakeFlag_[ci]) {
      wake(c.a);
      wake(c.b);
    }
    if (c.count == 0 && !broadPhase_.fatOverlap(c.a, c.b)) {
      pairs_.erase(PairMap::key(c.a, c.b));
      const uint32_t last = static_cast<uint32_t>(contacts_.size() - 1);
      if (ci != last) {
        contacts_[ci] = contacts_[last];
        wakeFlag_[ci] = wakeFlag_[last];
        contactEdges_[ci] = contactEdges_[last];
        pairs_.set(PairMap::key(contacts_[ci].a, contacts_[ci].b), ci);
      }
      contacts_.pop_back();
      wakeFlag_.pop_back();
      contactEdges_.pop_back();
      continue;
    }
    ++ci;
  }
}

// ---- solve -------------------------------------------------------------------------------

SolverParams World::solverParams() const {
  SolverParams sp;
  sp.dt = settings_.dt;
  sp.omega = settings_.omega;
  sp.beta = settings_.beta;
  sp.slop = settings_.slop;
  sp.restitutionThreshold = settings_.restitutionThreshold;
  sp.warmStart = settings_.warmStart;
  sp.maxPushVelocity = settings_.maxPushVelocity;
  sp.frictionAnchors = settings_.frictionAnchors;
  return sp;
}

int World::relaxIterationsFor(int iterations) {
  // A quarter of the iterations (at least one) relax: enough to take the push-out velocity away.
  return iterations >= 2 ? std::max(1, iterations / 4) : 0;
}

template <class First, class Second>
void World::forEachIslandTimed(First&& first, Second&& second, bool firstIsSweeps) {
  const uint32_t batches = static_cast<uint32_t>(batchStart_.size()) - 1;
  parallelFor(batches, 1, [&](uint32_t begin, uint32_t end) {
    for (uint32_t b = begin; b < end; ++b) {
      // A batch is ~kBatchRows rows: its constraints stay in cache from one phase to the next.
      const auto t0 = Clock::now();
      for (uint32_t k = batchStart_[b]; k < batchStart_[b + 1]; ++k) first(k);
      const auto t1 = Clock::now();
      for (uint32_t k = batchStart_[b]; k < batchStart_[b + 1]; ++k) second(k);
      const auto t2 = Clock::now();
      const double a = std::chrono::duration<double, std::milli>(t1 - t0).count();
      const double c = std::chrono::duration<double, std::milli>(t2 - t1).count();
      PhaseClock& pc = phaseClock();
      pc.fixedMs += firstIsSweeps ? c : a;
      pc.sweepMs += firstIsSweeps ? a : c;
    }
  });
}

// Runs f(begin, end) over island k's contact range and merges the SweepResults f returns. A split
// island runs its strips in two parallel phases, even strips then odd ones, then its tail (see
// island_split.h), and merges in strip order, so sums do not depend on the thread count. Any other
// island is one range on the calling thread.
template <class F>
SweepResult World::forEachStrip(uint32_t k, F&& f) {
  const int32_t li = layoutOf_[k];
  if (li < 0) return f(0u, islands_.islands[k].contactCount);
  const StripLayout& layout = layouts_[li];
  SweepResult* res = stripResult_.data() + size_t(li) * (kMaxStrips + 1);
  SweepResult total;
  for (uint32_t phase = 0; phase < 2; ++phase) {
    const uint32_t tasks = (layout.strips + 1 - phase) / 2;
    parallelFor(tasks, 1, [&](uint32_t begin, uint32_t end) {
      for (uint32_t t = begin; t < end; ++t) {
        const uint32_t s = 2 * t + phase;
        res[s] = f(layout.start[s], layout.start[s + 1]);
      }
    });
    for (uint32_t t = 0; t < tasks; ++t) total.merge(res[2 * t + phase]);
  }
  const uint32_t tail = layout.strips;
  total.merge(f(layout.start[tail], layout.start[tail + 1]));
  return total;
}

template <class F>
void World::forEachContactChunk(uint32_t k, uint32_t grain, F&& f) {
  const uint32_t n = islands_.islands[k].contactCount;
  if (layoutOf_[k] >= 0) parallelFor(n, grain, f);
  else f(0u, n);
}

Vec3 World::upDirection() const {
  return settings_.gravity.squaredNorm() > 0.0f ? Vec3(-settings_.gravity.normalized()) : Vec3::UnitY();
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
  const float omega = settings_.omega;
  SweepResult r;
  if (isChain_[k]) {
    r = solveChainIteration(bodies_, cs, chainLinks_.data() + isl.firstContact, isl.contactCount, omega, useBias);
  } else if (isWide(k)) {
    const LaneBatches lb = lanesOf(k);
    if (restartDirection) startDirectionLanes(cs, isl.contactCount, lb);
    r = forEachStrip(k, [&](uint32_t b, uint32_t e) {
      return solveIterationLanes(bodies_, cs + b, e - b, lb.from(b), omega, useBias);
    });
  } else {
    r = forEachStrip(k, [&](uint32_t b, uint32_t e) {
      return solveIteration(bodies_, cs + b, e - b, omega, useBias, restartDirection, measureChange);
    });
  }
  if (isl.jointCount > 0) {
    JointTree* tree = settings_.joints.treeSolve ? &jointTrees_[k] : nullptr;
    r.residual = std::max(r.residual, solveJointIteration(bodies_, jointConstraints_.data() + isl.firstJoint,
                                                          isl.jointCount, tree, omega, useBias));
  }
  return r;
}

// Giant islands without joints are cut into strips for parallel sweeps. The island's largest
// unsplittable piece of work then becomes its critical path, which is what the controller plans with.
void World::splitGiantIslands() {
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  layoutOf_.assign(m, -1);
  const Vec3 up = upDirection();
  uint32_t used = 0, largest = 0;
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    if (isl.rows >= kSplitRows && isl.jointCount == 0) {
      if (layouts_.size() <= used) layouts_.emplace_back();
      splitter_.split(bodies_, contactEdges_.data(), up, islands_, k, layouts_[used]);
      layoutOf_[k] = int32_t(used);
      largest = std::max(largest, layouts_[used].criticalRows());
      ++used;
    } else {
      largest = std::max(largest, isl.rows);
    }
  }
  stripResult_.resize(layouts_.size() * (kMaxStrips + 1));
  islands_.largestRows = largest;
}

// Each range a sweep runs as one piece (an island, or a strip or tail of a split one) is grouped
// into lane batches for the wide sweep; the order change does not change the sweep's result.
void World::batchLanes() {
  if (!settings_.wideSolve) return;
  laneRun_.resize(islands_.contacts.size());
  const float* levels = settings_.topDownOrder ? contactHeight_.data() : nullptr;
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    uint32_t* ids = islands_.contacts.data() + isl.firstContact;
    uint8_t* run = laneRun_.data() + isl.firstContact;
    const int32_t li = layoutOf_[k];
    if (li < 0) {
      laneBatcher_.batch(bodies_, contacts_.data(), levels, ids, isl.contactCount, run);
      continue;
    }
    const StripLayout& layout = layouts_[li];
    for (uint32_t s = 0; s <= layout.strips; ++s) {
      const uint32_t b = layout.start[s], e = layout.start[s + 1];
      laneBatcher_.batch(bodies_, contacts_.data(), levels, ids + b, e - b, run + b);
    }
  }
  // Batches of at least kMinWideLanes constraints are packed for the wide sweep.
  wideOf_.resize(laneRun_.size());
  uint32_t packed = 0;
  for (size_t j = 0; j < laneRun_.size(); ++j)
    wideOf_[j] = laneRun_[j] >= kMinWideLanes ? int32_t(packed++) : -1;
  if (wide_.size() < packed) wide_.resize(packed);
}

LaneBatches World::lanesOf(uint32_t k) {
  const uint32_t first = islands_.islands[k].firstContact;
  return {laneRun_.data() + first, wideOf_.data() + first, wide_.data()};
}

bool World::isWide(uint32_t k) const { return settings_.wideSolve && !isChain_[k]; }

void World::solveIslands(int iterations) {
  const SolverParams sp = solverParams();
  const float tol = settings_.residualTolerance;
  const int iMin = std::min(controller_->iMin, iterations);
  auto prepareIsland = [&](uint32_t k) {
    const Island& isl = islands_.islands[k];
    ContactConstraint* cs = constraints_.data() + isl.firstContact;
    const uint32_t* ids = islands_.contacts.data() + isl.firstContact;
    forEachContactChunk(k, 256, [&](uint32_t begin, uint32_t end) {
      for (uint32_t j = begin; j < end; ++j) prepareContact(bodies_, contacts_[ids[j]], ids[j], sp, cs[j]);
    });
    isChain_[k] = settings_.chainSolve && layoutOf_[k] < 0 && isl.jointCount == 0 &&
                  prepareChain(contacts_.data(), cs, isl.contactCount, chainMark_.data(),
                               chainLinks_.data() + isl.firstContact);
    if (sp.warmStart) forEachStrip(k, [&](uint32_t b, uint32_t e) {
      warmStart(bodies_, cs + b, e - b);
      return SweepResult{};
    });
    if (isWide(k)) {
      const LaneBatches lb = lanesOf(k);
      forEachStrip(k, [&](uint32_t b, uint32_t e) {
        packLanes(cs + b, e - b, lb.from(b));
        return SweepResult{};
      });
    }
    if (isl.jointCount > 0) prepareJoints(k, sp);
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
    double lastChange = 0.0;
    int it = 0;
    float residual = 0.0f;
    bool restart = false;  // the next sweep starts the direction from this sweep's change
    while (it < iterations) {
      const SweepResult sweep = sweepIsland(k, true, restart, cg);
      restart = false;
      residual = sweep.residual;
      ++it;
      // Converged islands stop: precision nobody can see is not paid for. A chain stops as soon as
      // a sweep changes nothing: its sweeps solve it exactly, so I_min's guard against a sweep that
      // only looks converged is not needed there.
      if (tol > 0.0f && (it >= iMin || isChain_[k]) && residual < tol) break;
      if (!cg || it == iterations) continue;  // the main sweeps end on a sweep, not a momentum step
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
          else accelerate(bodies_, cs + b, e - b, beta);
          return SweepResult{};
        });
      }
      lastChange = change;
    }
    islandIterations_[k] = isl.contactCount + isl.jointCount > 0 ? it : 0;
    islandResidual_[k] = residual;
  };
  forEachIslandTimed(prepareIsland, sweepIslandMain);
  if (tol > 0.0f && iterations > 0) shareSpareIterations(iterations);
}

// Islands that converged early leave part of the step's work unspent: Σ (I − run) × rows. That
// budget goes to islands still above the tolerance, the largest residual first (where a sweep
// buys the most accuracy), each at most doubling its count (a bound that depends only on I, so
// replaying the counts reproduces the run).
void World::shareSpareIterations(int iterations) {
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  uint64_t spare = 0;
  for (uint32_t k = 0; k < m; ++k)
    spare += uint64_t(iterations - std::min(iterations, islandIterations_[k])) * islands_.islands[k].rows;
  islandExtra_.assign(m, 0);
  bool any = false;
  const float tol = settings_.residualTolerance;
  spareOrder_.clear();
  for (uint32_t k = 0; k < m; ++k)
    if (islands_.islands[k].rows > 0 && islandResidual_[k] >= tol) spareOrder_.push_back(k);
  // Ties broken by index: the order, and so the state, does not depend on the thread count.
  std::sort(spareOrder_.begin(), spareOrder_.end(), [&](uint32_t x, uint32_t y) {
    return islandResidual_[x] != islandResidual_[y] ? islandResidual_[x] > islandResidual_[y] : x < y;
  });
  for (const uint32_t k : spareOrder_) {
    if (spare == 0) break;
    const uint32_t rows = islands_.islands[k].rows;
    const int extra = int(std::min<uint64_t>(uint64_t(iterations), spare / rows));
    if (extra == 0) continue;
    islandExtra_[k] = extra;
    spare -= uint64_t(extra) * rows;
    any = true;
  }
  if (!any) return;
  forEachIslandTimed([](uint32_t) {}, [&](uint32_t k) {  // sweeps only
    int it = 0;
    float residual = islandResidual_[k];
    while (it < islandExtra_[k] && residual >= tol) {
      residual = sweepIsland(k, true).residual;
      ++it;
    }
    islandIterations_[k] += it;
    islandResidual_[k] = residual;
  });
}

void World::relaxIslands(int relaxIterations) {
  const SolverParams sp = solverParams();
  auto relax = [&](uint32_t k) {
    // A chain keeps the factors of its rows from the main sweeps, lanes hold packed copies, and a
    // jointed island's joint rows were built with the stiffened inertia that integration has since
    // reset (stiffenJointedBodies; re-aimed contact rows next to them gained energy in random
    // mixed worlds): their rows stay as they were.
    if (relaxIterations > 0 && !isChain_[k] && !isWide(k) && islands_.islands[k].jointCount == 0) {
      const Island& isl = islands_.islands[k];
      ContactConstraint* cs = constraints_.data() + isl.firstContact;
      forEachContactChunk(k, 1024, [&](uint32_t b, uint32_t e) {
        for (uint32_t j = b; j < e; ++j) reaimForRelax(bodies_, contacts_[cs[j].contact], sp, cs[j]);
      });
    }
    for (int it = 0; it < relaxIterations; ++it) sweepIsland(k, false);
  };
  auto store = [&](uint32_t k) {
    const Island& isl = islands_.islands[k];
    ContactConstraint* cs = constraints_.data() + isl.firstContact;
    if (isWide(k)) {
      const LaneBatches lb = lanesOf(k);
      forEachStrip(k, [&](uint32_t b, uint32_t e) {
        unpackLanes(cs + b, e - b, lb.from(b));
        return SweepResult{};
      });
    }
    forEachContactChunk(k, 1024, [&](uint32_t b, uint32_t e) { storeImpulses(cs + b, e - b, contacts_.data()); });
    if (isl.jointCount > 0) finishJoints(k);
    if (isl.contactCount + isl.jointCount > 0) islandIterations_[k] += relaxIterations;
  };
  forEachIslandTimed(relax, store, /*firstIsSweeps=*/true);
}

namespace {

// Sets a value for the life of the object and puts the old one back, exceptions included.
template <class T>
class ScopedValue {
 public:
  ScopedValue(T& ref, T value) : ref_(ref), old_(ref) { ref_ = value; }
  ~ScopedValue() { ref_ = old_; }
  ScopedValue(const ScopedValue&) = delete;
  ScopedValue& operator=(const ScopedValue&) = delete;

 private:
  T& ref_;
  T old_;
};

}  // namespace

double World::measureSolveError(int iterations) {
  // e = |v_I - v*|_M / |v_0 - v*|_M over the dynamic bodies of the islands (docs/metrics.md), with v_0
  // the solver's starting point (after warm starting), v_I after the iterations, v* converged.
  const uint32_t n = bodyCount();
  const auto t0 = Clock::now();
  saveV_ = bodies_.v;
  saveW_ = bodies_.w;
  solveIslands(0);  // prepare + warm start only
  startV_ = bodies_.v;
  startW_ = bodies_.w;
  bodies_.v = saveV_;
  bodies_.w = saveW_;
  {
    // The reference solve converges: a tight tolerance and no floor on the sweeps, put back on the
    // way out of this block however it is left.
    const ScopedValue<float> tol(settings_.residualTolerance, 1e-6f);
    const ScopedValue<int> iMin(controller_->iMin, 1);
    solveIslands(1000);
  }
  refV_ = bodies_.v;
  refW_ = bodies_.w;
  bodies_.v = saveV_;
  bodies_.w = saveW_;
  measurementMs_ = msSince(t0);  // the reference solve is measurement, not step time
  resetPhaseClocks();
  solveIslands(iterations);
  double num = 0.0, den = 0.0, massSum = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies_.kind[i] != BodyKind::Dynamic || bodies_.asleep[i]) continue;
    massSum += bodies_.mass[i];
    const Mat3 I = bodies_.xf[i].q.toRotationMatrix() * bodies_.inertiaLocal[i] *
                   bodies_.xf[i].q.toRotationMatrix().transpose();
    auto norm2 = [&](const Vec3& dv, const Vec3& dw) {
      return double(bodies_.mass[i]) * dv.squaredNorm() + double(dw.dot(I * dw));
    };
    num += norm2(bodies_.v[i] - refV_[i], bodies_.w[i] - refW_[i]);
    den += norm2(startV_[i] - refV_[i], startW_[i] - refW_[i]);
  }
  // When warm starting already put v_0 within float noise of v* (a resting stack), the ratio
  // of two noise-sized norms says nothing: the denominator is floored at an RMS velocity error
  // of kSolveErrorFloor, so a solve with nothing left to do reports an error near 0.
  const double floor = massSum * double(kSolveErrorFloor) * double(kSolveErrorFloor);
  return num > 0.0 ? std::sqrt(num / std::max(den, floor)) : 0.0;
}

void World::solve(int iterations) {
  // Iterations with position correction now; the relax iterations run after integration.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  constraints_.resize(islands_.contacts.size());
  chainLinks_.resize(constraints_.size());
  chainMark_.resize(bodyCount());
  isChain_.assign(m, 0);
  jointConstraints_.resize(islands_.joints.size());
  if (jointTrees_.size() < m) jointTrees_.resize(m);  // grows to the most islands seen, then reused
  if (!joints_.empty()) stiffenJointedBodies();
  islandIterations_.assign(m, 0);
  islandResidual_.assign(m, 0.0f);
  // Islands come largest first: big ones get a task each, small ones are batched.
  batchStart_.clear();
  batchStart_.push_back(0);
  uint32_t acc = 0;
  for (uint32_t k = 0; k < m; ++k) {
    acc += islands_.islands[k].rows;
    if (acc >= kBatchRows || k + 1 == m) {
      batchStart_.push_back(k + 1);
      acc = 0;
    }
  }
  if (m == 0) batchStart_.push_back(0);

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
  for (uint32_t k = 0; k < m; ++k) {
    const Island& isl = islands_.islands[k];
    if (isl.contactCount + isl.jointCount == 0) continue;
    lo = std::min(lo, islandIterations_[k]);
    hi = std::max(hi, islandIterations_[k]);
    sum += islandIterations_[k];
    ++counted;
    residual = std::max(residual, islandResidual_[k]);
    rowIt += uint64_t(isl.rows) * uint64_t(islandIterations_[k]);
  }
  stats_.iterationsMin = counted ? lo : 0;
  stats_.iterationsMax = counted ? hi : 0;
  stats_.iterationsMean = counted ? sum / counted : 0.0;
  stats_.residual = residual;
  stats_.rowIterations = rowIt;
}

// Gauss-Seidel order matters for stacking: solving the highest contacts first carries the weight
// of a stack down to the ground within one sweep (bottom-up needs one sweep per layer). Against
// gravity, a 100-layer pyramid at 10 iterations dropped 1.6 m on average bottom-up, 0.08 m top-down.
void World::orderContactsTopDown() {
  const Vec3 up = upDirection();
  contactHeight_.resize(contacts_.size());
  orderKeys_.resize(islands_.contacts.size());
  const uint32_t* ids = islands_.contacts.data();
  parallelFor(uint32_t(islands_.contacts.size()), 4096, [&](uint32_t begin, uint32_t end) {
    for (uint32_t j = begin; j < end; ++j) {
      const ContactEdge& c = contactEdges_[ids[j]];
      float h = up.dot(bodies_.xf[c.a].p + bodies_.xf[c.b].p);
      // A pinched body's static contacts come last, its kinematic ones first: the sweep's last word
      // keeps it out of the static world, and the kinematic body passes it (haif/pinch.h).
      if (pinchedBodies_ > 0 && contacts_[ids[j]].pinched) {
        const bool kinematic = bodies_.kind[c.a] == BodyKind::Kinematic || bodies_.kind[c.b] == BodyKind::Kinematic;
        h = kinematic ? std::numeric_limits<float>::max() : std::numeric_limits<float>::lowest();
      }
      contactHeight_[ids[j]] = h;
      orderKeys_[j] = descendingKey(h, ids[j]);  // top down; ties by index: deterministic
    }
  });
  // Islands own disjoint ranges: sorted concurrently; a giant island is sorted in parallel itself.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  parallelFor(m, 4, [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const Island& isl = islands_.islands[k];
      uint64_t* first = orderKeys_.data() + isl.firstContact;
      // Keys are unique (they hold the index): any sort gives the same order. Under TSan the sort
      // stays serial, as TBB's hand-offs are invisible to it (haif/tsan_pool.h).
      if (arena_ && isl.contactCount >= kParallelSortContacts && !kTsan)
        arena_->execute([&] { tbb::parallel_sort(first, first + isl.contactCount); });
      else
        std::sort(first, first + isl.contactCount);
      uint32_t* out = islands_.contacts.data() + isl.firstContact;
      for (uint32_t j = 0; j < isl.contactCount; ++j) out[j] = keyIndex(first[j]);
    }
  });
}

// A contact that just formed has no impulse to warm start from. In a pile created at rest every
// contact is new, and sweeps build the support up only a few layers per step: large_pyramid's upper
// half fell for tens of steps, then rebounded. Cold contacts between bodies that are nearly at rest
// relative to each other therefore start from the weight they carry: top-down, each body's own
// weight plus what rests on it is shared among the contacts holding it up. The sweeps correct the
// estimate; contacts that approach fast (a landing) start from zero as before.
void World::estimateColdImpulses() {
  const float g = settings_.gravity.norm();
  if (g <= 0.0f) return;
  const Vec3 up = -settings_.gravity / g;
  const float dt = settings_.dt;
  const float restSpeed = 2.0f * g * dt;
  carried_.resize(bodyCount());
  supports_.resize(bodyCount());
  // A support: a vertical-ish contact; its upper body is the one on the normal's upward side.
  auto upper = [&](const Contact& c, float& slope) -> int64_t {
    slope = c.manifold.points[0].normal.dot(up);
    if (std::fabs(slope) < 0.7f) return -1;
    const uint32_t u = slope > 0.0f ? c.b : c.a;
    return bodies_.isAwakeDynamic(u) ? int64_t(u) : -1;
  };
  // Cold: no impulse to warm start from (the narrow phase noted that in the contact's edge), and the
  // bodies nearly at rest relative to each other.
  auto isCold = [&](uint32_t ci) {
    if (!contactEdges_[ci].unloaded) return false;
    const Contact& c = contacts_[ci];
    return std::fabs(c.manifold.points[0].normal.dot(bodies_.v[c.b] - bodies_.v[c.a])) <= restSpeed;
  };
  // Islands share no dynamic body (a static lower body receives nothing): they run concurrently.
  const uint32_t m = static_cast<uint32_t>(islands_.islands.size());
  parallelFor(m, 4, [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const Island& isl = islands_.islands[k];
      const uint32_t* bodies = islands_.bodies.data() + isl.firstBody;
      const uint32_t* contacts = islands_.contacts.data() + isl.firstContact;
      float slope;
      // A pile that has settled has no cold support left: its loads need not be added up (in
      // large_pyramid that was 0.4 ms a step, serial on its one island).
      bool anyCold = false;
      // Only contacts whose edge says they carry no impulse are read.
      for (uint32_t j = 0; j < isl.contactCount && !anyCold; ++j) {
        const uint32_t ci = contacts[j];
        anyCold = contactEdges_[ci].count > 0 && isCold(ci) && upper(contacts_[ci], slope) >= 0;
      }
      if (!anyCold) continue;
      for (uint32_t j = 0; j < isl.bodyCount; ++j) {
        carried_[bodies[j]] = 0.0f;
        supports_[bodies[j]] = 0;
      }
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        const int64_t u = upper(contacts_[contacts[j]], slope);
        if (u >= 0 && supports_[u] < 0xffff) ++supports_[u];
      }
      // Islands' contacts are in top-down order: a body's load is complete before its supports are met.
      for (uint32_t j = 0; j < isl.contactCount; ++j) {
        Contact& c = contacts_[contacts[j]];
        const int64_t u = upper(c, slope);
        if (u < 0) continue;
        const uint32_t lower = uint32_t(u) == c.a ? c.b : c.a;
        const float share = (bodies_.mass[u] * g * dt + carried_[u]) / float(supports_[u]);
        if (bodies_.isAwakeDynamic(lower)) carried_[lower] += share;
        if (!isCold(contacts[j])) continue;
        const float perPoint = share / (std::fabs(slope) * float(c.manifold.count));
        for (int i = 0; i < c.manifold.count; ++i) c.normalImpulse[i] = perPoint;
      }
    }
  });
}

// ---- sleep -------------------------------------------------------------------------------

void World::putIslandToSleep(const Island& isl) {
  int32_t set;
  if (!freeSleepSets_.empty()) {
    set = freeSleepSets_.back();
    freeSleepSets_.pop_back();
  } else {
    set = static_cast<int32_t>(sleepSets_.size());
    sleepSets_.emplace_back();
  }
  auto& members = sleepSets_[set];
  for (uint32_t j = 0; j < isl.bodyCount; ++j) {
    const uint32_t i = islands_.bodies[isl.firstBody + j];
    bodies_.asleep[i] = 1;
    bodies_.sleepSet[i] = set;
    bodies_.v[i].setZero();
    bodies_.w[i].setZero();
    members.push_back(i);
  }
}

void World::detectSleep() {
  for (const Island& isl : islands_.islands) {
    float minRest = 1e30f;
    for (uint32_t j = 0; j < isl.bodyCount; ++j)
      minRest = std::min(minRest, bodies_.restTime[islands_.bodies[isl.firstBody + j]]);
    if (minRest >= settings_.timeToSleep) putIslandToSleep(isl);
  }
}

// ---- speed bound ---------------------------------------------------------------------------

float World::waterLift() const {
  if (water_.empty()) return 0.0f;
  float water = 0.0f, lightest = 1e30f;
  for (const WaterVolume& w : water_) water = std::max(water, w.density);
  for (uint32_t i = 0; i < bodyCount(); ++i)
    if (bodies_.kind[i] == BodyKind::Dynamic && volume_[i] > 0.0f) lightest = std::min(lightest, bodies_.mass[i] / volume_[i]);
  return lightest < 1e30f ? water / lightest : 0.0f;
}

void World::boundSpeeds() {
  std::atomic<uint32_t> slowed{0};
  parallelFor(bodyCount(), 8192, [&](uint32_t b, uint32_t e) {
    if (const uint32_t k = speedBound_.apply(bodies_, b, e)) slowed += k;
  });
  stats_.speedLimited += slowed.load();
}

// ---- step --------------------------------------------------------------------------------

void World::step() {
  const auto t0 = Clock::now();
  const uint32_t n = bodyCount();
  const float dt = settings_.dt;
  stats_ = StepStats{};
  measurementMs_ = 0.0;
  stats_.step = stepCount_;
  stats_.budgetMs = settings_.budgetMs;
  stats_.stages = kStageBroadPhase | kStageNarrowPhase | kStageSolve;

  // 1. External forces (what they may add to any body's speed is noted first: the speed bound).
  speedBound_.settings = settings_.speedBound;
  speedBound_.update(bodies_, settings_.gravity, dt, waterLift(), staticFloor_);
  // A few operations a body: tasks of 8192 bodies, or the step pays more in task overhead than it saves.
  parallelFor(n, 8192, [&](uint32_t b, uint32_t e) { integrateVelocities(bodies_, b, e, settings_.gravity, dt); });
  if (!water_.empty()) {
    stats_.stages |= kStageBuoyancy;
    for (const WaterVolume& w : water_) applyBuoyancy(bodies_, volume_, bounds_, w, settings_.gravity, dt);
  }

  // 2-3. Collision detection.
  updateBroadPhase();
  narrowPhase();
  pinchedBodies_ = settings_.resolvePinches ? pinch_.mark(bodies_, contactEdges_.data(), contacts_) : 0;
  stats_.pinchedBodies = pinchedBodies_;
  if (hasMesh_) stats_.stages |= kStageMeshTests;
  stats_.collisionMs = msSince(t0);

  // 4. Islands.
  if (!joints_.empty()) {
    stats_.stages |= kStageJoints;
    wakeJointedBodies();
  }
  islandBuilder_.build(bodies_, contactEdges_.data(), uint32_t(contactEdges_.size()), joints_, islands_);
  if (settings_.topDownOrder) orderContactsTopDown();
  if (settings_.coldStartFromWeight && settings_.warmStart && settings_.topDownOrder) estimateColdImpulses();
  splitGiantIslands();
  batchLanes();
  std::fill(islandOfBody_.begin(), islandOfBody_.end(), -1);
  for (uint32_t k = 0; k < islands_.islands.size(); ++k) {
    const Island& isl = islands_.islands[k];
    for (uint32_t j = 0; j < isl.bodyCount; ++j) islandOfBody_[islands_.bodies[isl.firstBody + j]] = int32_t(k);
  }

  // 5. Iteration count.
  ControlContext ctx;
  ctx.step = stepCount_;
  ctx.budgetMs = settings_.budgetMs;
  ctx.elapsedMs = msSince(t0);
  ctx.totalRows = islands_.totalRows;
  ctx.largestRows = islands_.largestRows;
  ctx.islands = static_cast<uint32_t>(islands_.islands.size());
  ctx.bodies = static_cast<uint32_t>(islands_.bodies.size());
  ctx.contactPoints = islands_.contactPoints;
  ctx.threads = settings_.threads;
  const int iterations = std::clamp(controller_->choose(ctx), controller_->iMin, controller_->iMax);
  stats_.iterationsChosen = iterations;

  // 6. Parallel constraint solving.
  const auto t1 = Clock::now();
  const int relax = relaxIterationsFor(iterations);
  solve(iterations - relax);
  stats_.solveMs = msSince(t1) - measurementMs_;
  SolveObservation obs;
  obs.iterations = iterations;

  // 7. Integration and sleep; no body moves faster than the bound (speed_bound.h).
  const auto t2 = Clock::now();
  boundSpeeds();
  const float restSpeed = restDampingSpeed(settings_.restDamping, settings_.gravity, dt);
  parallelFor(n, 512, [&](uint32_t b, uint32_t e) {
    dampRestingMotion(bodies_, islandOfBody_.data(), islands_, restSpeed, b, e);
    integratePositions(bodies_, b, e, dt, settings_.sleepLinear, settings_.sleepAngular);
  });
  const auto t3 = Clock::now();
  relaxIslands(relax);
  boundSpeeds();
  if (!joints_.empty()) breakJoints();
  const double relaxMs = msSince(t3);
  stats_.solveMs += relaxMs;
  summariseIterations();
  // What the solve did, relax sweeps included, once the counts are summed (not before).
  obs.solveMs = stats_.solveMs;
  obs.rowIterations = stats_.rowIterations;
  obs.criticalRowIterations = uint64_t(islands_.largestRows) * uint64_t(stats_.iterationsMax);
  for (const PhaseClock& pc : phaseClocks_) {
    obs.fixedThreadMs += pc.fixedMs;
    obs.sweepThreadMs += pc.sweepMs;
  }
  if (settings_.sleeping) {
    stats_.stages |= kStageSleep;
    detectSleep();
  }
  stats_.integrateMs = msSince(t2) - relaxMs;

  speedBound_.noteLowest(bodies_, upDirection());
  // Counters.
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies_.kind[i] != BodyKind::Dynamic) continue;
    if (bodies_.asleep[i]) ++stats_.sleepingBodies;
    else ++stats_.awakeBodies;
  }
  stats_.contacts = islands_.touchingContacts;  // counted while the islands were built
  stats_.contactPoints = islands_.contactPoints;
  stats_.islands = static_cast<uint32_t>(islands_.islands.size());
  stats_.largestIsland = islands_.largestBodies;
  stats_.totalMs = msSince(t0) - measurementMs_;
  stats_.deadlineMiss = settings_.budgetMs > 0.0 && stats_.totalMs > settings_.budgetMs;
  if (!joints_.empty()) measureJointErrors();  // a metric: outside the step's timing
  obs.integrateMs = stats_.integrateMs;
  obs.totalMs = stats_.totalMs;
  controller_->observe(ctx, obs);
  ++stepCount_;
}

// ---- queries -----------------------------------------------------------------------------

uint64_t World::stateHash() const {
  PoseHash h;
  for (const Transform& xf : bodies_.xf) h.add(xf.p, xf.q);
  return h.value();
}

double World::kineticEnergy() const {
  double e = 0.0;
  for (uint32_t i = 0; i < bodyCount(); ++i) {
    if (bodies_.kind[i] != BodyKind::Dynamic) continue;
    const Vec3 wb = bodies_.xf[i].q.conjugate() * bodies_.w[i];
    e += 0.5 * bodies_.mass[i] * bodies_.v[i].squaredNorm() + 0.5 * double(wb.dot(bodies_.inertiaLocal[i] * wb));
  }
  return e;
}

double World::potentialEnergy() const {
  double e = 0.0;
  for (uint32_t i = 0; i < bodyCount(); ++i)
    if (bodies_.kind[i] == BodyKind::Dynamic) e -= bodies_.mass[i] * double(settings_.gravity.dot(bodies_.xf[i].p));
  return e;
}

}  // namespace haif
