// The physics world: bodies, shapes, contacts, and the step pipeline (docs/architecture.md, "One step").
// It lives in src/haif (not src/core) because the step uses islands and the iteration
// controller, and dependencies must point one way: haif -> dynamics -> collision -> core.
#pragma once

#include "collision/broad_phase.h"
#include "collision/pair_map.h"
#include "collision/shape.h"
#include "core/body_store.h"
#include "core/growing_array.h"
#include "dynamics/buoyancy.h"
#include "dynamics/contact.h"
#include "dynamics/contact_chain.h"
#include "dynamics/contact_solver.h"
#include "dynamics/integrator.h"
#include "dynamics/joint_solver.h"
#include "dynamics/joint_coupling.h"
#include "dynamics/joint_tree.h"
#include "dynamics/motor_mass.h"
#include "haif/island_split.h"
#include "haif/islands.h"
#include "haif/iteration_controller.h"
#include "haif/lane_batches.h"
#include "haif/pinch.h"
#include "haif/rest_damping.h"
#include "haif/sleep_sets.h"
#include "haif/small_bodies.h"
#include "haif/speed_bound.h"
#include "haif/step_stats.h"
#include "haif/tsan_pool.h"
#include "haif/world_settings.h"

#include <tbb/task_arena.h>

#include <algorithm>

#include <limits>
#include <memory>
#include <vector>

namespace haif {

struct BodyDef {
  BodyKind kind = BodyKind::Dynamic;
  Shape shape;
  Transform xf;
  Vec3 linearVelocity = Vec3::Zero();
  Vec3 angularVelocity = Vec3::Zero();
  float mass = 0.0f;          ///< > 0 overrides density
  float density = 1000.0f;
  float friction = 0.6f;
  float restitution = 0.0f;
  /// Rolling resistance coefficient (≥ 0): a sphere or capsule rolling on a surface feels a torque
  /// against its roll of this times the normal force times its radius (docs/solver.md, "Rolling
  /// resistance"). 0: it rolls on, as an ideal rigid ball does.
  float rollingResistance = 0.0f;
  float linearDamping = 0.0f;
  float angularDamping = 0.0f;
};

/// How far apart (m) a contact's points may be and still close within a step (World::outOfReach):
/// the slop scaled to its bodies (`scale`, haif/small_bodies.h) and a fall's step (`fall`: g dt²).
inline float contactReach(float slop, float scale, float fall) { return slop * scale + fall; }

class World {
 public:
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Adds a body; returns its id (dense, in insertion order).
  uint32_t addBody(const BodyDef& def);
  void addWater(const WaterVolume& w) { water_.push_back(w); }
  /// Adds a joint between two bodies, or a body and kWorldBody; returns its id (dense, in insertion
  /// order). Throws std::invalid_argument for unknown bodies or a body joined to itself.
  uint32_t addJoint(const JointDef& def);
  uint32_t jointCount() const { return static_cast<uint32_t>(joints_.size()); }
  const Joint& joint(uint32_t id) const { return joints_[id]; }
  /// The definition of a joint, to change its motor, limits or thresholds between steps.
  JointDef& jointDef(uint32_t id) { return joints_[id].def; }
  /// Position error of a joint at the current state (docs/metrics.md, "Joint error"); zero for a broken joint.
  JointError jointError(uint32_t id) const;
  /// Replaces the iteration controller (default: fixed at settings.iterations).
  void setController(std::unique_ptr<IterationController> c);
  IterationController& controller() { return *controller_; }
  /// Worker threads used by the parallel stages (1 = everything on the calling thread).
  void setThreads(int threads);
  int threads() const { return settings_.threads; }
  /// Threads the parallel stages run on now (settings().threads takes effect at the next step).
  int workerThreads() const { return workerThreads_; }
  /// Measure the solve error (docs/metrics.md) every `every` steps (0: never). Costs a converged solve.
  void setSolveErrorInterval(int every) { solveErrorEvery_ = every; }

