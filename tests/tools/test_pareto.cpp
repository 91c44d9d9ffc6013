// The Pareto front keeps exactly the points no other point beats on both cost and error.
#include "tools/pareto.h"

#include <gtest/gtest.h>

#include <cmath>

namespace haif {
namespace {

TEST(Pareto, KeepsOnlyUndominatedPointsCheapestFirst) {
  //                          0    1    2    3    4    5
  const std::vector<double> x{4.0, 1.0, 2.0, 3.0, 2.5, 8.0};
  const std::vector<double> y{0.5, 9.0, 3.0, 4.0, 1.0, 0.1};
  // 3 is beaten by 4 (cheaper and better); 0 by nothing; 5 is the most exact.
  EXPECT_EQ(paretoFront(x, y), (std::vector<size_t>{1, 2, 4, 0, 5}));
}

TEST(Pareto, TiesAndEqualPoints) {
  // Same cost: only the smaller error; same error: only the cheaper; identical: the first.
  EXPECT_EQ(paretoFront({1.0, 1.0, 2.0, 2.0}, {5.0, 3.0, 3.0, 1.0}), (std::vector<size_t>{1, 3}));
  EXPECT_EQ(paretoFront({1.0, 1.0}, {2.0, 2.0}), (std::vector<size_t>{0}));
}

TEST(Pareto, SkipsPointsWithoutAValue) {
  // A set-up whose error cannot be measured (NaN) is not on the front, and hides nothing.
  EXPECT_EQ(paretoFront({1.0, 2.0, 3.0}, {NAN, 2.0, 1.0}), (std::vector<size_t>{1, 2}));
  EXPECT_TRUE(paretoFront({}, {}).empty());
  EXPECT_TRUE(paretoFront({INFINITY}, {1.0}).empty());
}

}  // namespace
}  // namespace haif
