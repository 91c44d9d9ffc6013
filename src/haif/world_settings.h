// Every setting of a World, in one struct: the scene file's "settings" embed it (scene/scene_desc.h)
// and the World keeps it, so a new setting is written once here, read where it acts, and parsed once.
#pragma once

#include "core/math.h"
#include "dynamics/contact_solver.h"
#include "dynamics/joint_solver.h"
#include "haif/speed_bound.h"
#include "haif/turn_projection.h"

namespace haif {

struct WorldSettings {
  float dt = 1.0f / 60.0f;
  Vec3 gravity = Vec3(0.0f, -9.81f, 0.0f);
  int iterations = 10;              ///< used by the default (fixed) controller
  /// How contacts are solved: SOR factor ω, Baumgarte β, slop, restitution threshold, warm starting,
  /// push-out cap, friction anchors (dynamics/contact_solver.h). Its dt is not read: the World's is.
  SolverParams contact;
  float contactMargin = 0.02f;      ///< speculative distance (m) beyond which points are not reported
  /// The contact tolerances (slop, contact margin, broad-phase margins, manifold reuse, the turn
  /// projection's depths; not the skin) are lengths for bodies at least this thick (m); a thinner
  /// body's pairs scale them by its thickness over this (haif/small_bodies.h). Read when a body is
  /// added. 0: never scaled.
  float toleranceThickness = 0.05f;
  bool topDownOrder = true;         ///< solve the highest contacts of an island first
  bool accelerate = true;           ///< conjugate-gradient momentum between sweeps (contact_solver.h)
  /// Momentum only for islands at least this many layers of bodies deep (World::supportLayers): it
  /// carries a deep pile's weight down, and only adds overshoot to a low one (world.cpp).
  float momentumLayers = 16.0f;
  bool coldStartFromWeight = true;  ///< new contacts of a resting pile start from the weight they carry
  /// Sweep contacts kLanes manifolds at a time with SIMD, in lane batches (wide_contact_solver.h,
  /// lane_batches.h). Off by default: 3.8× faster per manifold in cache, but no faster yet on whole
  /// scenes (docs/solver.md, "Wide sweeps").
  bool wideSolve = false;
  /// Sweep each island's contacts in lane-batch order (constraints that share no dynamic body side
  /// by side), so the processor overlaps neighbours instead of waiting on each one's velocities. The
  /// same result as the plain order to the bit (World::batchLanes); off only to compare the two.
  bool interleaveSolveOrder = true;
  bool chainSolve = true;           ///< solve the normal rows of chain-shaped islands (stacks) exactly
  /// Small islands (up to 32 contacts) in which a body rests on or against one this many times
  /// lighter or heavier have their normal rows solved together each sweep (contact_chain.h): sweeps
  /// pass a heavy body's landing through a light one a fraction per sweep. Islands of up to 64
  /// contacts need 6 times this ratio (DenseNormalSystem::kLargeIslandRatioFactor). An island with
  /// joints and up to 32 contacts has them solved through its joint tree where a contact moves at most
  /// 1/(2 × this) as much through the joints as on its own bodies (dynamics/joint_coupling.h). 0: off.
  float exactMassRatio = 4.0f;
  /// An island of up to 32 contacts, more contacts than bodies and no joints, more than this many
  /// layers of bodies deep (World::supportLayers) per main sweep of the step, has its normal rows
  /// solved together, as a chain's are (a sweep passes a landing down about one layer). Columns of
  /// unit boxes landing through 1 cm gaps with a box beside the bottom one (no chain), swept: 12
  /// layers stood at 3 main sweeps, 14, 16 and 20 fell; 25 fell at 5 and stood at 6; 30 fell at 6 and
  /// stood at 8: sweeps fail from ~4.7 layers a sweep, and 3 leaves room. 0, or chainSolve off: off.
  float deepLayersPerSweep = 3.0f;
  /// A swept island in motion (a body's surface faster than a quarter of |g| dt) gets main sweeps
  /// enough for its depth, one per this many layers of bodies (World::supportLayers), and a third of
  /// those added as relax sweeps. A sweep settles about half a layer of a tower's sway; with fewer
  /// the sway grew until the tower fell (towers of crossed 2-block layers, nudged or landing through
  /// 1 cm gaps, fell from 8 layers at 4 iterations and from 12 at 10; brick walls from 14 at 4). At
  /// rest the warm start holds them, and the step's count stands. Chains, islands solved together,
  /// jointed and split islands keep the step's count, and so does every island under a frame budget
  /// (budgetMs > 0: the controller plans the sweeps). 0: off.
  float movingLayersPerSweep = 0.5f;
  /// A contact between two dynamic bodies whose points are all farther apart than the pair can close
  /// within the step (ContactEdge::apart) joins no two bodies into one island: a bed of bricks laid
  /// 2-3 cm apart is then many islands, and a heavy ball landing on it an island of the few bricks
  /// under it, solved together (a 20 t ball on 250 kg bricks comes to rest instead of bouncing and
  /// rolling off). Off by default: the landing, solved so, still kicks a light brick sideways
  /// (1-3.5 m/s, its relax sweep's normal impulse on a tilted edge normal, with no friction after
  /// it), and its cost under a frame budget is not yet measured (docs/solver.md, "Contacts that
  /// cannot touch this step").
  bool splitApartContacts = false;
  bool reuseManifolds = true;       ///< keep a pair's manifold while its bodies keep still (manifold_cache.h)
  JointSolverParams joints;         ///< how joints are solved (dynamics/joint_solver.h)
  SpeedBoundSettings speedBound;    ///< the bound on every body's speed (haif/speed_bound.h)
  /// Bodies pressed from opposite sides by static or kinematic ones get no push-out and carry no
  /// impulse between steps, and their static contacts are solved last (haif/pinch.h).
  bool resolvePinches = true;
  /// After the step, pairs a fast turn, a crush or a blow within the step carried deeper than they
  /// may keep are collided again and moved apart (haif/turn_projection.h).
  TurnProjectionSettings turnProjection;
  /// Bodies in contact moving slower than this fraction of |g| dt are slowed before their poses move:
  /// the solve's leftover creep in a resting pile (haif/rest_damping.h). 0: off.
  float restDamping = 0.05f;
  bool sleeping = false;
  float timeToSleep = 0.5f;         ///< s an island must rest before it sleeps
  float sleepLinear = 0.05f;        ///< m/s
  float sleepAngular = 0.05f;       ///< rad/s
  float residualTolerance = 0.0f;   ///< islands stop iterating below this velocity correction (0: never)
  double budgetMs = 0.0;            ///< frame budget given to the controller (0: none)
  int threads = 1;
};

}  // namespace haif
