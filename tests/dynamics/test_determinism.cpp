// The same scene stepped twice gives bit-identical states (the replay/fixed-mode guarantee rests on it).
#include "stress/random_world.h"
#include "support/physics_test_util.h"

#include <random>

namespace haif::test {
namespace {

// A random-ish pile of boxes and spheres built from a fixed seed; they fall and collide.
void buildPile(World& w, uint32_t seed) {
  addGround(w);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xz(-2.0f, 2.0f), ang(-1.0f, 1.0f), size(0.2f, 0.5f);
  for (int i = 0; i < 100; ++i) {
    BodyDef d;
    d.shape = (i % 3 == 0) ? Shape::sphere(size(rng)) : Shape::box(Vec3(size(rng), size(rng), size(rng)));
    d.xf.p = Vec3(xz(rng), 1.0f + 1.1f * float(i / 4), xz(rng));
    d.xf.q = Quat(Eigen::AngleAxisf(ang(rng) * kPi, Vec3(ang(rng), ang(rng), ang(rng) + 2.0f).normalized()));
    d.density = 500.0f + 1000.0f * (ang(rng) + 1.0f);
    d.friction = 0.5f;
    w.addBody(d);
  }
}

uint64_t runPile(int threads, int steps, uint64_t* startHash = nullptr) {
  WorldSettings s;
  s.threads = threads;
  World w(s);
  buildPile(w, 2024);
  if (startHash) *startHash = w.stateHash();
  for (int i = 0; i < steps; ++i) w.step();
  EXPECT_GT(w.lastStats().contactPoints, 50u) << "the pile should be in contact";
  return w.stateHash();
}

TEST(Determinism, SamePileTwiceGivesSameHash) {
  uint64_t start = 0;
  const uint64_t a = runPile(1, 150, &start);
  const uint64_t b = runPile(1, 150);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, start) << "nothing moved: the comparison would be trivial";
}

TEST(Determinism, ThreadCountDoesNotChangeTheResult) {
  // Fixed mode must be bit-identical for any thread count (docs/architecture.md, Threads).
  const uint64_t one = runPile(1, 150);
  EXPECT_EQ(runPile(4, 150), one);
}

TEST(Determinism, RandomWorldsGiveOneStateOnAnyThreadCount) {
  // Every shape and a kinematic paddle (tests/stress/random_world.h; with joints a world is one
  // island): islands solved side by side on 2 threads must end where one thread ends. Under
  // ThreadSanitizer (docs/race_checking.md) this also checks that no two share memory unsynchronised.
  for (uint32_t seed = 5000; seed < 5012; ++seed) {
    RandomWorld one = makeRandomWorld(seed, RandomWorldKinds{false, true});
    RandomWorld two = makeRandomWorld(seed, RandomWorldKinds{false, true});
    two.world->setThreads(2);
    for (int s = 0; s < 120; ++s) {
      one.world->step();
      two.world->step();
    }
    EXPECT_GT(two.world->lastStats().islands, 1u) << "seed " << seed << ": islands to solve side by side";
    EXPECT_EQ(one.world->stateHash(), two.world->stateHash()) << "seed " << seed << "\n" << one.description;
  }
}

TEST(Determinism, HashSeesASingleBitOfState) {
  World w;
  buildPile(w, 7);
  const uint64_t h = w.stateHash();
  float& x = w.bodies().xf[50].p.x();
  x = std::nextafter(x, 1e30f);
  EXPECT_NE(w.stateHash(), h);
}

}  // namespace
}  // namespace haif::test
