// Repeated bench runs of one set-up combine to the run in the middle: its ms/step, its errors and
// its hash, with the spread of the runs kept beside it.
#include "tools/bench_sweep.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

BenchResult run(double ms, double p95, double cpu, double drop, uint64_t hash) {
  BenchResult r;
  r.msMedian = r.msMin = r.msMax = ms;
  r.msP95 = p95;
  r.cpuMsMedian = cpu;
  r.meanDrop = drop;
  r.stateHash = hash;
  return r;
}

TEST(BenchRounds, TheMiddleRunSpeaksForTheSetUp) {
  // Unordered, one slow outlier: the median run is the 12 ms one, whatever the order.
  const BenchResult r = combineRounds({run(30.0, 40.0, 29.0, 0.3, 3), run(12.0, 15.0, 11.0, 0.1, 1),
                                       run(11.0, 30.0, 10.5, 0.2, 2)});
  EXPECT_EQ(r.rounds, 3);
  EXPECT_EQ(r.msMedian, 12.0);
  EXPECT_EQ(r.msMin, 11.0);
  EXPECT_EQ(r.msMax, 30.0);
  EXPECT_EQ(r.msP95, 30.0);        // the median of 40, 15 and 30: taken on its own
  EXPECT_EQ(r.cpuMsMedian, 11.0);  // the median of 29, 11 and 10.5
  EXPECT_EQ(r.meanDrop, 0.1);      // errors and hash of the 12 ms run
  EXPECT_EQ(r.stateHash, 1u);
}

TEST(BenchRounds, EvenCountsTakeTheLowerMiddleAndOneRunIsItself) {
  const BenchResult two = combineRounds({run(20.0, 25.0, 19.0, 0.0, 7), run(10.0, 12.0, 9.0, 0.0, 8)});
  EXPECT_EQ(two.msMedian, 10.0);
  EXPECT_EQ(two.stateHash, 8u);
  EXPECT_EQ(two.msMax, 20.0);
  const BenchResult one = combineRounds({run(5.0, 6.0, 4.0, 0.5, 9)});
  EXPECT_EQ(one.rounds, 1);
  EXPECT_EQ(one.msMedian, 5.0);
  EXPECT_EQ(one.msMin, 5.0);
  EXPECT_EQ(one.msMax, 5.0);
  EXPECT_EQ(one.meanDrop, 0.5);
}

}  // namespace
}  // namespace haif
