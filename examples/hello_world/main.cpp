// Hello world: a ground, a box dropped from 2 m and a ball rolled along it, stepped through the
// public API (haif/world.h) for two seconds and printed.
#include "haif/world.h"

#include <cstdio>

int main() {
  haif::WorldSettings settings;  // 60 Hz, gravity -9.81 m/s^2 along y, 10 iterations
  haif::World world(settings);

  haif::BodyDef ground;
  ground.kind = haif::BodyKind::Static;
  ground.shape = haif::Shape::box(haif::Vec3(20.0f, 0.5f, 20.0f));
  ground.xf.p = haif::Vec3(0.0f, -0.5f, 0.0f);
  world.addBody(ground);

  haif::BodyDef box;
  box.shape = haif::Shape::box(haif::Vec3(0.5f, 0.5f, 0.5f));
  box.xf.p = haif::Vec3(0.0f, 2.0f, 0.0f);
  const uint32_t boxId = world.addBody(box);

  haif::BodyDef ball;
  ball.shape = haif::Shape::sphere(0.25f);
  ball.xf.p = haif::Vec3(2.0f, 0.25f, 0.0f);
  ball.linearVelocity = haif::Vec3(-1.0f, 0.0f, 0.0f);
  const uint32_t ballId = world.addBody(ball);

  for (int step = 1; step <= 120; ++step) {
    world.step();
    if (step % 30 == 0) {
      const haif::Vec3 b = world.bodies().xf[boxId].p, s = world.bodies().xf[ballId].p;
      std::printf("t = %.2f s  box at (%.3f, %.3f, %.3f)  ball at (%.3f, %.3f, %.3f)\n", step * settings.dt,
                  b.x(), b.y(), b.z(), s.x(), s.y(), s.z());
    }
  }
  // The box has landed and rests on the ground: its centre half a metre up.
  const float y = world.bodies().xf[boxId].p.y();
  std::printf("box resting at y = %.3f m (expected 0.5)\n", y);
  return y > 0.49f && y < 0.51f ? 0 : 1;
}
