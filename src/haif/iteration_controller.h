// Chooses the solver iteration count of each step (docs/architecture.md, "The iteration controller").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// What the controller sees when it decides, after collision detection.
struct ControlContext {
  uint64_t step = 0;
  double budgetMs = 0;      ///< frame budget for the whole step (0: none)
  double elapsedMs = 0;     ///< already spent in this step (measured, or modelled in model mode)
  uint32_t totalRows = 0;   ///< solver rows over all islands (work of one iteration)
  uint32_t largestRows = 0; ///< rows of the largest island
  uint32_t islands = 0;
  uint32_t bodies = 0;          ///< awake dynamic bodies
  uint32_t contactPoints = 0;   ///< contact points found by the narrow phase
  int threads = 1;
};

/// What the solve cost, reported back after it.
struct SolveObservation {
  /// Measured wall time of the solve stage: rows built, sweeps, relax sweeps, impulses stored (not the
  /// turn projection or joint breaking after them, which StepStats::solveMs includes: they are in
  /// integrateMs here, work that does not grow with the iterations).
  double solveMs = 0;
  uint64_t rowIterations = 0;       ///< Σ rows × iterations over islands
  uint64_t criticalRowIterations = 0;  ///< the same along the critical path
  int iterations = 0;               ///< I that was chosen
  double integrateMs = 0;           ///< measured time of integration, sleep, turn projection and joint breaking
  double totalMs = 0;               ///< measured time of the whole step
  /// Thread time (summed over threads) of the solve's once-per-step work and of its sweeps; their
  /// ratio splits solveMs. Both 0: not measured (the model's ratio is used).
  double fixedThreadMs = 0;
  double sweepThreadMs = 0;
};

class IterationController {
 public:
  virtual ~IterationController() = default;
  /// Iteration count for this step (islands may stop earlier once converged).
  virtual int choose(const ControlContext& ctx) = 0;
  /// Called at the end of every step with what it cost.
  virtual void observe(const ControlContext&, const SolveObservation&) {}
  virtual std::string name() const = 0;
  /// Whether the step's decisions depend on the wall clock (only `adaptive` does).
  virtual bool usesClock() const { return false; }
  int iMin = 1;   ///< keeps basic stability
  int iMax = 64;
};

/// The same count every step.
class FixedController final : public IterationController {
 public:
  explicit FixedController(int iterations) : n_(iterations) { iMin = iMax = iterations; }
  int choose(const ControlContext&) override { return n_; }
  std::string name() const override { return "fixed"; }

 private:
  int n_;
};

}  // namespace haif
