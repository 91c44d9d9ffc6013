// Randomized stress test: many small random worlds (tests/stress/random_world.h) must never produce
// NaN, explode (speeds beyond what their start energy allows) or gain energy without cause.
// Seeds are fixed, so every run checks the same worlds; a failing seed is reproduced by RandomWorldSeed.
#include "random_world.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <cmath>
#include <sstream>

namespace haif::test {
namespace {

constexpr uint32_t kFirstSeed = 1000;
constexpr int kWorlds = 200;
constexpr int kSteps = 120;
// Seeds that fail for a known, not yet fixed reason; each has a DISABLED_ regression test below that
// says why. The sweep skips them so that it guards everything else.
constexpr std::array<uint32_t, 0> kKnownFailures{};  // none at present

bool knownFailure(uint32_t seed) {
  for (uint32_t s : kKnownFailures)
    if (s == seed) return true;
  return false;
}

bool stateFinite(const World& w) {
  const BodyStore& b = w.bodies();
  for (size_t i = 0; i < b.size(); ++i)
    if (!isFinite(b.xf[i].p) || !isFinite(b.v[i]) || !isFinite(b.w[i]) || !std::isfinite(b.xf[i].q.w()) ||
        !isFinite(b.xf[i].q.vec()))
      return false;
  return true;
}

// An iteration count drawn anew every step from [4, 64], with islands stopping once converged: what
// the adaptive controller does, without its clock (so a seed still reproduces its run).
class DrawnIterations final : public IterationController {
 public:
  explicit DrawnIterations(uint32_t seed) : rng_(seed) { iMin = 4, iMax = 64; }
  int choose(const ControlContext&) override { return std::uniform_int_distribution<int>(iMin, iMax)(rng_); }
  std::string name() const override { return "drawn"; }

