// The cold start's division of a resting body's load among its support points (haif/support_balance.h):
// it balances force and moments where it can, never pulls, and gives the lever rule.
#include "haif/support_balance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace haif {
namespace {

struct Balance {
  double force = 0.0, mx = 0.0, mz = 0.0, least = 1e30;
};

Balance sums(const std::vector<SupportPoint>& p) {
  Balance b;
  for (const SupportPoint& s : p) {
    b.force += s.load;
    b.mx += double(s.load) * s.x;
    b.mz += double(s.load) * s.z;
    b.least = std::fmin(b.least, double(s.load));
  }
  return b;
}

TEST(SupportBalance, CentredLoadOnASquareSharesEqually) {
  std::vector<SupportPoint> p = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  ASSERT_TRUE(balanceSupportLoad(p.data(), 4, 2.0f, 0.0f, 0.0f));
  for (const SupportPoint& s : p) EXPECT_NEAR(s.load, 0.5f, 1e-6f);
}

TEST(SupportBalance, TwoSupportsFollowTheLeverRule) {
  // Supports 1 m and 3 m from the load's line of action carry 3/4 and 1/4 of it.
  std::vector<SupportPoint> p = {{-1, 0}, {3, 0}};
  ASSERT_TRUE(balanceSupportLoad(p.data(), 2, 4.0f, 0.0f, 0.0f));
  EXPECT_NEAR(p[0].load, 3.0f, 1e-5f);
  EXPECT_NEAR(p[1].load, 1.0f, 1e-5f);
}

TEST(SupportBalance, ALoadFromAboveActsWhereItRests) {
  // A body's own weight 1 at its centre and 2 resting on it at x = 0.5 (moment 1): the load's centre
  // is at x = 1/3, so supports at x = ±1 carry 1 and 2.
  std::vector<SupportPoint> p = {{-1, 0}, {1, 0}};
  ASSERT_TRUE(balanceSupportLoad(p.data(), 2, 3.0f, 1.0f, 0.0f));
  EXPECT_NEAR(p[0].load, 1.0f, 1e-5f);
  EXPECT_NEAR(p[1].load, 2.0f, 1e-5f);
}

TEST(SupportBalance, ALoadOutsideItsSupportsRestsOnTheNearestWithoutPulling) {
  // The load's centre at x = 2, outside supports at ±1: no division balances; the far one would
  // pull, so it is let go and the near one carries everything (the body will tip, as it should).
  std::vector<SupportPoint> p = {{-1, 0}, {1, 0}};
  ASSERT_TRUE(balanceSupportLoad(p.data(), 2, 1.0f, 2.0f, 0.0f));
  EXPECT_EQ(p[0].load, 0.0f);
  EXPECT_NEAR(p[1].load, 1.0f, 1e-6f);
}

TEST(SupportBalance, PointsInALineTakeNoMomentAcrossIt) {
  // An edge along x: the moment about it (mz) cannot be held; the division along it still balances.
  std::vector<SupportPoint> p = {{-1, 0}, {0, 0}, {2, 0}};
  ASSERT_TRUE(balanceSupportLoad(p.data(), 3, 3.0f, 0.6f, 0.3f));
  const Balance b = sums(p);
  EXPECT_NEAR(b.force, 3.0, 1e-5);
  EXPECT_NEAR(b.mx, 0.6, 1e-5);
  EXPECT_GE(b.least, 0.0);
}

TEST(SupportBalance, NothingToDivideIsNoDivision) {
  std::vector<SupportPoint> p = {{0, 0}};
  EXPECT_FALSE(balanceSupportLoad(p.data(), 0, 1.0f, 0.0f, 0.0f));
  EXPECT_FALSE(balanceSupportLoad(p.data(), 1, 0.0f, 0.0f, 0.0f));
}

TEST(SupportBalance, AnyLoadInsideItsSupportsIsBalancedWithoutPulling) {
  // 2000 random sets of 3-16 points in a 10 cm square (a block's footprint), the load's centre a
  // random convex combination of them, so a balance without pulling exists: the one found holds
  // the force to 1e-5 of the load and its centre to 1 µm, and no point pulls (worst of 200,000: 0.04 µm).
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> at(-0.05f, 0.05f), weight(0.0f, 1.0f);
  std::uniform_int_distribution<int> size(3, 16);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<SupportPoint> p(size_t(size(rng)));
    double wsum = 0.0, cx = 0.0, cz = 0.0;
    for (SupportPoint& s : p) {
      s.x = at(rng);
      s.z = at(rng);
      const double w = std::pow(weight(rng), 4.0);  // often near one point or edge
      wsum += w;
      cx += w * s.x;
      cz += w * s.z;
    }
    const float load = 0.3f;
    const float mx = float(load * cx / wsum), mz = float(load * cz / wsum);
    ASSERT_TRUE(balanceSupportLoad(p.data(), int(p.size()), load, mx, mz));
    const Balance b = sums(p);
    EXPECT_NEAR(b.force, load, 1e-5 * load) << "trial " << trial;
    EXPECT_NEAR(b.mx, mx, 1e-6 * load) << "trial " << trial;
    EXPECT_NEAR(b.mz, mz, 1e-6 * load) << "trial " << trial;
    EXPECT_GE(b.least, 0.0) << "trial " << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 2000);
}

}  // namespace
}  // namespace haif
