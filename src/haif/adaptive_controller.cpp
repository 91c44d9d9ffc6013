#include "haif/adaptive_controller.h"

#include <algorithm>
#include <cmath>

namespace haif {

AdaptiveController::AdaptiveController(const CostModel& model, const AdaptiveSettings& s, bool useClock)
    : model_(model), s_(s), useClock_(useClock) {
  iMin = s.iMin;
  iMax = s.iMax;
}

int AdaptiveController::threadsFor(const ControlContext& ctx) const {
  // Model mode must decide the same for any thread count (docs/architecture.md, Threads), so it plans for the
  // cost model's thread count, not the run's.
  return useClock_ ? ctx.threads : model_.modelThreads;
}

double AdaptiveController::criticalRows(const ControlContext& ctx) const {
  return CostModel::criticalRows(ctx.totalRows, ctx.largestRows, threadsFor(ctx), model_.parallelEfficiency);
}

double AdaptiveController::iterationMs(const ControlContext& ctx) const {
  return model_.msPerRowIteration * criticalRows(ctx);
}

int AdaptiveController::choose(const ControlContext& ctx) {
  if (ctx.budgetMs <= 0.0 || ctx.totalRows == 0) {
    previous_ = iMax;
    return iMax;  // no budget, or nothing to solve: precision costs nothing
  }
  const double crit = criticalRows(ctx);
  const double elapsed = useClock_ ? ctx.elapsedMs : model_.collisionMs(ctx.bodies, ctx.contactPoints);
  const double post = useClock_ && postMs_ >= 0.0 ? postMs_ : model_.msPerBody * 0.5 * ctx.bodies;
  const double prepare = model_.msPerRowPrepare * crit;
  // What is left after collision detection, shrunk by how much the rest of recent steps overran
  // their plans (at the aimed quantile), then what the solve costs besides its sweeps.
  const double remaining = (ctx.budgetMs - elapsed) / overrunFactor() - post - prepare;
  const double tIter = model_.msPerRowIteration * crit;
  int I = tIter > 0.0 ? static_cast<int>(std::floor(s_.alpha * std::max(0.0, remaining) / tIter)) : iMax;
  // Smooth upward changes only: a step that must do less does so at once, to keep the deadline.
  if (previous_ > 0) I = std::min(I, previous_ + s_.maxStepUp);
  I = std::clamp(I, iMin, iMax);
  previous_ = I;
  plannedRestMs_ = post + prepare + double(I) * tIter;
  return I;
}

double AdaptiveController::overrunFactor() const {
  if (overrunCount_ == 0) return 1.0;
  std::array<float, kOverrunWindow> sorted = overrun_;
  const int k = std::min(overrunCount_ - 1, static_cast<int>(s_.aimQuantile * double(overrunCount_)));
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.begin() + overrunCount_);
  return std::clamp(double(sorted[size_t(k)]), 0.25, 8.0);
}

void AdaptiveController::observe(const ControlContext& ctx, const SolveObservation& obs) {
  if (!useClock_) return;  // model mode never learns from the clock: it must stay deterministic
  // The first step pays one-time costs (arrays grow, pages fault in, every pair is new): it says
  // little about the next ones. After it, a plain mean over the first observations, then the moving
  // average: measured steps replace the (uncalibrated) model at once instead of over ~10 steps.
  if (ctx.step == 0) return;
  ++observed_;
  if (plannedRestMs_ > 0.0 && ctx.budgetMs > 0.0 && obs.totalMs > 0.0) {
    overrun_[size_t(overrunNext_)] = float(std::max(0.0, obs.totalMs - ctx.elapsedMs) / plannedRestMs_);
    overrunNext_ = (overrunNext_ + 1) % kOverrunWindow;
    overrunCount_ = std::min(overrunCount_ + 1, kOverrunWindow);
  }
  const double lr = std::max(s_.learnRate, 1.0 / double(observed_));
  postMs_ = postMs_ < 0.0 ? obs.integrateMs : (1.0 - lr) * postMs_ + lr * obs.integrateMs;
  const double crit = criticalRows(ctx);
  if (crit <= 0.0 || obs.solveMs <= 0.0) return;
  // Sweeps along the critical path: the row-weighted mean when the path is the threads' share of
  // all rows (islands stop early on their own), the largest island's count when that island is it.
  const double share = CostModel::criticalRows(ctx.totalRows, 0, threadsFor(ctx), model_.parallelEfficiency);
  double sweeps = double(obs.iterations);
  if (share >= double(ctx.largestRows) && obs.rowIterations > 0 && ctx.totalRows > 0)
    sweeps = double(obs.rowIterations) / double(ctx.totalRows);
  else if (obs.criticalRowIterations > 0 && ctx.largestRows > 0)
    sweeps = double(obs.criticalRowIterations) / double(ctx.largestRows);
  sweeps = std::max(1.0, sweeps);
  // The part of the solve's wall time that went to sweeps: the measured thread-time ratio, or,
  // when the world did not measure it, the model's own.
  const double measured = obs.fixedThreadMs + obs.sweepThreadMs;
  const double modelSweeps = sweeps * model_.msPerRowIteration;
  const double sweepShare = measured > 0.0 ? obs.sweepThreadMs / measured
                                           : modelSweeps / (model_.msPerRowPrepare + modelSweeps);
  const double perRowIteration = obs.solveMs * sweepShare / (crit * sweeps);
  const double perRowPrepare = obs.solveMs * (1.0 - sweepShare) / crit;
  model_.msPerRowIteration = (1.0 - lr) * model_.msPerRowIteration + lr * perRowIteration;
  model_.msPerRowPrepare = (1.0 - lr) * model_.msPerRowPrepare + lr * perRowPrepare;
}

ReplayController::ReplayController(std::vector<int> counts) : counts_(std::move(counts)) {
  iMin = 1;
  iMax = 1 << 20;
}

int ReplayController::choose(const ControlContext& ctx) {
  if (counts_.empty()) return 1;
  return counts_[std::min<size_t>(ctx.step, counts_.size() - 1)];
}

}  // namespace haif
