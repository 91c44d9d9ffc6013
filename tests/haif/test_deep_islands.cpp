// Small islands deeper than the main sweeps reach: a sweep passes a landing down one layer, so a
// tall column that is no chain (a box beside its foot touches two of its boxes) bounced at 4
// iterations, leaned and fell. Such islands have their normal rows solved together every step
// (World::tooDeepForSweeps, WorldSettings::deepLayersPerSweep), as a chain's are.
#include "support/physics_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace haif {
namespace {

using test::addBox;
using test::addColumn;
using test::addGround;

WorldSettings settingsAt(int iterations, float deepLayersPerSweep = WorldSettings{}.deepLayersPerSweep) {
  WorldSettings ws;
  ws.iterations = iterations;
  ws.deepLayersPerSweep = deepLayersPerSweep;
  return ws;
}

// How far the boxes of a column (at x = z = 0, placed with 1 cm gaps) ended from where they would
// stand with the gaps closed: sideways and down (m), and their largest tilt from upright (rad).
struct ColumnState {
  float sideways = 0.0f, sunk = 0.0f, tilt = 0.0f;
};

ColumnState columnState(const World& w, const std::vector<uint32_t>& column, float bottomY = 0.5f) {
  ColumnState s;
  for (size_t h = 0; h < column.size(); ++h) {
    const Vec3 p = w.bodies().xf[column[h]].p;
    s.sideways = std::max(s.sideways, Vec3(p.x(), 0.0f, p.z()).norm());
    s.sunk = std::max(s.sunk, bottomY + float(h) - p.y());
    const Vec3 up = w.bodies().xf[column[h]].q * Vec3::UnitY();
    s.tilt = std::max(s.tilt, std::acos(std::clamp(up.y(), -1.0f, 1.0f)));
  }
  return s;
}

TEST(DeepIslands, AColumnOfTwentyWithABoxBesideItsFootStandsForHalfAMinute) {
  // Before: at 4 iterations the column bounced (its top at up to 2.4 m/s) and fell by step ~600.
  for (const int iterations : {4, 10}) {
    World w(settingsAt(iterations));
    addGround(w);
    const std::vector<uint32_t> column = addColumn(w, 20, 0.0f, 0.0f, 1.01f);
    addBox(w, Vec3(1.01f, 0.5f, 0.0f));
    for (int s = 0; s < 1800; ++s) w.step();
    const ColumnState st = columnState(w, column);
    const std::string what = std::to_string(iterations) + " iterations";
    EXPECT_LT(st.sideways, 0.01f) << what;  // nothing leaned
    EXPECT_LT(st.sunk, 20 * w.settings().contact.slop) << what;  // the gaps closed, no contact past the slop
    EXPECT_LT(st.tilt, 0.01f) << what;
    EXPECT_LT(w.kineticEnergy(), 1e-4) << what;
  }
}

TEST(DeepIslands, AColumnOnTwoBoxesStandsAtFourIterations) {
  // Fifteen unit boxes with 1 cm gaps on two boxes side by side: before, it fell at 4 iterations.
  World w(settingsAt(4));
  addGround(w);
  addBox(w, Vec3(-0.55f, 0.5f, 0.0f));
  addBox(w, Vec3(0.55f, 0.5f, 0.0f));
  std::vector<uint32_t> column;
  for (int h = 0; h < 15; ++h) column.push_back(addBox(w, Vec3(0.0f, 1.5f + 1.01f * float(h), 0.0f)));
  for (int s = 0; s < 1800; ++s) w.step();
  const ColumnState st = columnState(w, column, 1.5f);
  EXPECT_LT(st.sideways, 0.01f);
  EXPECT_LT(st.sunk, 17 * w.settings().contact.slop);
  EXPECT_LT(st.tilt, 0.01f);
  EXPECT_LT(w.kineticEnergy(), 1e-4);
}

TEST(DeepIslands, ShallowIslandsAreSweptAsBefore) {
  // Six boxes deep at 10 iterations (8 main sweeps) is within the sweeps' reach: the same state with
  // the deep rule on or off.
  auto run = [](float deepLayersPerSweep) {
    World w(settingsAt(10, deepLayersPerSweep));
    addGround(w);
    addColumn(w, 6, 0.0f, 0.0f, 1.01f);
    addBox(w, Vec3(1.01f, 0.5f, 0.0f));
    for (int s = 0; s < 120; ++s) w.step();
    return w.stateHash();
  };
  EXPECT_EQ(run(WorldSettings{}.deepLayersPerSweep), run(0.0f));
}

TEST(DeepIslands, SameStateForAnyThreadCount) {
  // Six deep columns, each with a box beside its foot, solved concurrently island by island.
  test::expectSameStateForThreadCounts([](int threads) {
    WorldSettings ws = settingsAt(4);
    ws.threads = threads;
    World w(ws);
    addGround(w);
    for (int c = 0; c < 6; ++c) {
      const float x = 4.0f * float(c);
      addColumn(w, 12 + c, x, 0.0f, 1.01f);
      addBox(w, Vec3(x + 1.01f, 0.5f, 0.0f));
    }
    for (int s = 0; s < 120; ++s) w.step();
    return w.stateHash();
  });
}

}  // namespace
}  // namespace haif