  /// Advances the world by settings().dt.
  void step();
  /// Of I iterations, how many are relax iterations (run after integration, without position
  /// correction, so the push-out velocity does not become kinetic energy).
  static int relaxIterationsFor(int iterations);

  const WorldSettings& settings() const { return settings_; }
  WorldSettings& settings() { return settings_; }
  const BodyStore& bodies() const { return bodies_; }
  BodyStore& bodies() { return bodies_; }
  uint32_t bodyCount() const { return static_cast<uint32_t>(bodies_.size()); }
  const Shape& shape(uint32_t body) const { return shapes_[body]; }
  const ContactList& contacts() const { return contacts_; }
  /// Per contact, its bodies and point count as of the last narrow phase (what island building reads).
  const std::vector<ContactEdge>& contactEdges() const { return contactEdges_; }
  const IslandSet& islands() const { return islands_; }
  /// The broad phase's boxes (read-only: tests and tools look at what the step keeps).
  const BroadPhase& broadPhase() const { return broadPhase_; }
  /// Island index (into islands().islands) a body was solved in during the last step; -1 if none.
  int32_t islandOf(uint32_t body) const { return body < islandOfBody_.size() ? islandOfBody_[body] : -1; }
  const StepStats& lastStats() const { return stats_; }
  /// The surface speed (m/s) no body may exceed in the last step (haif/speed_bound.h).
  float speedLimit() const { return speedBound_.limit(); }
  uint64_t stepCount() const { return stepCount_; }
  bool hasWater() const { return !water_.empty(); }

  /// FNV-1a hash of every body's position and orientation bits: equal states give equal hashes.
  uint64_t stateHash() const;
  /// Kinetic energy (J) and potential energy relative to y = 0 (J) of the dynamic bodies.
  double kineticEnergy() const;
  double potentialEnergy() const;
  /// Wakes a sleeping body and the sleeping island it belongs to.
  void wake(uint32_t body);

