// Fast small bodies against a thin static wall: the speculative contact margin must reach as far as the
// bodies move in one step, or they pass through the wall between two steps (no continuous collision).
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

// A 5 cm thick wall (x in [-0.025, 0.025]) and one body 3 m in front of it at `speed` towards it.
// Returns the largest x its centre reached (it must stay in front of the wall).
float farthestReach(const Shape& shape, float speed) {
  WorldSettings s;
  s.gravity = Vec3::Zero();
  s.iterations = 10;
  s.sleeping = false;
  World w(s);
  BodyDef wall;
  wall.kind = BodyKind::Static;
  wall.shape = Shape::box(Vec3(0.025f, 2.0f, 2.0f));
  w.addBody(wall);
  BodyDef d;
  d.shape = shape;
  d.mass = 0.2f;
  d.xf.p = Vec3(-3.0f, 0.3f, -0.2f);
  d.linearVelocity = Vec3(speed, 0.0f, 0.0f);
  const uint32_t b = w.addBody(d);
  float reach = -1e30f;
  for (int step = 0; step < 60; ++step) {
    w.step();
    reach = std::max(reach, w.bodies().xf[b].p.x());
  }
  return reach;
}

TEST(FastBodies, SmallSphereDoesNotTunnelThroughThinWall) {
  for (float speed : {55.0f, 100.0f, 300.0f})
    EXPECT_LT(farthestReach(Shape::sphere(0.05f), speed), 0.0f) << "at " << speed << " m/s";
}

TEST(FastBodies, SmallBoxDoesNotTunnelThroughThinWall) {
  for (float speed : {60.0f, 100.0f, 300.0f})
    EXPECT_LT(farthestReach(Shape::box(Vec3::Constant(0.05f)), speed), 0.0f) << "at " << speed << " m/s";
}

}  // namespace
}  // namespace haif::test
