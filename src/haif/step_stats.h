// What one step did and cost: the row of stats.csv.
#pragma once

#include <cstdint>
#include <limits>

namespace haif {

/// Pipeline stages that ran in a step (a bitmask): what the scene did not need is skipped.
enum StageBits : uint32_t {
  kStageBroadPhase = 1u << 0,
  kStageNarrowPhase = 1u << 1,
  kStageBuoyancy = 1u << 2,
  kStageMeshTests = 1u << 3,
  kStageJoints = 1u << 4,
  kStageSolve = 1u << 5,
  kStageSleep = 1u << 6,
};

struct StepStats {
  uint64_t step = 0;
  double collisionMs = 0, solveMs = 0, integrateMs = 0, totalMs = 0;
  double budgetMs = 0;            ///< 0: no budget
  bool deadlineMiss = false;      ///< totalMs > budgetMs (with a budget)
  int iterationsChosen = 0;       ///< I decided by the controller for this step
  int iterationsMin = 0, iterationsMax = 0;  ///< iterations actually run, over islands
  double iterationsMean = 0;
  uint64_t rowIterations = 0;     ///< Σ rows × iterations run (work done)
  float residual = 0;             ///< largest last-iteration velocity correction over islands (m/s)
  double solveError = std::numeric_limits<double>::quiet_NaN();  ///< docs/metrics.md; NaN: not measured
  uint32_t islands = 0, largestIsland = 0;   ///< largest in bodies
  uint32_t awakeBodies = 0, sleepingBodies = 0;
  uint32_t contacts = 0, contactPoints = 0;  ///< touching manifolds and their points
  uint32_t newPairs = 0;
  bool treeRebuilt = false;       ///< the broad phase built its tree afresh (many bodies left their fat boxes)
  uint32_t manifoldsReused = 0;   ///< touching pairs whose manifold moved with their bodies instead of being made again
  uint32_t stages = 0;            ///< StageBits
  float jointErrorM = 0;          ///< largest joint anchor error after the step (m); 0 without joints
  float jointErrorRad = 0;        ///< largest joint angular error after the step (rad)
  uint32_t pinchedBodies = 0;     ///< dynamic bodies pressed from opposite sides by static or kinematic ones (haif/pinch.h)
  uint32_t turnProjected = 0;     ///< pairs a fast turn, a crush or a blow carried into each other, moved apart after the step (haif/turn_projection.h)
  uint32_t speedLimited = 0;      ///< times a body was slowed to the speed bound this step (haif/speed_bound.h)
  uint32_t exactFactors = 0;      ///< factorisations of the systems of islands solved together (dynamics/contact_chain.h)
  uint32_t mostUnsettledSweeps = 0;  ///< most sweeps of one island solved together whose rounds did not settle
};

}  // namespace haif
