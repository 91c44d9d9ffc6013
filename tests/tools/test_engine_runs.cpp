// HAIF and Bullet behind EngineRun: the same scene file gives the same bodies, the same free fall,
// the same friction between the same materials, and metrics computed by the same code; engine
// specs parse or fail with a clear message. Bullet parts skip when Bullet is not built.
#include "tools/engine_metrics.h"
#include "tools/engine_spec.h"
#include "tools/haif_engine_run.h"
#ifdef HAIF_HAVE_BULLET
#include "tools/bullet_engine_run.h"
#endif

#include <gtest/gtest.h>

#include <vector>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace haif {
namespace {

namespace fs = std::filesystem;

class EngineRuns : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("haif_engines_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string writeScene(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  std::unique_ptr<EngineRun> start(const std::string& spec, const std::string& path) {
    EngineSpec s;
    std::string error;
    EXPECT_TRUE(parseEngineSpec(spec, s, error)) << error;
    auto run = makeEngineRun(s, path, 1, error);
    EXPECT_TRUE(run) << error;
    return run;
  }

  fs::path dir_;
};

// A box resting on the ground, a sphere dropped from 20 m beside it. Bodies come first, generated
// ones after: box 0 (smooth), sphere 1, ground 2 (rough).
const char* kScene = R"({
  "settings": {"iterations": 10},
  "materials": {"rough": {"friction": 0.9}, "smooth": {"friction": 0.4}},
  "generators": [{"type": "ground", "half_extents": [50, 1, 50], "material": "rough"}],
  "bodies": [
    {"shape": {"type": "box", "half_extents": 0.5}, "position": [0, 0.5, 0], "mass": 2, "material": "smooth"},
    {"shape": {"type": "sphere", "radius": 0.25}, "position": [5, 20, 0], "mass": 1}
  ]
})";

TEST_F(EngineRuns, SpecsParseOrSayWhatIsWrong) {
  EngineSpec s;
  std::string error;
  ASSERT_TRUE(parseEngineSpec("fixed:12", s, error)) << error;
  EXPECT_EQ(s.engine, "haif");
  EXPECT_EQ(s.solver.iterations, 12);
  ASSERT_TRUE(parseEngineSpec("haif:adaptive:2.5", s, error)) << error;
  EXPECT_EQ(s.solver.mode, "adaptive");
  EXPECT_DOUBLE_EQ(s.solver.budgetMs, 2.5);
  ASSERT_TRUE(parseEngineSpec("haif", s, error)) << error;
  EXPECT_EQ(s.solver.mode, "fixed");
  EXPECT_EQ(s.solver.iterations, -1);  // the scene's count
  ASSERT_TRUE(parseEngineSpec("bullet:10", s, error)) << error;
  EXPECT_EQ(s.engine, "bullet");
  EXPECT_EQ(s.solver.iterations, 10);
  ASSERT_TRUE(parseEngineSpec("bullet:fixed:3", s, error)) << error;
  EXPECT_EQ(s.solver.iterations, 3);
  ASSERT_TRUE(parseEngineSpec("bullet", s, error)) << error;
  EXPECT_EQ(s.solver.iterations, -1);
  EXPECT_FALSE(parseEngineSpec("bullet:adaptive:4", s, error));
  EXPECT_NE(error.find("fixed iteration counts only"), std::string::npos) << error;
  EXPECT_FALSE(parseEngineSpec("bullet:0", s, error));
  EXPECT_FALSE(parseEngineSpec("physx:10", s, error));
  EXPECT_NE(error.find("physx"), std::string::npos) << error;
  EXPECT_NE(error.find("haif, bullet"), std::string::npos) << error;
}

TEST_F(EngineRuns, BulletWithoutBulletIsAClearError) {
  if (bulletAvailable()) GTEST_SKIP() << "this build has Bullet";
  EngineSpec s;
  std::string error;
  ASSERT_TRUE(parseEngineSpec("bullet:10", s, error));
  EXPECT_FALSE(makeEngineRun(s, writeScene("a.json", kScene), 1, error));
  EXPECT_NE(error.find("without Bullet"), std::string::npos) << error;
}

TEST_F(EngineRuns, HaifHashAndContactsMatchItsWorld) {
  const std::string path = writeScene("a.json", kScene);
  auto run = start("fixed:10", path);
  ASSERT_TRUE(run);
  for (int i = 0; i < 5; ++i) run->step();
  std::vector<BodySample> bodies;
  run->readBodies(bodies);
  ASSERT_EQ(bodies.size(), 3u);
  EXPECT_EQ(hashPoses(bodies), run->stateHash());
  EXPECT_TRUE(bodies[0].dynamic);
  EXPECT_FALSE(bodies[2].dynamic);
  std::vector<ContactSample> contacts;
  run->readContacts(contacts);
  ASSERT_FALSE(contacts.empty());
  for (const ContactSample& c : contacts) EXPECT_EQ(c.extent, 1.0f);  // the box is the smaller body
}

