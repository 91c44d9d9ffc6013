// Google Benchmark of the narrow phase: every pair of shape types (sphere, box, capsule, convex
// hull, and a mesh triangle as the second shape), each separated beyond the margin, touching, and
// deep, reporting ns per collide() call (issue 27); and per pair the depth bound from two support
// queries (reach_bound/*), which the turn projection takes instead of a collision where it suffices.
// The pile/* rows time each pair over many poses that touch the way a pile's pairs do (corners,
// edges and faces, turned every way); the stacked poses above meet face to face, which is the
// cheapest way to touch.
// Timings are medians of repetitions:
//   ./build/bench_narrow_phase --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "collision/collide.h"
#include "collision/convex_hull.h"
#include "collision/support.h"
#include "collision/triangle_mesh.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace haif {
namespace {

constexpr float kMargin = 0.02f;  // the world's default speculative margin

// A shape with how far it reaches above and below its centre: the pairs are stacked along y, and
// only turned about y (which keeps those reaches), so each gap is exact.
struct Piece {
  std::string name;
  Shape shape;
  Quat q = Quat::Identity();
  float up = 0.0f, down = 0.0f;
};

std::vector<Piece> pieces() {
  std::vector<Piece> out;
  out.push_back({"sphere", Shape::sphere(0.5f), Quat::Identity(), 0.5f, 0.5f});
  out.push_back({"box", Shape::box(Vec3(0.6f, 0.4f, 0.5f)), Quat::Identity(), 0.4f, 0.4f});
  // A capsule lying along x (its core runs along local y).
  out.push_back({"capsule", Shape::capsule(0.3f, 0.5f), Quat(Eigen::AngleAxisf(1.5707963f, Vec3::UnitZ())), 0.3f, 0.3f});
  // A hull of 20 points, as a cut rock: hexagonal top and bottom faces (so "touching" touches) and
  // an octagonal waist, turned against each other: faces and edges of mixed sizes.
  std::vector<Vec3> pts;
  for (int i = 0; i < 6; ++i) {
    const float t = float(i) * 1.0471976f;
    pts.emplace_back(0.35f * std::cos(t), 0.45f, 0.3f * std::sin(t));
    pts.emplace_back(0.3f * std::cos(t + 0.5f), -0.45f, 0.35f * std::sin(t + 0.5f));
  }
  for (int i = 0; i < 8; ++i) {
    const float t = float(i) * 0.7853982f + 0.2f;
    pts.emplace_back(0.6f * std::cos(t), 0.1f * std::sin(3.0f * t), 0.5f * std::sin(t));
  }
  std::string error;
  auto hull = buildConvexHull(pts, &error);
  float top = -1e30f, bottom = 1e30f;
  for (const Vec3& p : pts) top = std::max(top, p.y()), bottom = std::min(bottom, p.y());
  out.push_back({"hull", Shape::convexHull(hull), Quat::Identity(), top, -bottom});
  return out;
}

Piece meshTriangle() {
  auto mesh = buildTriangleMesh({Vec3(-20.0f, 0.0f, -20.0f), Vec3(20.0f, 0.0f, -20.0f), Vec3(0.0f, 0.0f, 30.0f)},
                                {0, 2, 1}, nullptr);
  return {"mesh_triangle", Shape::triangleMesh(mesh), Quat::Identity(), 0.0f, 0.0f};
}

// Gap between the two shapes along y: beyond the margin (an early out), touching, deep.
struct Setting {
  const char* name;
  float gap;
};
constexpr Setting kSettings[] = {{"separated", 0.1f}, {"touching", -0.001f}, {"deep", -0.1f}};

void timeCollide(benchmark::State& state, const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  Manifold m;
  int points = 0;
  for (auto _ : state) {
    points = collide(a, xa, b, xb, kMargin, m);
    benchmark::DoNotOptimize(m);
  }
  state.counters["points"] = points;
}

// a below, b above by `gap`, b turned 0.3 rad about y so no edges or faces line up exactly.
void collidePair(benchmark::State& state, Piece a, Piece b, float gap) {
  Transform xa, xb;
  xa.q = a.q;
  xb.q = Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitY())) * b.q;
  xb.p = Vec3(0.05f, a.up + b.down + gap, 0.03f);
  timeCollide(state, a.shape, xa, b.shape, xb);
}

// The same pair's depth bound along its normal (collision/support.h): what the turn projection pays
// for a candidate it settles instead of colliding.
void reachPair(benchmark::State& state, Piece a, Piece b, float gap) {
  Transform xa, xb;
  xa.q = a.q;
  xb.q = Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitY())) * b.q;
  xb.p = Vec3(0.05f, a.up + b.down + gap, 0.03f);
  float bound = 0.0f;
  for (auto _ : state) {
    bound = depthBoundFromOverlap(overlapAlong(a.shape, xa, b.shape, xb, Vec3::UnitY()));
    benchmark::DoNotOptimize(bound);
  }
  state.counters["bound_mm"] = 1000.0 * bound;
}

// A mesh is static and second: the shape rests on the triangle (in the plane y = 0) by `gap`.
void collideOnTriangle(benchmark::State& state, Piece above, Piece tri, float gap) {
  Transform xa, xb;
  xa.q = Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitY())) * above.q;
  xa.p = Vec3(0.05f, above.down + gap, 0.03f);
  timeCollide(state, above.shape, xa, tri.shape, xb);
}

