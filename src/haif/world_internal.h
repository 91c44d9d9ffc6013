// What the World's stage files share (not API): the clock, the task grains used by more than one
// stage, and the member templates that run a stage's work over islands, strips and chunks.
#pragma once

#include "core/flush_denormals.h"
#include "haif/world.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace haif {

namespace world_detail {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Rows of an island whose total is below this are batched with their neighbours into one task,
/// so thousands of tiny islands do not each pay a task's overhead.
constexpr uint32_t kBatchRows = 1024;

// Task grains of the parallel loops: the fewest items a task takes, sized so each task runs for
// tens of microseconds (a TBB task costs about a microsecond to hand out).
/// Per-body passes of a few operations each (integrate velocities, the speed bound).
constexpr uint32_t kBodyGrain = 8192;
/// Per-body passes that also move the pose (rest damping, integrate positions): ~10x the work.
constexpr uint32_t kPoseGrain = 512;
/// Tight boxes: one per moving body, a hull's or compound's box costs hundreds of nanoseconds.
constexpr uint32_t kBoundsGrain = 1024;
/// Steps of its path a body in free flight has its broad-phase box reach ahead (updateBroadPhase).
constexpr int kFlightLeadSteps = 4;
/// Share of the moving bodies that must leave their fat boxes in one step for the broad phase's tree
/// to be built afresh rather than moved into body by body (World::updateBroadPhase).
constexpr float kRebuildShare = 0.25f;
/// Share of the moving tree's bodies that must query it in one step for the queries to read a
/// four-wide copy of it (BroadPhase::prepareQueries): the copy costs about as much as 1/16 of them.
constexpr float kWideQueryShare = 1.0f / 16.0f;
/// Narrow-phase pairs cost 0.1 to 10 microseconds each, very unevenly: small tasks balance them.
constexpr uint32_t kPairGrain = 64;
/// Contacts prepared in one chunk (row building, a few hundred nanoseconds each).
constexpr uint32_t kPrepareChunk = 256;
/// Contacts in one chunk of the light per-contact passes (re-aiming for relax, storing impulses).
constexpr uint32_t kContactChunk = 1024;
/// Contact heights for the solve order: a few loads each.
constexpr uint32_t kHeightGrain = 4096;
/// Islands in one task of the per-island passes (sorting, cold start): islands vary in size.
constexpr uint32_t kIslandGrain = 4;

}  // namespace world_detail

using world_detail::Clock;
using world_detail::msSince;
using world_detail::kBatchRows;
using world_detail::kBodyGrain;
using world_detail::kFlightLeadSteps;
using world_detail::kBoundsGrain;
using world_detail::kRebuildShare;
using world_detail::kWideQueryShare;
using world_detail::kContactChunk;
using world_detail::kHeightGrain;
using world_detail::kIslandGrain;
using world_detail::kPairGrain;
using world_detail::kPoseGrain;
using world_detail::kPrepareChunk;

template <class F>
void World::parallelFor(uint32_t n, uint32_t grain, F&& f) {
  if (!arena_ || n <= grain) {
    if (n > 0) f(0u, n);
    return;
  }
  // Each chunk runs in the step's floating-point mode, on whichever thread takes it.
#ifdef HAIF_TSAN
  pool_->run(n, grain, [&](uint32_t b, uint32_t e) {
    const FlushDenormals mode;
    f(b, e);
  });
#else
  arena_->execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, grain), [&](const tbb::blocked_range<uint32_t>& r) {
      const FlushDenormals mode;
      f(r.begin(), r.end());
    });
  });
#endif
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
// A phase's strips are cut into one contiguous group per thread (fewer where the phase has fewer
// strips), and a group runs its strips two at a time, pair(b1, e1, b2, e2, r1, r2) on both ranges,
// writing each one's result: the sweep interleaves them (solveIterationPair). Strips of a phase share
// no dynamic body, so the grouping changes no result. Tasks of two strips each left threads idle
// wherever their count was odd: 6 strips on 2 threads were 3 tasks, one thread running two of them
// while the other waited.
template <class F, class Pair>
SweepResult World::forEachStrip(uint32_t k, F&& f, Pair&& pair) {
  const int32_t li = layoutOf_[k];
  if (li < 0) return f(0u, islands_.islands[k].contactCount);
  const StripLayout& layout = layouts_[li];
  SweepResult* res = stripResult_.data() + size_t(li) * (kMaxStrips + 1);
  SweepResult total;
  for (uint32_t phase = 0; phase < 2; ++phase) {
    const uint32_t strips = (layout.strips + 1 - phase) / 2;  // strips 2i + phase, i < strips
    const uint32_t groups = stripGroups(strips, workerThreads_);
    parallelFor(groups, 1, [&](uint32_t begin, uint32_t end) {
      for (uint32_t g = begin; g < end; ++g) {
        const StripGroup group = stripGroup(g, groups, strips);
        uint32_t i = group.first;
        for (; i + 1 < group.last; i += 2) {
          const uint32_t s = 2 * i + phase, s2 = s + 2;
          pair(layout.start[s], layout.start[s + 1], layout.start[s2], layout.start[s2 + 1], res[s], res[s2]);
        }
        if (i < group.last) {
          const uint32_t s = 2 * i + phase;
          res[s] = f(layout.start[s], layout.start[s + 1]);
        }
      }
    });
    for (uint32_t i = 0; i < strips; ++i) total.merge(res[2 * i + phase]);
  }
  const uint32_t tail = layout.strips;
  total.merge(f(layout.start[tail], layout.start[tail + 1]));
  return total;
}

template <class F>
SweepResult World::forEachStrip(uint32_t k, F&& f) {
  return forEachStrip(k, f, [&](uint32_t b1, uint32_t e1, uint32_t b2, uint32_t e2, SweepResult& r1, SweepResult& r2) {
    r1 = f(b1, e1);
    r2 = f(b2, e2);
  });
}

template <class F>
void World::forEachLaneRange(uint32_t k, F&& f) {
  const LaneBatches lb = lanesOf(k);
  ContactConstraint* cs = constraints_.data() + islands_.islands[k].firstContact;
  forEachStrip(k, [&](uint32_t b, uint32_t e) {
    f(cs + b, size_t(e - b), lb.from(b));
    return SweepResult{};
  });
}

template <class F>
void World::forEachContactChunk(uint32_t k, uint32_t grain, F&& f) {
  const uint32_t n = islands_.islands[k].contactCount;
  if (layoutOf_[k] >= 0) parallelFor(n, grain, f);
  else f(0u, n);
}

}  // namespace haif
