// The wide sweep (wide_contact_solver.h) does for 8 manifolds at once what the scalar sweep does for
// each: same impulses and velocities to float rounding, through every branch of a sweep (exact
// block, passes after a pulling block, friction circle, twist limit, bounce in a relax sweep,
// empty manifold), and the momentum step likewise.
#include "dynamics/wide_contact_solver.h"
#include "eight_boxes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace haif {
namespace {

using test::EightBoxes;
static_assert(EightBoxes::kBoxes == kLanes, "a box a lane");

void expectNear(const Vec3& a, const Vec3& b, const char* what, int body) {
  const float tol = 2e-5f * std::max(1.0f, b.norm());
  EXPECT_LT((a - b).norm(), tol) << what << " of body " << body << ": " << a.transpose() << " vs "
                                 << b.transpose();
}

TEST(WideSolver, SweepsAndMomentumMatchTheScalarSolver) {
  EightBoxes scalar, wide;
  ContactConstraint cs[kLanes], cw[kLanes];
  scalar.prepare(cs);
  wide.prepare(cw);
  WideContactBatch w;
  packWide(cw, kLanes, w);

  bool sawPasses = false;
  // Three main sweeps with a momentum step after the second and third, then two relax sweeps.
  double lastChange = 0.0;
  for (int sweep = 0; sweep < 5; ++sweep) {
    const bool useBias = sweep < 3;
    const SweepResult rs = solveIteration(scalar.bodies, cs, kLanes, 1.0f, useBias);
    const SweepResult rw = solveWide(wide.bodies, w, 1.0f, useBias);
    EXPECT_NEAR(rw.residual, rs.residual, 2e-5f * std::max(1.0f, rs.residual)) << "sweep " << sweep;
    EXPECT_NEAR(rw.change, rs.change, 1e-4 * std::max(1.0, rs.change)) << "sweep " << sweep;
    for (int l = 0; l < kLanes; ++l) {  // a block that would pull: some points let go, others push
      float lo = 1e9f, hi = 0.0f;
      for (int i = 0; i < cs[l].count; ++i) {
        lo = std::min(lo, cs[l].normalImpulse[i]);
        hi = std::max(hi, cs[l].normalImpulse[i]);
      }
      sawPasses |= cs[l].count == 4 && lo == 0.0f && hi > 0.0f;
    }
    if (sweep == 0) {
      startDirection(cs, kLanes);
      startDirectionWide(w);
    } else if (useBias) {
      const float beta = float(rs.change / lastChange);
      accelerate(scalar.bodies, cs, kLanes, beta);
      accelerateWide(wide.bodies, w, beta);
    }
    lastChange = rs.change;
    for (uint32_t b = 1; b < scalar.bodies.size(); ++b) {
      expectNear(wide.bodies.v[b], scalar.bodies.v[b], "v", int(b));
      expectNear(wide.bodies.w[b], scalar.bodies.w[b], "w", int(b));
    }
  }
  unpackWideImpulses(w, cw);
  bool sawClamp = false, sawBounce = false;
  for (int l = 0; l < kLanes; ++l) {
    for (int i = 0; i < cs[l].count; ++i)
      EXPECT_NEAR(cw[l].normalImpulse[i], cs[l].normalImpulse[i], 2e-5f) << "lane " << l << " point " << i;
    EXPECT_NEAR(cw[l].frictionImpulse[0], cs[l].frictionImpulse[0], 2e-5f) << "lane " << l;
    EXPECT_NEAR(cw[l].frictionImpulse[1], cs[l].frictionImpulse[1], 2e-5f) << "lane " << l;
    EXPECT_NEAR(cw[l].frictionImpulse[2], cs[l].frictionImpulse[2], 2e-5f) << "lane " << l;
    float total = 0.0f;
    for (int i = 0; i < cs[l].count; ++i) total += cs[l].normalImpulse[i];
    const float t = std::hypot(cs[l].frictionImpulse[0], cs[l].frictionImpulse[1]);
    sawClamp |= total > 0.0f && std::fabs(t - cs[l].friction * total) < 1e-4f * total;
    sawBounce |= cs[l].restitutionBias[0] < 0.0f;
  }
  // The cases do reach the branches they are meant to.
  EXPECT_TRUE(sawPasses);
  EXPECT_TRUE(sawClamp);
  EXPECT_TRUE(sawBounce);
}

TEST(WideSolver, PartialBatchLeavesUnusedLanesAndEmptyManifoldsAlone) {
  EightBoxes scalar, wide;
  scalar.contacts[2].manifold.count = 0;  // separated this step: skipped by a sweep
  wide.contacts[2].manifold.count = 0;
  ContactConstraint cs[kLanes], cw[kLanes];
  constexpr int lanes = 5;
  scalar.prepare(cs, lanes, SolverParams{});  // warm started
  wide.prepare(cw, lanes, SolverParams{});
  WideContactBatch w;
  packWide(cw, lanes, w);
  solveIteration(scalar.bodies, cs, lanes, 1.0f, true);
  solveWide(wide.bodies, w, 1.0f, true);
  for (uint32_t b = 1; b < scalar.bodies.size(); ++b) {
    expectNear(wide.bodies.v[b], scalar.bodies.v[b], "v", int(b));
    expectNear(wide.bodies.w[b], scalar.bodies.w[b], "w", int(b));
  }
  // Bodies of the empty manifold and of lanes past the batch keep their velocities exactly.
  for (const int l : {2, 5, 6, 7}) {
    const uint32_t b = uint32_t(l) + 1;
    EXPECT_EQ(wide.bodies.v[b], EightBoxes().bodies.v[b]) << "body " << b;
    EXPECT_EQ(wide.bodies.w[b], EightBoxes().bodies.w[b]) << "body " << b;
  }
  EXPECT_EQ(wide.bodies.v[0], Vec3::Zero());  // the static ground is never written
}

// The scalar sweep can restart the momentum direction itself (solveIteration's restartDirection),
// in place of a startDirection pass before it: the same numbers, bit for bit, on every branch above.
TEST(ScalarSolver, RestartInTheSweepEqualsAStartDirectionPass) {
  EightBoxes passScene, foldScene;
  ContactConstraint pass[kLanes], fold[kLanes];
  passScene.prepare(pass);
  foldScene.prepare(fold);
  // Sweep, restart, sweep, momentum step, sweep: as World runs the main sweeps.
  const SweepResult p1 = solveIteration(passScene.bodies, pass, kLanes, 1.0f, true);
  startDirection(pass, kLanes);
  const SweepResult p2 = solveIteration(passScene.bodies, pass, kLanes, 1.0f, true);
  const SweepResult f1 = solveIteration(foldScene.bodies, fold, kLanes, 1.0f, true);
  const SweepResult f2 = solveIteration(foldScene.bodies, fold, kLanes, 1.0f, true, /*restartDirection=*/true);
  EXPECT_EQ(p1.change, f1.change);
  EXPECT_EQ(p2.change, f2.change);
  bool anyDirection = false;
  for (int l = 0; l < kLanes; ++l)
    for (int r = 0; r < ContactConstraint::kRows; ++r) {
      EXPECT_EQ(fold[l].direction[r], pass[l].direction[r]) << "lane " << l << " row " << r;
      anyDirection |= fold[l].direction[r] != 0.0f;
    }
  EXPECT_TRUE(anyDirection);  // the first sweep changed impulses: the restart has something to carry
  const float beta = float(p2.change / p1.change);
  accelerate(passScene.bodies, pass, kLanes, beta);
  accelerate(foldScene.bodies, fold, kLanes, beta);
  solveIteration(passScene.bodies, pass, kLanes, 1.0f, true);
  solveIteration(foldScene.bodies, fold, kLanes, 1.0f, true);
  for (uint32_t b = 1; b < passScene.bodies.size(); ++b) {
    EXPECT_EQ(foldScene.bodies.v[b], passScene.bodies.v[b]) << "body " << b;
    EXPECT_EQ(foldScene.bodies.w[b], passScene.bodies.w[b]) << "body " << b;
  }
  for (int l = 0; l < kLanes; ++l)
    for (int i = 0; i < pass[l].count; ++i) EXPECT_EQ(fold[l].normalImpulse[i], pass[l].normalImpulse[i]);
}

}  // namespace
}  // namespace haif