 private:
  void updateBroadPhase();
  /// A contact for a new pair, with the two bodies' materials combined.
  Contact newContact(uint32_t a, uint32_t b) const;
  void narrowPhase();
  /// How far a compound's far parts move in a second from its spin (|ω| times its reach); 0 for
  /// single shapes (their margin follows the centre's speed only).
  float spinReach(uint32_t body) const;
  void solve(int iterations);
  void solveIslands(int iterations);
  void splitGiantIslands();
  void batchLanes();
  template <class F> SweepResult forEachStrip(uint32_t island, F&& f);
  template <class F, class Pair> SweepResult forEachStrip(uint32_t island, F&& f, Pair&& pair);
  /// f(begin, end) over island k's contacts: in chunks of `grain` in parallel for a split (giant)
  /// island, as one range on the calling thread otherwise.
  template <class F> void forEachContactChunk(uint32_t island, uint32_t grain, F&& f);
  /// f(rows, count, lanes) over each strip of a wide island k (forEachStrip), with the strip's rows
  /// and its view of the lane batches: packing, unpacking and re-aiming the lanes.
  template <class F> void forEachLaneRange(uint32_t island, F&& f);
  /// Against gravity (+y without gravity): what top-down order and strips are measured along.
  Vec3 upDirection() const;
  /// Island k's top-down keys (in island order): when the island is no chain only because of
  /// contacts whose points are all further apart than the slop and a fall's step (a thin plate's
  /// contact with the plate two below, past the one between), their keys are moved to its end, so
  /// the chain before them is solved exactly and they are swept after it (world_solve_order.cpp).
  /// Returns how many were moved.
  uint32_t moveOutOfReachToTail(uint32_t k, uint64_t* keys);
  uint32_t tailOf(uint32_t k) const { return order_.tail[k]; }
  bool sortsAsLastStep(uint32_t k) const;
  /// How far (m) two bodies fall towards each other in a step: g dt². Taken once per pass, not per
  /// contact (a square root).
  float fallOfAStep() const { return settings_.gravity.norm() * settings_.dt * settings_.dt; }
  /// Every point of contact `ci` is farther apart than its slop (scaled to its bodies, as the contact's
  /// own: haif/small_bodies.h) and a fall's step (`fall`, fallOfAStep): nothing can close it this step
  /// unless something moves fast, so it holds nothing up. Unscaled, the 5 mm slop reached past a 4 mm
  /// plate to the one below it: a stack of such plates was no chain, and swept at 4 iterations it sank
  /// half a plate into itself.
  bool outOfReach(uint32_t ci, float fall) const {
    const ContactEdge& e = contactEdges_[ci];
    return e.nearest < -contactReach(settings_.contact.slop, pairToleranceScale(toleranceScale_[e.a], toleranceScale_[e.b]), fall);
  }
  /// `restartDirection`: the island's momentum direction restarts from the last sweep's change
  /// (see solveIteration); only for joint-free islands swept plainly or wide. `measureChange`:
  /// fill SweepResult::change, which only the momentum step needs.
  SweepResult sweepIsland(uint32_t island, bool useBias, bool restartDirection = false, bool measureChange = false);
  void shareSpareIterations(int iterations);
  void relaxIslands(int relaxIterations);
  bool onlyPinned(uint32_t island) const;  // every body of the island is pinned (BodyStore::pinned)
  /// Island k is to be solved as a small island (prepareSmallIsland) this step: few contacts, no
  /// joints, not split, two bodies in contact whose masses differ by exactMassRatio or more, and a
  /// landing in it lately (counted down in its contacts' Contact::exactSteps).
  bool wantsSmallIslandSolve(uint32_t k);
  /// Island k, of at most kCheapLinks contacts and more contacts than bodies (no lone column), no
  /// joints and not split, is deeper than this step's `mainSweeps` carry a landing through
  /// (WorldSettings::deepLayersPerSweep): solved as a small island too, with room for all its rows.
  bool tooDeepForSweeps(uint32_t k, int mainSweeps) const;
  /// Main sweeps beyond the step's `mainSweeps` that swept island k needs this step: where a body
  /// moves and the island is deeper (World::supportLayers) than mainSweeps settle
  /// (WorldSettings::movingLayersPerSweep), enough to settle its depth; 0 elsewhere, and under a
  /// frame budget, whose sweeps the controller plans.
  int sweepsForDepth(uint32_t k, int mainSweeps) const;
  /// Island k may have its contacts solved through its joints (dynamics/joint_coupling.h): joints and
  /// at most kCheapLinks contacts, not split. Whether it is, prepareIsland decides from its rows.
  bool mayCoupleJoints(uint32_t k) const;
  /// The coupling of island k's contacts with its joint tree, for its sweeps.
  JointCoupling jointCouplingOf(uint32_t k);
  /// The rows island k's small-island system may need: 3 a contact (a force and two torques), at
  /// most kCheapRows for an island of up to kCheapLinks contacts.
  int denseRowsOf(uint32_t k) const {
    const uint32_t contacts = islands_.islands[k].contactCount;
    const int most = contacts > uint32_t(DenseNormalSystem::kCheapLinks) ? DenseNormalSystem::kMaxRows
                                                                          : DenseNormalSystem::kCheapRows;
    return int(std::min<uint32_t>(3 * contacts, uint32_t(most)));
  }
  void summariseIterations();
  SolverParams solverParams() const;
  /// Runs over the islands in parallel, batched (batchStart_), in two phases per batch: first(k) for
  /// all its islands then second(k), timing both on the thread that runs the batch: one phase is
  /// once-per-step work, the other sweeps (see PhaseClock).
  template <class First, class Second>
  void forEachIslandTimed(First&& first, Second&& second, bool firstIsSweeps = false);
  double measureSolveError(int iterations);
  void detectSleep();
  void orderContactsTopDown();
  void estimateColdImpulses();
  void putIslandToSleep(const Island& isl);
  void wakeJointedBodies();
  float motorSurfaceSpeed();
  void stiffenJointedBodies();
  void prepareJoints(uint32_t island, const SolverParams& sp);
  void finishJoints(uint32_t island);
  void breakJoints();
  void findPinnedBodies();
  void measureJointErrors();
  template <class F> void parallelFor(uint32_t n, uint32_t grain, F&& f);
  /// parallelFor as a callable, for the stages that take one (TurnProjection, IslandBuilder, IslandSplitter).
  auto parallelRanges() {
    return [this](uint32_t n, uint32_t grain, auto&& f) { parallelFor(n, grain, f); };
  }

