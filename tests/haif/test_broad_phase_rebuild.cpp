// The broad phase builds its tree afresh, the root's two halves on two workers, when many bodies
// leave their fat boxes in one step (World::updateBroadPhase): the state must not depend on the
// thread count, and ThreadSanitizer runs this test (.ci/tsan).
#include "haif/world.h"
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

using test::addStaticBox;

// 500 boxes, capsules and balls thrown about at 4-6 m/s without gravity in a closed 6 m room: most
// move more than the broad phase's kept margin every step.
uint64_t churnAtThreads(int threads, int& rebuilds) {
  World w;
  w.setThreads(threads);
  w.settings().gravity = Vec3::Zero();
  for (int side = -1; side <= 1; side += 2) {
    addStaticBox(w, Vec3(3.5f * float(side), 0, 0), Vec3(0.5f, 4, 4));
    addStaticBox(w, Vec3(0, 3.5f * float(side), 0), Vec3(4, 0.5f, 4));
    addStaticBox(w, Vec3(0, 0, 3.5f * float(side)), Vec3(4, 4, 0.5f));
  }
  for (int i = 0; i < 500; ++i) {
    BodyDef d;
    const int kind = i % 3;
    d.shape = kind == 0 ? Shape::box(Vec3(0.2f, 0.15f, 0.1f)) : kind == 1 ? Shape::capsule(0.1f, 0.2f) : Shape::sphere(0.18f);
    d.xf.p = Vec3(-2.4f + 0.6f * float(i % 9), -2.4f + 0.6f * float(i / 81), -2.4f + 0.6f * float((i / 9) % 9));
    const float speed = 4.0f + 0.5f * float(i % 5);
    d.linearVelocity = speed * Vec3(float(i % 7) - 3.0f, float(i % 5) - 2.0f, float(i % 3) - 1.0f).normalized();
    d.angularVelocity = Vec3(float(i % 4) - 1.5f, float(i % 3) - 1.0f, float(i % 5) - 2.0f);
    w.addBody(d);
  }
  rebuilds = 0;
  for (int step = 0; step < 120; ++step) {
    w.step();
    rebuilds += w.lastStats().treeRebuilt ? 1 : 0;
  }
  return w.stateHash();
}

TEST(BroadPhaseRebuild, AChurningRoomHasOneStateAtAnyThreadCount) {
  int one = 0, two = 0, three = 0;
  const uint64_t hash = churnAtThreads(1, one);
  EXPECT_EQ(churnAtThreads(2, two), hash);
  EXPECT_EQ(churnAtThreads(3, three), hash);
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, three);
  EXPECT_GE(one, 24) << "the tree should be rebuilt while the bodies fly (36 of the 120 steps)";
}

}  // namespace
}  // namespace haif
