// haif calibrate: measures this machine's cost model and writes it to a file that the adaptive
// controller starts from and model mode decides with (docs/architecture.md, "The iteration controller").
#include "app/cli.h"
#include "app/commands.h"
#include "haif/cost_model.h"
#include "haif/world.h"
#include "tools/atomic_file.h"
#include "tools/interrupts.h"
#include "tools/staged_output.h"

#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace haif {

namespace {

/// `stacks` stacks of 10 unit boxes on a ground box, settled for a second.
std::unique_ptr<World> makeStacks(int stacks, int threads) {
  WorldSettings ws;
  ws.threads = threads;
  auto w = std::make_unique<World>(ws);
  BodyDef ground;
  ground.kind = BodyKind::Static;
  ground.shape = Shape::box(Vec3(500, 1, 500));
  ground.xf.p = Vec3(0, -1, 0);
  w->addBody(ground);
  const int k = int(std::ceil(std::sqrt(double(stacks))));
  for (int s = 0; s < stacks; ++s)
    for (int h = 0; h < 10; ++h) {
      BodyDef b;
      b.shape = Shape::box(Vec3::Constant(0.5f));
      b.mass = 1.0f;
      b.xf.p = Vec3(3.0f * float(s % k), 0.5f + 1.01f * float(h), 3.0f * float(s / k));
      w->addBody(b);
    }
  for (int i = 0; i < 60; ++i) w->step();
  return w;
}

struct Sample {
  double solveMs, collisionMs, integrateMs;
  double rows, points, bodies;
};

Sample measure(World& w, int iterations, int steps) {
  w.setController(std::make_unique<FixedController>(iterations));
  std::vector<double> solve, coll, integ;
  Sample s{};
  for (int i = 0; i < steps; ++i) {
    w.step();
    const StepStats& st = w.lastStats();
    solve.push_back(st.solveMs);
    coll.push_back(st.collisionMs);
    integ.push_back(st.integrateMs);
    s.rows = double(w.islands().totalRows);
    s.points = st.contactPoints;
    s.bodies = st.awakeBodies;
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  s.solveMs = median(solve);
  s.collisionMs = median(coll);
  s.integrateMs = median(integ);
  return s;
}

}  // namespace

int commandCalibrate(int argc, char** argv) {
  CommandLine cl("calibrate", {"--out", "--threads", "--stacks"}, {});
  std::string error;
  int threads = int(tbb::info::default_concurrency()), stacks = 100;
  if (!cl.parse(argc, argv, 2, error) || !cl.getInt("--threads", 1, 1024, threads, error) ||
      !cl.getInt("--stacks", 4, 10000, stacks, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  // Checked before measuring, created after: a failed or interrupted calibration leaves nothing.
  const std::string out = cl.get("--out", "output/cost_model.txt");
  if (!checkOutputFile(out, error)) {
    std::fprintf(stderr, "haif calibrate: %s\n", error.c_str());
    return 1;
  }
  registerTemporary(out + ".tmp");  // CostModel::save's temporary name

  // Two iteration counts on one thread separate the per-iteration cost from the fixed per-row cost.
  auto w = makeStacks(stacks, 1);
  const int lo = 4, hi = 24, steps = 60;
  const Sample a = measure(*w, lo, steps);
  const Sample b = measure(*w, hi, steps);
  CostModel m;
  const double rows = std::max(1.0, b.rows);
  m.msPerRowIteration = std::max(1e-9, (b.solveMs - a.solveMs) / (rows * (hi - lo)));
  m.msPerRowPrepare = std::max(1e-9, a.solveMs / rows - lo * m.msPerRowIteration);
  m.msPerContactPoint = std::max(1e-9, b.collisionMs / std::max(1.0, b.points));
  m.msPerBody = std::max(1e-9, b.integrateMs / std::max(1.0, b.bodies));
  // Parallel efficiency from the same scene (many equal islands) on `threads` threads.
  if (threads > 1) {
    auto wp = makeStacks(stacks, threads);
    const Sample p = measure(*wp, hi, steps);
    const double speedup = b.solveMs / std::max(1e-9, p.solveMs);
    m.parallelEfficiency = std::clamp((speedup - 1.0) / double(threads - 1), 0.05, 1.0);
  }
  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if ((!parent.empty() && !ensureWritableDir(parent.string(), error)) || !m.save(out, error)) {
    waitIfInterrupted();
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("cost model (%d stacks, %d threads) written to %s\n", stacks, threads, out.c_str());
  std::printf("  ms_per_row_iteration %.3g\n  ms_per_row_prepare %.3g\n  ms_per_contact_point %.3g\n"
              "  ms_per_body %.3g\n  parallel_efficiency %.3g\n",
              m.msPerRowIteration, m.msPerRowPrepare, m.msPerContactPoint, m.msPerBody, m.parallelEfficiency);
  return 0;
}

}  // namespace haif
