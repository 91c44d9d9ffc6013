// The joint stage: joints added and broken, their bodies woken and stiffened, their rows prepared
// and their impulses kept per island.
#include "haif/world_internal.h"

namespace haif {

namespace {

// The simulated time at the end of the step being taken: what the servos' trajectories are read at.
inline float stepEndTime(uint64_t stepCount, float dt) { return float(stepCount + 1) * dt; }

}  // namespace

uint32_t World::addJoint(const JointDef& def) {
  auto valid = [&](uint32_t b) { return b == kWorldBody || b < bodyCount(); };
  if (!valid(def.bodyA) || !valid(def.bodyB)) throw std::invalid_argument("addJoint: unknown body");
  if (def.bodyA == def.bodyB) throw std::invalid_argument("addJoint: a joint needs two different bodies");
  Joint j;
  j.def = def;
  joints_.push_back(j);
  if (def.bodyA != kWorldBody && def.bodyB != kWorldBody) {
    // A second joint between the same two bodies: their rows are merged for the tree (mergeParallelJoints).
    const uint64_t key = PairMap::key(def.bodyA, def.bodyB);
    const uint32_t n = jointedPairs_.find(key);
    jointedPairs_.set(key, n == PairMap::kNotFound ? 1u : n + 1u);
    if (n != PairMap::kNotFound) parallelJoints_ = true;
  }
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

// The fastest surface any island's motors drive (haif/speed_bound.h): a hinge motor turns a body about
// its anchor at its aim, a slider moves it along at its aim; motors in one island (an arm's servos, a
// car's wheels) add up. The lever of a hinge is the shorter of its dynamic bodies' (anchor distance
// plus reach): the wheel of a car, not the chassis it is fixed to, is what the motor spins.
float World::motorSurfaceSpeed() {
  const float time = stepEndTime(stepCount_, settings_.dt);
  bool summing = false;  // the per-island sums are cleared at the first motor (most jointed scenes have none)
  float fastest = 0.0f;
  for (const Joint& j : joints_) {
    const JointDef& d = j.def;
    if (j.broken || !d.motorEnabled || (d.type != JointType::Hinge && d.type != JointType::Slider)) continue;
    int32_t island = -1;
    float lever = 1e30f;
    for (const auto& [body, anchor] : {std::pair{d.bodyA, d.localAnchorA}, std::pair{d.bodyB, d.localAnchorB}}) {
      if (body == kWorldBody || bodies_.kind[body] != BodyKind::Dynamic) continue;
      island = std::max(island, islandOfBody_[body]);
      lever = std::min(lever, anchor.norm() + speedBound_.reach(body));
    }
    if (island < 0) continue;  // asleep: it drives nothing this step
    const float position = d.servo.empty() ? 0.0f : jointPosition(bodies_, d);
    const float aim = std::abs(motorAim(d, position, time, settings_.dt));
    if (!summing) {
      islandMotorSurface_.assign(islands_.islands.size(), 0.0f);
      summing = true;
    }
    float& sum = islandMotorSurface_[uint32_t(island)];
    sum += d.type == JointType::Hinge ? aim * lever : aim;
    fastest = std::max(fastest, sum);
  }
  return fastest;
}

// Bodies whose only unbroken joint is a ball joint to the world or a static body turn about its
// anchor (integratePinned). Found every step: joints break, and their defs may be edited.
// Touches only the joints' bodies and the last step's pins, not every body.
void World::findPinnedBodies() {
  for (const PinnedBody& pin : pins_) bodies_.pinned[pin.body] = 0;
  pins_.clear();
  if (jointsOfBody_.size() < bodyCount()) jointsOfBody_.resize(bodyCount(), 0);  // zero between calls
  auto fixed = [&](uint32_t b) { return b == kWorldBody || bodies_.kind[b] == BodyKind::Static; };
  auto forJointedBodies = [&](auto&& f) {
    for (const Joint& j : joints_)
      if (!j.broken)
        for (uint32_t b : {j.def.bodyA, j.def.bodyB})
          if (!fixed(b)) f(jointsOfBody_[b]);
  };
  forJointedBodies([](uint8_t& n) { n = uint8_t(std::min(2, n + 1)); });
  for (const Joint& j : joints_) {
    const JointDef& d = j.def;
    if (j.broken || d.type != JointType::Ball || fixed(d.bodyA) == fixed(d.bodyB)) continue;
    const bool bodyIsB = fixed(d.bodyA);
    const uint32_t body = bodyIsB ? d.bodyB : d.bodyA, holder = bodyIsB ? d.bodyA : d.bodyB;
    if (bodies_.kind[body] != BodyKind::Dynamic || jointsOfBody_[body] != 1) continue;
    PinnedBody pin;
    pin.body = body;
    pin.anchor = bodyIsB ? d.localAnchorB : d.localAnchorA;
    const Vec3& held = bodyIsB ? d.localAnchorA : d.localAnchorB;
    pin.point = holder == kWorldBody ? held : bodies_.xf[holder].apply(held);
    pins_.push_back(pin);
    bodies_.pinned[body] = 1;
  }
  forJointedBodies([](uint8_t& n) { n = 0; });
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
      pairs_.set(key, static_cast<uint32_t>(contacts_.size()));
      contacts_.push_back(newContact(d.bodyA, d.bodyB));
    }
  }
}

