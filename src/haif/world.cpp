// The World's API and its step: the stages run in order, each defined in its own file
// (world_collision.cpp, world_joints.cpp, world_solve_order.cpp, world_solve.cpp,
// world_solve_error.cpp, world_sleep.cpp; docs/architecture.md).
#include "haif/world_internal.h"
#include "haif/small_bodies.h"

#include "core/pose_hash.h"
#include "dynamics/integrator.h"

namespace haif {

World::World(const WorldSettings& settings) : settings_(settings) {
  controller_ = std::make_unique<FixedController>(settings_.iterations);
  setThreads(settings_.threads);
}

World::~World() = default;

void World::setController(std::unique_ptr<IterationController> c) { controller_ = std::move(c); }

void World::setThreads(int threads) {
  settings_.threads = std::max(1, threads);
  workerThreads_ = settings_.threads;
  // The arena's worker threads are created once and reused by every step.
  arena_ = settings_.threads > 1 ? std::make_unique<tbb::task_arena>(settings_.threads) : nullptr;
#ifdef HAIF_TSAN
  pool_ = settings_.threads > 1 ? std::make_unique<TsanPool>(settings_.threads) : nullptr;
#endif
  phaseClocks_.assign(size_t(settings_.threads), PhaseClock{});
  laneBatchers_.resize(size_t(settings_.threads));
}

size_t World::threadSlot() const {
#ifdef HAIF_TSAN
  const int slot = TsanPool::threadIndex();
#else
  const int slot = arena_ ? tbb::this_task_arena::current_thread_index() : 0;
#endif
  return slot >= 0 && slot < workerThreads_ ? size_t(slot) : 0;
}

// threadSlot is below workerThreads_, which setThreads sized phaseClocks_ (and laneBatchers_) to.
World::PhaseClock& World::phaseClock() { return phaseClocks_[threadSlot()]; }

void World::resetPhaseClocks() { std::fill(phaseClocks_.begin(), phaseClocks_.end(), PhaseClock{}); }

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
  bodies_.rollingResistance[id] = def.rollingResistance;
  hasRolling_ |= def.rollingResistance > 0.0f;
  bodies_.rollingRadius[id] =
      def.shape.type == ShapeType::Sphere || def.shape.type == ShapeType::Capsule ? def.shape.radius : 0.0f;
  bodies_.linearDamping[id] = def.linearDamping;
  bodies_.angularDamping[id] = def.angularDamping;
  shapes_.push_back(def.shape);
  volume_.push_back(unit.mass);
  toleranceScale_.push_back(toleranceScale(def.shape, settings_.toleranceThickness));
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
  broadPhase_.addBody(id, bounds_[id], def.kind == BodyKind::Static, toleranceScale_[id]);
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
  for (uint32_t i : sleepSets_.members(set)) wakeOne(i);
  sleepSets_.close(set);
}

Vec3 World::upDirection() const {
  return settings_.gravity.squaredNorm() > 0.0f ? Vec3(-settings_.gravity.normalized()) : Vec3::UnitY();
}

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
  parallelFor(bodyCount(), kBodyGrain, [&](uint32_t b, uint32_t e) {
    if (const uint32_t k = speedBound_.apply(bodies_, b, e)) slowed += k;
  });
  stats_.speedLimited += slowed.load();
}

uint32_t World::projectTurns() {
  TurnProjectionInput in;
  in.bodies = &bodies_;
  in.shapes = &shapes_;
  in.contacts = &contacts_;
  in.edges = contactEdges_.data();
  in.jointed = bodies_.implicitGyro.data();  // set for every body given a joint (World::addJoint)
  in.pinched = settings_.resolvePinches ? &pinch_.pinchedContacts() : nullptr;
  in.up = upDirection();
  in.reach = speedBound_.reaches();
  in.toleranceScale = toleranceScale_.data();
  in.startBounds = bounds_.data();
  in.dt = settings_.dt;
  in.contactMargin = settings_.contactMargin;
  return turnProjection_.apply(in, settings_.turnProjection, parallelRanges());
}

void World::step() {
  const auto t0 = Clock::now();
  const FlushDenormals mode;  // core/flush_denormals.h: a resting pile's tiny speeds cost microcode
  // settings() is writable: a thread count set there takes effect here, before anything runs on the
  // workers, so the arena, the phase clocks and the controller's cost split never disagree.
  if (settings_.threads != workerThreads_) setThreads(settings_.threads);
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
  parallelFor(n, kBodyGrain, [&](uint32_t b, uint32_t e) { integrateVelocities(bodies_, b, e, settings_.gravity, dt); });
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
    findPinnedBodies();
  }
  islandBuilder_.build(bodies_, contactEdges_.data(), uint32_t(contactEdges_.size()), joints_, islands_,
                       parallelRanges());
  if (settings_.topDownOrder) orderContactsTopDown();
  else order_.tail.assign(islands_.islands.size(), 0);
  if (settings_.coldStartFromWeight && settings_.contact.warmStart && settings_.topDownOrder) estimateColdImpulses();
  splitGiantIslands();
  batchLanes();
  std::fill(islandOfBody_.begin(), islandOfBody_.end(), -1);
  for (uint32_t k = 0; k < islands_.islands.size(); ++k) {
    const Island& isl = islands_.islands[k];
    for (uint32_t j = 0; j < isl.bodyCount; ++j) islandOfBody_[islands_.bodies[isl.firstBody + j]] = int32_t(k);
  }
  if (!joints_.empty()) speedBound_.setMotorSurface(motorSurfaceSpeed());

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
  parallelFor(n, kPoseGrain, [&](uint32_t b, uint32_t e) {
    dampRestingMotion(bodies_, islandOfBody_.data(), islands_, restSpeed, b, e);
    integratePositions(bodies_, b, e, dt, settings_.sleepLinear, settings_.sleepAngular);
  });
  for (const PinnedBody& pin : pins_) integratePinned(bodies_, pin, settings_.gravity, dt, settings_.sleepLinear, settings_.sleepAngular);
  const auto t3 = Clock::now();
  relaxIslands(relax);
  boundSpeeds();
  const auto t4 = Clock::now();
  stats_.turnProjected = projectTurns();
  if (!joints_.empty()) breakJoints();
  // The turn projection and joint breaking are counted in solve_ms (docs/metrics.md), but they cost
  // the same whatever the iteration count: the controller plans them with the work after the solve.
  // Split by the phase clocks, which do not see them, they made sweeps look dearer (in `tumbler` at
  // 4 iterations the projection moved 1930 bodies a step, ~2 ms of one thread's time).
  const double afterSolveMs = msSince(t4);
  const double relaxMs = msSince(t3);
  stats_.solveMs += relaxMs;
  summariseIterations();
  // What the solve did, relax sweeps included, once the counts are summed (not before).
  obs.solveMs = stats_.solveMs - afterSolveMs;
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
  obs.integrateMs = stats_.integrateMs + afterSolveMs;
  obs.totalMs = stats_.totalMs;
  controller_->observe(ctx, obs);
  ++stepCount_;
}

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
