// Adaptive iteration control (DESIGN.md §2):
//   I = clamp(floor(α · T_remaining / t_iter), I_min, I_max)
// T_remaining is the budget minus what the step already spent (after collision detection) minus
// what it will still spend outside the iterations (row preparation, integration); t_iter is the
// cost of one iteration along the critical path: max(largest island, total / threads) rows.
// In `adaptive` mode times come from the wall clock and the per-row costs are learned online; in
// `model` mode both come from the cost model alone, so decisions are deterministic.
//
// Learning: the solve costs p + n·q per critical row, p the once-per-step part (rows built, warm
// started, stored) and q one sweep, n the sweeps run along the critical path. The world times both
// parts on the threads that run them; their ratio splits the measured solve time, and p and q are
// averaged from step to step. Fitting one scale at the cost model's p/q ratio instead was wrong
// whenever the ratio was: a ratio 3x too low made every extra sweep look 2x dearer than it was,
// and the controller settled at half the budget.
#pragma once

#include "haif/cost_model.h"
#include "haif/iteration_controller.h"

namespace haif {

struct AdaptiveSettings {
  double alpha = 0.8;       ///< fraction of the remaining time the iterations may use
  int iMin = 4;
  int iMax = 64;
  int maxStepUp = 2;        ///< I rises by at most this much per step (smoothing); it falls at once
  double learnRate = 0.15;  ///< EMA weight of a new measurement of the per-row costs
};

class AdaptiveController final : public IterationController {
 public:
  AdaptiveController(const CostModel& model, const AdaptiveSettings& s, bool useClock);
  int choose(const ControlContext& ctx) override;
  void observe(const ControlContext& ctx, const SolveObservation& obs) override;
  std::string name() const override { return useClock_ ? "adaptive" : "model"; }
  bool usesClock() const override { return useClock_; }

  const CostModel& model() const { return model_; }
  /// Rows on the critical path for this context (see CostModel::criticalRows).
  double criticalRows(const ControlContext& ctx) const;
  /// Time (ms) the controller expects an iteration over the critical path to take.
  double iterationMs(const ControlContext& ctx) const;
  /// Threads the critical path is planned for: the run's (adaptive) or the model's (model mode).
  int threadsFor(const ControlContext& ctx) const;

 private:
  CostModel model_;  // as given (calibrated or default); adaptive mode learns its per-row costs
  AdaptiveSettings s_;
  bool useClock_;
  double postMs_ = -1.0;  // learned integration time (adaptive mode)
  int observed_ = 0;      // steps learned from so far
  int previous_ = -1;
};

/// Replays the iteration counts of an earlier run, step by step (the last one repeats).
class ReplayController final : public IterationController {
 public:
  explicit ReplayController(std::vector<int> counts);
  int choose(const ControlContext& ctx) override;
  std::string name() const override { return "replay"; }

 private:
  std::vector<int> counts_;
};

}  // namespace haif