// Geometric stiffness of loaded joints, added to their bodies' inertia for this step's solve
// (contacts and joints alike); integration puts the true inertia back.
void World::stiffenJointedBodies() {
  if (!settings_.joints.geometricStiffness) return;
  jointStiffness_.assign(bodyCount(), 0.0f);
  for (uint32_t ji : islands_.joints) accumulateJointStiffness(bodies_, joints_[ji], jointStiffness_.data());
  // A pinned body turns about its point by its true inertia there (integratePinned), which reads
  // the solve's velocities as angular momentum about the point: the joint's impulse has no moment
  // about it only if the solve splits it by the true inertia too. Stiffened, a 1 m pendulum of a
  // 5 cm ball (k = m g L dt², 2.7 × its own inertia) lost 0.02 % of its swing's energy a swing.
  for (const PinnedBody& pin : pins_) jointStiffness_[pin.body] = 0.0f;
  for (uint32_t i : islands_.bodies) stiffenInertia(bodies_, i, jointStiffness_[i], settings_.dt);
}

// Rows of island k's joints, warm started, and its joint tree factorised (when joints are solved as a tree).
void World::prepareJoints(uint32_t k, const SolverParams& sp) {
  const Island& isl = islands_.islands[k];
  JointConstraint* js = jointConstraints_.data() + isl.firstJoint;
  const uint32_t nj = isl.jointCount;
  const uint32_t* ids = islands_.joints.data() + isl.firstJoint;
  const float time = stepEndTime(stepCount_, sp.dt);
  const JointSolverParams& jp = settings_.joints;
  for (uint32_t j = 0; j < nj; ++j) prepareJointForStep(bodies_, joints_[ids[j]], ids[j], sp, jp, time, js[j]);
  if (sp.warmStart) warmStartJoints(bodies_, js, nj);
  if (jp.treeSolve) {
    jointTreeOf(k).build(js, nj, parallelJoints_);
    prepareTreeMotors(js, nj, jointTreeOf(k), treeMotorsOf(k));
  } else
    for (uint32_t j = 0; j < nj; ++j) prepareSoftBlock(js[j]);
  // No tree holds these joints (a net): every row is swept, no stiffer than the sweeps converge on.
  const float hertz = jp.softHertzFor(jointMainSweeps_, sp.dt);
  if ((!jp.treeSolve || jointTreeOf(k).size() == 0) && hertz < jp.softHertz)
    for (uint32_t j = 0; j < nj; ++j) setSoftness(js[j], hertz, jp.softDampingRatio, sp.dt);
}

// After the relax sweeps: keep the impulses for the next step, then (the rows being free now) project the
// tree joints back onto their constraints at the integrated positions.
void World::finishJoints(uint32_t k) {
  const Island& isl = islands_.islands[k];
  JointConstraint* js = jointConstraints_.data() + isl.firstJoint;
  const uint32_t nj = isl.jointCount;
  storeJointImpulses(js, nj, settings_.dt, settings_.joints.stiffnessHold, joints_.data());
  const bool stiff = settings_.joints.geometricStiffness;
  const uint32_t* bodies = islands_.bodies.data() + isl.firstBody;
  if (settings_.joints.treeSolve && settings_.joints.postProjection) {
    // The projection moves bodies in the same metric as the solve: light loaded links mostly translate.
    if (stiff)
      for (uint32_t j = 0; j < isl.bodyCount; ++j)
        stiffenInertia(bodies_, bodies[j], jointStiffness_[bodies[j]], settings_.dt);
    projectJointPositions(bodies_, joints_.data(), islands_.joints.data() + isl.firstJoint, nj, solverParams(),
                          settings_.joints, js, jointTreeOf(k), parallelJoints_);
    if (stiff)
      for (uint32_t j = 0; j < isl.bodyCount; ++j) bodies_.updateWorldInertia(bodies[j]);
  }
}

void World::measureJointErrors() {
  for (uint32_t i = 0; i < jointCount(); ++i) {
    const JointError e = jointError(i);
    stats_.jointErrorM = std::max(stats_.jointErrorM, e.linear);
    stats_.jointErrorRad = std::max(stats_.jointErrorRad, e.angular);
  }
}

}  // namespace haif
