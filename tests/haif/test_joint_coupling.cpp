// Contacts whose push a joint carries on to a heavier body: sweeps
// pass it on a sliver per sweep (contacts, then the joint tree), so light wheels under a heavy car
// sank into the ground and sprang out, and a chain pulled its links into the ball hanging from it.
// Such islands have their contacts' normal rows solved through the joint tree
// (dynamics/joint_coupling.h).
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace haif {
namespace {

using test::addBox;
using test::addGround;
using test::addSphere;
using test::maxContactDepth;

WorldSettings settingsAt(int iterations) {
  WorldSettings ws;
  ws.iterations = iterations;
  return ws;
}

void hinge(World& w, uint32_t a, uint32_t b, const Vec3& anchor, const Vec3& axis) {
  const Transform world{};
  const Transform& xfA = a == kWorldBody ? world : w.bodies().xf[a];
  w.addJoint(jointAtWorld(JointType::Hinge, a, b, xfA, w.bodies().xf[b], anchor, axis, anchor));
}

struct Car {
  uint32_t chassis;
  uint32_t wheels[4];
};

// A 2000 kg body (2.4 x 0.4 x 1.2 m) on four balls of 5 kg (radius 0.4 m) hinged to it about z,
// rolling along x at `speed`, its centre line at z.
Car addCar(World& w, float speed, float z0 = 0.0f) {
  Car car;
  car.chassis = addBox(w, Vec3(0.0f, 0.9f, z0), Vec3(1.2f, 0.2f, 0.6f), 2000.0f);
  w.bodies().v[car.chassis] = Vec3(speed, 0.0f, 0.0f);
  int i = 0;
  for (const float x : {-0.9f, 0.9f})
    for (const float z : {z0 - 0.85f, z0 + 0.85f}) {
      const uint32_t wheel = addSphere(w, Vec3(x, 0.4f, z), 0.4f, 5.0f);
      w.bodies().v[wheel] = Vec3(speed, 0.0f, 0.0f);
      w.bodies().w[wheel] = Vec3(0.0f, 0.0f, -speed / 0.4f);
      hinge(w, car.chassis, wheel, Vec3(x, 0.4f, z), Vec3::UnitZ());
      car.wheels[i++] = wheel;
    }
  return car;
}

TEST(JointCoupling, LightWheelsUnderAHeavyCarStayOnTheGround) {
  // Swept, the wheels sank 13-17 cm into the ground at 4 iterations and 6 cm at 10, and sprang out
  // again, every half second.
  for (const int iterations : {4, 10}) {
    World w(settingsAt(iterations));
    addGround(w);
    const Car car = addCar(w, 3.0f);
    float deepest = 0.0f, lowest = 1.0f;
    for (int s = 0; s < 600; ++s) {
      w.step();
      deepest = std::max(deepest, maxContactDepth(w));
      for (const uint32_t wheel : car.wheels) lowest = std::min(lowest, w.bodies().xf[wheel].p.y());
    }
    const std::string what = std::to_string(iterations) + " iterations";
    EXPECT_LT(deepest, 0.01f) << what;
    EXPECT_GT(lowest, 0.39f) << what;
    EXPECT_NEAR(w.bodies().xf[car.chassis].p.y(), 0.9f, 0.01f) << what;
    EXPECT_NEAR(w.bodies().v[car.chassis].x(), 3.0f, 0.05f) << what;  // rolls on: no energy lost to bouncing
  }
}

TEST(JointCoupling, ALightChainsLinksAreNotPulledIntoTheHeavyBallAtItsEnd) {
  // Twenty capsule links of 0.5 kg on ball joints from a fixed point, a 100 kg ball at the end, let
  // go level: swinging down, the last links wrap onto the ball, and swept, the chain pulled one
  // 19.5 cm into it at 4 iterations (7.3 cm at 10).
  for (const int iterations : {4, 10}) {
    World w(settingsAt(iterations));
    addGround(w);
    const Transform world{};
    uint32_t prev = kWorldBody;
    for (int i = 0; i < 20; ++i) {
      BodyDef d;
      d.shape = Shape::capsule(0.05f, 0.1f);
      d.xf.p = Vec3(0.3f * float(i) + 0.15f, 6.0f, 0.0f);
      d.xf.q = Quat(Eigen::AngleAxisf(float(M_PI) / 2.0f, Vec3::UnitZ()));
      d.mass = 0.5f;
      const uint32_t link = w.addBody(d);
      const Vec3 anchor(0.3f * float(i), 6.0f, 0.0f);
      w.addJoint(jointAtWorld(JointType::Ball, prev, link, prev == kWorldBody ? world : w.bodies().xf[prev],
                              w.bodies().xf[link], anchor, Vec3::UnitX(), anchor));
      prev = link;
    }
    const uint32_t ball = addSphere(w, Vec3(6.3f, 6.0f, 0.0f), 0.3f, 100.0f);
    w.addJoint(jointAtWorld(JointType::Ball, prev, ball, w.bodies().xf[prev], w.bodies().xf[ball],
                            Vec3(6.0f, 6.0f, 0.0f), Vec3::UnitX(), Vec3(6.0f, 6.0f, 0.0f)));
    float deepest = 0.0f;
    for (int s = 0; s < 300; ++s) {
      w.step();
      deepest = std::max(deepest, maxContactDepth(w));
    }
    EXPECT_LT(deepest, 0.04f) << iterations << " iterations";
  }
}

TEST(JointCoupling, TheCarsStateDoesNotDependOnTheThreadCount) {
  test::expectSameStateForThreadCounts([](int threads) {
    WorldSettings ws = settingsAt(4);
    ws.threads = threads;
    World w(ws);
    addGround(w);
    addCar(w, 3.0f);
    addCar(w, -2.0f, 4.0f);  // a second island beside it
    for (int s = 0; s < 120; ++s) w.step();
    return w.stateHash();
  });
}

}  // namespace
}  // namespace haif