  WorldSettings settings_;
  BodyStore bodies_;
  std::vector<Shape> shapes_;
  std::vector<float> volume_;
  std::vector<float> toleranceScale_;  // per body: its factor on the contact tolerances (haif/small_bodies.h)
  std::vector<Aabb> bounds_;
  std::vector<WaterVolume> water_;
  bool hasMesh_ = false;
  /// A body has a rolling resistance: the solver builds rolling rows (SolverParams::rolling).
  bool hasRolling_ = false;

  BroadPhase broadPhase_;
  PairMap pairs_;
  ContactList contacts_;
  // The broad and narrow phase's scratch (world_collision.cpp).
  struct CollisionBuffers {
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> newPairRuns;  // per run of moved bodies: pairs found
    std::vector<uint8_t> pairFlags;   // per contact: kPairWakes | kPairApart, this step
    std::vector<uint8_t> reusedFlag;  // per contact: its manifold was reused this step
    std::vector<uint8_t> leftFat;     // per body: its box left its fat box this step
  } collision_;
  std::vector<ContactEdge> contactEdges_;  // per contact: its bodies and point count, from the narrow phase on
  PinchDetector pinch_;               // marks contacts of bodies pressed between immovable ones
  uint32_t pinchedBodies_ = 0;        // this step's, from pinch_
  TurnProjection turnProjection_;     // moves apart the pairs the step carried too deep into each other