// Pair poses as a pile makes them: both shapes turned at random, b moved out from a along a random
// direction to where they first touch (a bisection on collide), then kPileDepth further in. In the
// swept pit the hull pairs cost 1.2-5x, and a capsule on a box 4x, their stacked time (measured in
// the world, session 68).
constexpr int kPilePoses = 512;
constexpr float kPileDepth = 0.005f;
struct PosedPair {
  Transform xa, xb;
};

Quat randomTurn(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  Quat q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q;
}

std::vector<PosedPair> pilePoses(const Piece& a, const Piece& b, uint32_t seed, float depth = kPileDepth) {
  std::mt19937 rng(seed);
  std::vector<PosedPair> out;
  Manifold m;
  while (int(out.size()) < kPilePoses) {
    PosedPair pp;
    pp.xa.q = randomTurn(rng);
    pp.xb.q = randomTurn(rng);
    std::normal_distribution<float> g(0.0f, 1.0f);
    Vec3 d(g(rng), g(rng), g(rng));
    if (d.squaredNorm() < 1e-6f) continue;
    d.normalize();
    // Along d the two reach no farther than their supports: beyond that they are apart.
    float lo = 0.0f, hi = supportAlong(a.shape, pp.xa, d) + supportAlong(b.shape, Transform{Vec3::Zero(), pp.xb.q}, -d) + 0.01f;
    for (int k = 0; k < 40; ++k) {
      const float mid = 0.5f * (lo + hi);
      pp.xb.p = mid * d;
      (collide(a.shape, pp.xa, b.shape, pp.xb, 0.0f, m) > 0 ? lo : hi) = mid;
    }
    pp.xb.p = (lo - depth) * d;
    if (depth > 0.0f && collide(a.shape, pp.xa, b.shape, pp.xb, 0.0f, m) == 0) continue;  // a pose the bisection missed
    out.push_back(pp);
  }
  return out;
}

void collidePile(benchmark::State& state, Piece a, Piece b) {
  const std::vector<PosedPair> poses = pilePoses(a, b, 68);
  Manifold m;
  size_t i = 0;
  int64_t points = 0;
  for (auto _ : state) {
    points += collide(a.shape, poses[i].xa, b.shape, poses[i].xb, kMargin, m);
    benchmark::DoNotOptimize(m);
    if (++i == poses.size()) i = 0;
  }
  state.counters["points"] = benchmark::Counter(double(points), benchmark::Counter::kAvgIterations);
}

// Most pairs a pile's broad phase keeps are apart: their boxes overlap, the shapes are a little
// farther apart than the margin. The pile's poses moved kApartGap out from where they touch, each
// pose with its own manifold as each pair in the world has: `noted` keeps the face a pair routine
// noted as keeping it apart (Manifold::apartAxis) from one visit to the next, `fresh` forgets it.
constexpr float kApartGap = kMargin + 0.01f;
void collidePileApart(benchmark::State& state, Piece a, Piece b, bool noted) {
  const std::vector<PosedPair> poses = pilePoses(a, b, 68, -kApartGap);
  std::vector<Manifold> ms(poses.size());
  size_t i = 0;
  int64_t points = 0;
  for (auto _ : state) {
    if (!noted) ms[i].apartAxis = kNoApartAxis;
    points += collide(a.shape, poses[i].xa, b.shape, poses[i].xb, kMargin, ms[i]);
    benchmark::DoNotOptimize(ms[i]);
    if (++i == poses.size()) i = 0;
  }
  state.counters["points"] = benchmark::Counter(double(points), benchmark::Counter::kAvgIterations);
}

void registerAll() {
  const std::vector<Piece> ps = pieces();
  const Piece tri = meshTriangle();
  for (size_t i = 0; i < ps.size(); ++i) {
    for (size_t j = i; j < ps.size(); ++j)
      for (const Setting& s : kSettings)
        benchmark::RegisterBenchmark((ps[i].name + "-" + ps[j].name + "/" + s.name).c_str(), collidePair, ps[i], ps[j], s.gap);
  }
  for (const Piece& p : ps)
    for (const Setting& s : kSettings)
      benchmark::RegisterBenchmark((p.name + "-" + tri.name + "/" + s.name).c_str(), collideOnTriangle, p, tri, s.gap);
  for (size_t i = 0; i < ps.size(); ++i)
    for (size_t j = i; j < ps.size(); ++j)
      benchmark::RegisterBenchmark(("reach_bound/" + ps[i].name + "-" + ps[j].name).c_str(), reachPair, ps[i], ps[j], -0.001f);
  for (size_t i = 0; i < ps.size(); ++i)
    for (size_t j = i; j < ps.size(); ++j)
      benchmark::RegisterBenchmark(("pile/" + ps[i].name + "-" + ps[j].name).c_str(), collidePile, ps[i], ps[j]);
  for (size_t i = 0; i < ps.size(); ++i)
    for (size_t j = i; j < ps.size(); ++j)
      for (const bool noted : {false, true})
        benchmark::RegisterBenchmark(("pile_apart/" + ps[i].name + "-" + ps[j].name + (noted ? "/noted" : "/fresh")).c_str(),
                                     collidePileApart, ps[i], ps[j], noted);
}

}  // namespace
}  // namespace haif

int main(int argc, char** argv) {
  haif::registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
