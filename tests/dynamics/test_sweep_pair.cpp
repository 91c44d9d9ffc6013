// solveIterationPair sweeps two ranges on disjoint bodies a constraint of each in turn, for the
// processor's sake only: velocities, impulses and each range's SweepResult must be the bits two
// solveIteration calls give, whichever branches the constraints take.
#include "dynamics/contact_solver.h"
#include "eight_boxes.h"

#include <gtest/gtest.h>

#include <cstring>

namespace haif {
namespace {

using test::EightBoxes;

void expectSameBits(const SweepResult& a, const SweepResult& b, const char* what) {
  EXPECT_EQ(std::memcmp(&a.residual, &b.residual, sizeof a.residual), 0) << what << " residual";
  EXPECT_EQ(std::memcmp(&a.change, &b.change, sizeof a.change), 0) << what << " change";
}

TEST(SweepPair, TwoRangesInTurnGiveTheBitsOfTwoSweeps) {
  // Ranges of unequal length (3 and 5 boxes), so the longer one's rest runs alone.
  constexpr int kFirst = 3, kAll = EightBoxes::kBoxes;
  EightBoxes apart, paired;
  ContactConstraint ca[kAll], cp[kAll];
  apart.prepare(ca);
  paired.prepare(cp);
  warmStart(apart.bodies, ca, kAll);
  warmStart(paired.bodies, cp, kAll);
  // Main sweeps (one restarting the momentum direction, one not measuring), then relax sweeps.
  struct Sweep {
    bool useBias, restart, measure;
  };
  const Sweep sweeps[] = {{true, false, true}, {true, true, true}, {true, false, false}, {false, false, true}};
  for (const Sweep& s : sweeps) {
    const SweepResult a1 = solveIteration(apart.bodies, ca, kFirst, 1.0f, s.useBias, s.restart, s.measure);
    const SweepResult a2 =
        solveIteration(apart.bodies, ca + kFirst, kAll - kFirst, 1.0f, s.useBias, s.restart, s.measure);
    SweepResult p1, p2;
    solveIterationPair(VelocityView(paired.bodies), cp, kFirst, cp + kFirst, kAll - kFirst, 1.0f, s.useBias,
                       s.restart, s.measure, false, p1, p2);
    expectSameBits(p1, a1, "first range");
    expectSameBits(p2, a2, "second range");
  }
  const EightBoxes start;
  int changed = 0;  // the rows acted: there was something to compare
  for (uint32_t b = 0; b < start.bodies.size(); ++b) changed += apart.bodies.v[b] != start.bodies.v[b] ? 1 : 0;
  EXPECT_GE(changed, EightBoxes::kBoxes - 1);
  for (uint32_t b = 0; b < apart.bodies.size(); ++b) {
    EXPECT_EQ(paired.bodies.v[b], apart.bodies.v[b]) << "body " << b;
    EXPECT_EQ(paired.bodies.w[b], apart.bodies.w[b]) << "body " << b;
  }
  for (int k = 0; k < kAll; ++k) {
    EXPECT_EQ(std::memcmp(cp[k].normalImpulse, ca[k].normalImpulse, sizeof ca[k].normalImpulse), 0) << k;
    EXPECT_EQ(std::memcmp(cp[k].frictionImpulse, ca[k].frictionImpulse, sizeof ca[k].frictionImpulse), 0) << k;
    EXPECT_EQ(std::memcmp(cp[k].direction, ca[k].direction, sizeof ca[k].direction), 0) << k;
  }
}

}  // namespace
}  // namespace haif