 private:
  std::mt19937 rng_;
};

// Steps world `seed`; returns "" when it behaved, else what went wrong and when.
std::string runRandomWorld(uint32_t seed, RandomWorldKinds kinds = {}, bool drawnIterations = false) {
  RandomWorld rw = makeRandomWorld(seed, kinds);
  World& w = *rw.world;
  if (drawnIterations) {
    w.settings().residualTolerance = 1e-5f;
    w.setController(std::make_unique<DrawnIterations>(seed));
  }
  const double g = 9.81;
  // Fastest a body may get: all the start energy of the fastest, highest body as speed, after rising by
  // its size out of an overlap; a heavy body hitting a light one can give it up to twice its own speed
  // (e <= 1) and chains of such hits a little more, hence 3x, plus the push-out speed. A kinematic
  // mover hits bodies at up to twice its speed.
  const double vFree =
      std::sqrt(rw.maxStartSpeed * rw.maxStartSpeed + 2.0 * g * (rw.maxStartHeight + 2.0 * rw.maxRadius));
  const double speedBound = 3.0 * (vFree + 2.0 * rw.kinematicSpeed) + 2.0;
  const double e0 = w.kineticEnergy() + w.potentialEnergy();
  const double energyBound = e0 + rw.overlapAllowance + 0.01 * std::fabs(e0) + 1e-6;
  // How deep each body's lowest point starts in the ground (0 when above it): it may be pushed out,
  // never sink deeper (by more than sinkLimit; a 100 kg body on a 0.1 kg one presses it 10-16 cm in),
  // whatever part of it touches: a compound part the narrow phase skipped would pass through. Not
  // with joints: a loop of joints that cannot all hold may pull a body into the ground.
  const double sinkLimit = kinds.joints ? 1e30 : 0.25;
  std::vector<double> startDepth(w.bodyCount(), 0.0);
  for (uint32_t i = 0; i < w.bodyCount(); ++i)
    startDepth[i] = std::min(0.0, double(computeAabb(w.shape(i), w.bodies().xf[i]).lo.y()));
  std::ostringstream why;
  for (int s = 1; s <= kSteps; ++s) {
    w.step();
    if (!stateFinite(w)) why << "NaN/inf in the state after step " << s;
    else {
      const BodyStore& b = w.bodies();
      double vMax = 0.0, yMin = 1e30, sunk = 0.0;
      for (size_t i = 0; i < b.size(); ++i) {
        if (!b.isDynamic(uint32_t(i))) continue;
        vMax = std::max(vMax, double(b.v[i].norm()));
        yMin = std::min(yMin, double(b.xf[i].p.y()));
        sunk = std::max(sunk, startDepth[i] - double(computeAabb(w.shape(uint32_t(i)), b.xf[i]).lo.y()));
      }
      const double e = w.kineticEnergy() + w.potentialEnergy();
      if (vMax > speedBound) why << "speed " << vMax << " m/s > bound " << speedBound << " after step " << s;
      else if (rw.kinematicSpeed == 0.0 && e > energyBound)  // a mover may add energy
        why << "energy " << e << " J > bound " << energyBound << " J (start " << e0 << " J) after step " << s;
      else if (yMin < -1.0) why << "a body fell through the ground (centre at y = " << yMin << ") after step " << s;
      else if (sunk > sinkLimit) why << "a body sank " << sunk << " m deeper into the ground than it started after step " << s;
    }
    if (!why.str().empty()) {
      why << "\n" << rw.description;
      return why.str();
    }
  }
  return "";
}

TEST(RandomWorlds, NeverNaNExplodeOrGainEnergy) {
  int failures = 0;
  for (int k = 0; k < kWorlds; ++k) {
    const uint32_t seed = kFirstSeed + uint32_t(k);
    if (knownFailure(seed)) continue;
    const std::string problem = runRandomWorld(seed);
    if (!problem.empty()) {
      ++failures;
      ADD_FAILURE() << "random world seed " << seed << ": " << problem;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << kWorlds << " random worlds";
}

// Runs `worlds` seeds from `firstSeed`, each with every kind in `kinds`, at fixed 10 iterations and at
// counts drawn from [4, 64] every step; reports each failing run and returns how many failed.
int runWorldVariants(const char* label, uint32_t firstSeed, int worlds, std::initializer_list<RandomWorldKinds> kinds) {
  int failures = 0;
  for (int k = 0; k < worlds; ++k) {
    const uint32_t seed = firstSeed + uint32_t(k);
    for (const RandomWorldKinds kind : kinds)
      for (const bool drawn : {false, true}) {
        const std::string problem = runRandomWorld(seed, kind, drawn);
        if (!problem.empty()) {
          ++failures;
          ADD_FAILURE() << label << " world seed " << seed << (kind.kinematic ? " with a paddle" : "")
                        << (drawn ? ", drawn iterations" : ", fixed 10") << ": " << problem;
        }
      }
  }
  return failures;
}

TEST(RandomWorlds, MixedWorldsWithJointsAndMoversNeverNaNOrExplode) {
  // Joints (chains, rings, loops, pins; many of them unsatisfiable once bodies collide) and kinematic
  // paddles, at fixed 10 iterations and at counts drawn from [4, 64] every step: 500 runs.
  constexpr int kMixedWorlds = 125;
  const int failures = runWorldVariants("mixed", 5000, kMixedWorlds, {RandomWorldKinds{true, false}, RandomWorldKinds{true, true}});
  EXPECT_EQ(failures, 0) << "of " << 4 * kMixedWorlds << " mixed runs";
}

TEST(RandomWorlds, WorldsWithCompoundsNeverNaNOrExplode) {
  // Compound bodies of 2 to 4 parts among the others, with and without a kinematic paddle, at fixed
  // 10 iterations and at counts drawn from [4, 64]: 240 runs.
  constexpr int kCompoundWorlds = 60;
  const int failures =
      runWorldVariants("compound", 9000, kCompoundWorlds, {RandomWorldKinds{false, false, true}, RandomWorldKinds{false, true, true}});
  EXPECT_EQ(failures, 0) << "of " << 4 * kCompoundWorlds << " compound runs";
}

// Found by the sweep: an 80 kg capsule much longer than it is thick (tiny inertia about its axis),
// knocked into a tumble near the ground, spun up from 3 to 470 rad/s in 12 steps of free flight and the
// world gained 16% energy: integratePositions turned the body by its start angular velocity and then
// read w from the kept world angular momentum, an update that pumps energy into a body with one very
// small principal moment. Free bodies now take the implicit midpoint rule, which keeps the energy.
TEST(RandomWorlds, Seed1113ThinCapsuleDoesNotSpinUp) { EXPECT_EQ(runRandomWorld(1113), ""); }

TEST(RandomWorlds, SameSeedSameWorld) {
  // Reproducibility is what makes a failing seed useful: the same seed must give the same run.
  RandomWorld a = makeRandomWorld(kFirstSeed + 7), b = makeRandomWorld(kFirstSeed + 7);
  ASSERT_EQ(a.description, b.description);
  for (int s = 0; s < 30; ++s) {
    a.world->step();
    b.world->step();
  }
  EXPECT_EQ(a.world->stateHash(), b.world->stateHash());
}

}  // namespace
}  // namespace haif::test