TEST_F(EngineRuns, BothEnginesFallAtGAndRestTheSame) {
  // HAIF always; Bullet where the build has it (HAIF's own free fall was skipped without it).
  const std::string path = writeScene("a.json", kScene);
  std::vector<const char*> specs{"fixed:10"};
  if (bulletAvailable()) specs.push_back("bullet:10");
  for (const char* spec : specs) {
    SCOPED_TRACE(spec);
    auto run = start(spec, path);
    ASSERT_TRUE(run);
    EXPECT_EQ(run->bodyCount(), 3u);
    EngineMetrics metrics;
    const int n = 60;
    metrics.begin(*run, n);
    for (int i = 0; i < n; ++i) {
      run->step();
      ASSERT_TRUE(metrics.afterStep(*run)) << "NaN at step " << i;
    }
    std::vector<BodySample> bodies;
    run->readBodies(bodies);
    // The sphere: one second of free fall, semi-implicit Euler: y = 20 − g dt² n(n+1)/2.
    const double dt = 1.0 / 60.0;
    EXPECT_NEAR(bodies[1].p.y(), 20.0 - 9.81 * dt * dt * n * (n + 1) / 2.0, 2e-3);
    EXPECT_NEAR(bodies[1].v.y(), -9.81, 2e-3);
    // The box stays where it was; penetration stays near the slop.
    EXPECT_NEAR(bodies[0].p.y(), 0.5, 0.01);
    EXPECT_LT(metrics.maxPenetration(), 0.02);
    // Bullet's box sinks into the slop; HAIF's starts from the impulse of its weight (a cold contact
    // at rest, World::estimateColdImpulses) and need not sink at all.
    if (std::string(spec).rfind("bullet", 0) == 0) EXPECT_GT(metrics.maxPenetration(), 0.0);
    else EXPECT_GE(metrics.maxPenetration(), 0.0);
    EXPECT_LE(metrics.rmsPenetration(), metrics.maxPenetration());
    EXPECT_NEAR(metrics.maxPenetrationFraction(), metrics.maxPenetration() / 1.0, 1e-9);
    // Mean drop: the sphere's fall dominates (≈ 17.6 m / 2 bodies).
    EXPECT_NEAR(metrics.maxDrop(), 20.0 - bodies[1].p.y(), 1e-4);
    EXPECT_NEAR(metrics.meanDrop(), 0.5 * (0.5 - bodies[0].p.y() + 20.0 - bodies[1].p.y()), 1e-4);
    // Jitter: the falling sphere's speed over the last second (0 .. 9.81 m/s), RMS over both bodies.
    EXPECT_GT(metrics.jitter(), 3.0);
    EXPECT_LT(metrics.jitter(), 5.0);
    EXPECT_FALSE(metrics.nanDetected());
  }
}

TEST_F(EngineRuns, FrictionBetweenTwoMaterialsIsTheSameInBothEngines) {
  if (!bulletAvailable()) GTEST_SKIP() << "built without Bullet";
  const std::string path = writeScene("a.json", kScene);
  auto haif = start("fixed:10", path);
  auto bullet = start("bullet:10", path);
  ASSERT_TRUE(haif && bullet);
  haif->step();
  bullet->step();
  const World& w = static_cast<const HaifEngineRun&>(*haif).world();
  float haifFriction = NAN;
  for (const Contact& c : w.contacts())
    if (c.touching() && ((c.a == 0 && c.b == 2) || (c.a == 2 && c.b == 0))) haifFriction = c.friction;
  EXPECT_NEAR(haifFriction, std::sqrt(0.9f * 0.4f), 1e-6f);
#ifdef HAIF_HAVE_BULLET
  // Bullet's pair friction, read from its contact point: the product of the per-body √μ values.
  EXPECT_NEAR(static_cast<const BulletEngineRun&>(*bullet).world().combinedFriction(0, 2), haifFriction, 1e-6f);
#endif
  // Sliding test of the pair: both engines decelerate a pushed box at the same μ g.
  const std::string slide = std::string(kScene).replace(std::string(kScene).find("\"mass\": 2"), 9,
                                                        "\"mass\": 2, \"velocity\": [2, 0, 0]");
  const std::string slidePath = writeScene("slide.json", slide);
  double speed[2] = {0, 0};
  int k = 0;
  for (const char* spec : {"fixed:10", "bullet:10"}) {
    auto run = start(spec, slidePath);
    ASSERT_TRUE(run);
    for (int i = 0; i < 20; ++i) run->step();
    std::vector<BodySample> s;
    run->readBodies(s);
    speed[k++] = s[0].v.x();
  }
  const double expected = 2.0 - std::sqrt(0.9 * 0.4) * 9.81 * 20.0 / 60.0;
  EXPECT_NEAR(speed[0], expected, 0.05) << "HAIF";
  EXPECT_NEAR(speed[1], expected, 0.05) << "Bullet";
}

}  // namespace
}  // namespace haif
