// Bodies in free flight have broad-phase boxes that lead along their path; bodies touching
// something keep boxes tight around them (World::updateBroadPhase).
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

using test::addBox;
using test::addGround;

TEST(FlightBoxes, AFallingBodysBoxLeadsAlongItsPathAndARestingOnesStaysTight) {
  World w;
  addGround(w);
  const uint32_t resting = addBox(w, Vec3(3.0f, 0.5f, 0.0f));
  const uint32_t falling = addBox(w, Vec3(-3.0f, 60.0f, 0.0f));
  int moves = 0;
  Aabb last = w.broadPhase().fatAabb(falling);
  for (int s = 0; s < 90; ++s) {
    w.step();
    // The falling box moves 0.08-0.25 m a step here, more than the kept margin: with a box only
    // one step ahead it would be re-inserted every step; four steps ahead, every four or five.
    const Aabb& fat = w.broadPhase().fatAabb(falling);
    if (s >= 30) {
      moves += fat.lo.y() != last.lo.y();
      // Still around the body with the kept margin below it (no pair can be missed).
      EXPECT_GE(w.bodies().xf[falling].p.y() - 0.5f - fat.lo.y(), w.broadPhase().keptMargin - 1e-4f) << "step " << s;
    }
    last = fat;
    // The resting box touches the ground: its fat box is its box and the margin, nothing ahead.
    const Aabb& still = w.broadPhase().fatAabb(resting);
    const Vec3 p = w.bodies().xf[resting].p;
    EXPECT_LT((still.hi - (p + Vec3::Constant(0.5f))).maxCoeff(), 0.2f) << "step " << s;
    EXPECT_LT(((p - Vec3::Constant(0.5f)) - still.lo).maxCoeff(), 0.2f) << "step " << s;
  }
  EXPECT_LE(moves, 60 / 4 + 1);
  EXPECT_GE(moves, 60 / 6);
  EXPECT_LT(w.bodies().xf[falling].p.y(), 50.0f);  // it did fall (11 m), and is still in flight
}

}  // namespace
}  // namespace haif