  IslandBuilder islandBuilder_;
  IslandSet islands_;
  std::vector<int32_t> islandOfBody_;
  std::vector<float> islandMotorSurface_;  // per island: its motors' surface speeds summed (scratch)
  // The solve order's scratch (world_solve_order.cpp): top-down keys and the cold-start loads.
  struct SolveOrderBuffers {
    std::vector<float> contactHeight;  // solve-order key per contact
    std::vector<uint64_t> keys;        // the top-down sort's keys (descendingKey), in island order
    std::vector<uint64_t> scratch;     // the radix sort's second buffer, beside keys
    std::vector<float> carried;        // per body: weight impulse (N s) it carries this step, for cold contacts
    std::vector<Vec2> carriedMoment;   // per body: that impulse's moment about its centre, across the vertical
    std::vector<uint32_t> supports;    // per body: contacts holding it up
    std::vector<uint32_t> firstSupport;     // per body: where its supports start in supportContacts
    std::vector<uint32_t> placed;           // per body: supports listed so far; 0 once its load is divided
    std::vector<uint32_t> supportContacts;  // the supports of each island's bodies, body by body
    std::vector<uint32_t> tail;        // per island: contacts at the end of its order that cannot touch this step
    // Last step's order, for islands that are last step's (IslandBuilder::reused): an island whose
    // contacts still sort as they did, with the same tail, takes that order and its lane batches again.
    std::vector<uint32_t> sorted, batched;  // islands_.contacts after the sort, and after the batching
    std::vector<uint32_t> tailBefore;       // per island: the tail the sort was made with
    std::vector<uint8_t> kept;              // per island, this step: its order is last step's
    uint64_t sortedStep = ~0ull, batchedStep = ~0ull;  // the steps they were made in
  } order_;
  // Rebuilt each step, 1.5 KB a touching contact; grown in place (core/growing_array.h).
  GrowingArray<ContactConstraint> constraints_;
  GrowingArray<ChainLink> chainLinks_;  // parallel to constraints_; used for islands that form a chain
  // Per island: how its normal rows are solved this step, when not swept (0): exactly as a chain, or
  // together as a small island (contact_chain.h).
  enum ExactSolve : uint8_t { kChainSolve = 1, kSmallIslandSolve = 2, kJointCoupledSolve = 3 };
  std::vector<uint8_t> isChain_;
  // Small islands holding a mass ratio (exactMassRatio) or too deep for the sweeps, solved with
  // their normal rows together: per island the system it uses, or -1; the systems grow to the most
  // such islands seen.
  std::vector<int32_t> denseOf_;
  std::vector<int> depthSweeps_;  // per island, this step: main sweeps added for its depth (sweepsForDepth)
  std::vector<int> denseRows_;  // per island: the rows its dense system has room for (0: none)
  std::vector<DenseNormalSystem> denseSystems_;
  std::vector<double> denseStorage_;  // their matrices, 3 per contact rows a side (grows, then reused)
  // Per body, zero between uses: the joints' response to one contact row (dynamics/joint_coupling.h).
  std::vector<Eigen::Vector3d> couplingDv_, couplingDw_;
  std::vector<Eigen::Vector3d> couplingChangeV_, couplingChangeW_;  // per body: change since the joints held
  std::vector<uint32_t> chainMark_;    // per body: scratch of prepareChain
  // Per island: what its sweeps did, and the spare iterations shared out (world_solve.cpp).
  struct SpareIterationBuffers {
    std::vector<int> iterations;    // sweeps it ran this step
    std::vector<float> residual;    // its last sweep's residual
    std::vector<int> extra;         // spare iterations given to it this step (unconverged)
    std::vector<uint32_t> order;    // unconverged islands, largest residual first
  } spare_;
  std::vector<uint32_t> batchStart_;  // island batches for parallel solving
  IslandSplitter splitter_;
  std::vector<int32_t> layoutOf_;     // per island: index into layouts_, or -1 when not split
  std::vector<StripLayout> layouts_;  // strips of this step's split islands (grows, then reused)
  std::vector<SweepResult> stripResult_;  // per layout, per strip: what its last sweep did
  // A split island's velocities while its rows are swept, its bodies strip by strip: two strips
  // swept at once then write no cache line in common (by body index they did wherever neighbouring
  // indices lay in different strips). Per layout; the rows name slots from prepare to store
  // (world_solve.cpp). Not with the wide solver, whose batches keep their own copies of indices.
  struct StripVelocities {
    std::vector<Vec3> v, w;
    std::vector<uint32_t> bodyOf;     // per slot: its body (the island's dynamic bodies first)
    std::vector<uint32_t> immovable;  // the immovable bodies its rows name, ascending, from slot immovableSlot on
    uint32_t dynamic = 0, immovableSlot = 0;
  };
  std::vector<StripVelocities> stripVelocities_;  // per layout
  std::vector<uint32_t> slotOf_;                  // per body of a split island: its slot there
  bool slotted(uint32_t island) const { return layoutOf_[island] >= 0 && !settings_.wideSolve; }
  VelocityView velocitiesOf(uint32_t island);
  void toSlots(uint32_t island, ContactConstraint& c) const;  // c's body ids to its island's slots
  void copyVelocitiesIn(uint32_t island);   // bodies' velocities into the island's slots
  void copyVelocitiesOut(uint32_t island);  // and back
  void assignSlots(uint32_t layout, uint32_t bodies);  // for the island the splitter just split
  std::vector<LaneBatcher> laneBatchers_;  // one per thread slot (threadSlot)
  std::vector<uint32_t> laneRanges_;      // this step's ranges to batch: begin, end in islands_.contacts
  std::vector<uint8_t> laneRun_;  // per contact slot: length of the lane batch starting there, else 0
  std::vector<int32_t> wideOf_;   // per contact slot starting a batch: its wide_ index, or -1 (scalar)
  std::vector<WideContactBatch> wide_;  // packed rows of this step's wide batches (grows, then reused)
  LaneBatches lanesOf(uint32_t island);
  /// Island k's contacts are swept by the wide solver (packed this step).
  bool isWide(uint32_t island) const;
  /// Layers of bodies the island's weight rests through: its height along `up` over its bodies'
  /// mean height (a pyramid of base 10 has 10, a 30-box column 30).
  float supportLayers(uint32_t island) const;

