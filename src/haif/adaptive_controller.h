// Adaptive iteration control (docs/architecture.md, "The iteration controller"):
//   I = clamp(floor(α · T_remaining / t_iter), I_min, I_max)
// T_remaining is what the budget leaves after the step's collision detection, divided by c, minus
// what the step will still spend outside the iterations (row preparation, integration); t_iter is
// the cost of one iteration along the critical path: max(largest island, total / threads) rows.
// c is the aimed quantile (95 %) of how much the last 64 steps overran their plans after collision
// detection: step costs scatter (mixed island kinds, early stops, other work on the cores), and a
// plan at their mean missed a third of demo's 4 ms deadlines; at the quantile, under 1 %.
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

#include <array>
#include "haif/iteration_controller.h"

namespace haif {

struct AdaptiveSettings {
  double alpha = 0.8;       ///< fraction of the remaining time the iterations may use
  int iMin = 4;
  int iMax = 64;
  int maxStepUp = 2;        ///< I rises by at most this much per step (smoothing); it falls at once
  double learnRate = 0.15;  ///< EMA weight of a new measurement of the per-row costs
  /// The plan is scaled by this quantile of the recent steps' overruns (measured over predicted
  /// time after collision detection), so that about this share of steps fits the budget even when
  /// step costs scatter (mixed island kinds, early stops, other work on the same cores).
  double aimQuantile = 0.95;
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
  // Overruns of the last kOverrunWindow steps (adaptive mode): measured time after collision
  // detection over what the plan predicted for it.
  static constexpr int kOverrunWindow = 64;
  std::array<float, kOverrunWindow> overrun_{};
  int overrunCount_ = 0, overrunNext_ = 0;
  double plannedRestMs_ = 0.0;  // the last plan's predicted time after collision detection
  /// aimQuantile of the recorded overruns (1 before any), within [0.25, 8].
  double overrunFactor() const;
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