  std::vector<Joint> joints_;
  std::vector<JointConstraint> jointConstraints_;  // solver rows, grouped by island like constraints_
  // One slot per island with joints (jointSlot_: island -> slot, -1 none), not per island: a pour of
  // 10^5 bodies starts as 10^5 islands, whose slots held 59 MB of trees none of them used.
  std::vector<JointTree> jointTrees_;              // per slot: factorisation buffers, reused
  std::vector<TreeMotors> treeMotors_;             // per slot: its motors through its tree
  std::vector<int32_t> jointSlot_;                 // per island
  JointTree& jointTreeOf(uint32_t island) { return jointTrees_[size_t(jointSlot_[island])]; }
  TreeMotors& treeMotorsOf(uint32_t island) { return treeMotors_[size_t(jointSlot_[island])]; }
  std::vector<float> jointStiffness_;              // per body, this step (N m)
  PairMap jointedPairs_;                           // joints per pair of bodies (both not the world)
  bool parallelJoints_ = false;                    // some pair has two joints: merge their rows
  int jointMainSweeps_ = 0;                        // this step's main sweeps: soft rows' frequency (softHertzFor)
  PairMap jointPairs_;  // body pair -> number of unbroken joints that keep the two from colliding
  std::vector<PinnedBody> pins_;          // this step's pinned bodies (findPinnedBodies)
  std::vector<uint8_t> jointsOfBody_;     // findPinnedBodies' scratch: unbroken joints per body (capped)

  SleepSets sleepSets_;  // the sleeping islands (world_sleep.cpp)

  std::unique_ptr<IterationController> controller_;
  std::unique_ptr<tbb::task_arena> arena_;
  int workerThreads_ = 1;  // what arena_ (or pool_) was made for
#ifdef HAIF_TSAN
  std::unique_ptr<TsanPool> pool_;  // stands in for arena_ under ThreadSanitizer (haif/tsan_pool.h)
#endif
  // Thread time of the solve's once-per-step work (rows built, warm started, stored) and of its
  // sweeps, per worker slot; the controller splits the measured solve time by their ratio.
  struct alignas(64) PhaseClock {
    double fixedMs = 0.0, sweepMs = 0.0;
  };
  std::vector<PhaseClock> phaseClocks_;
  PhaseClock& phaseClock();
  /// Index of the calling thread among the step's threads (0 .. threads − 1).
  size_t threadSlot() const;
  void resetPhaseClocks();
  int solveErrorEvery_ = 0;
  double measurementMs_ = 0.0;  // time of this step's reference solve, excluded from its timings
  // The solve-error probe's velocities (world_solve_error.cpp): saved, the solve's start, the
  // reference; and the islands' tails, which a solve may take in (a landing through the tail).
  struct ProbeBuffers {
    std::vector<Vec3> saveV, saveW, startV, startW, refV, refW;
    std::vector<uint32_t> saveTail;
  } probe_;

  SpeedBound speedBound_;
  /// Slows bodies over the speed bound (all of them, in parallel); adds the count to the step's stats.
  void boundSpeeds();
  /// Runs the after-step TurnProjection stage over the step's pairs; returns the pairs it moved apart.
  uint32_t projectTurns();
  /// Water density over the lightest dynamic body's density (0 without water), for the speed bound.
  float waterLift() const;
  /// Lowest point of the static bodies along up (planes excluded; +inf without any: no floor), for
  /// the speed bound.
  float staticFloor_ = std::numeric_limits<float>::infinity();

  StepStats stats_;
  uint64_t stepCount_ = 0;
};

}  // namespace haif
