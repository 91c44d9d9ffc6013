// Small scene builders shared by the physics tests (dynamics, haif).
#pragma once

#include "haif/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace haif::test {

/// The reference ground of docs/reference_scenes.md: static box half (500, 1, 500) centred at y = -1 (top at y = 0).
inline uint32_t addGround(World& w, float friction = 0.6f, float restitution = 0.0f) {
  BodyDef d;
  d.kind = BodyKind::Static;
  d.shape = Shape::box(Vec3(500.0f, 1.0f, 500.0f));
  d.xf.p = Vec3(0.0f, -1.0f, 0.0f);
  d.friction = friction;
  d.restitution = restitution;
  return w.addBody(d);
}

/// A static ramp (box half (10, 0.5, 3), centre at y = 10) tilted by thetaDeg about z: its
/// orientation, its up and uphill directions and its centre.
struct Ramp {
  Quat q;
  Vec3 up, uphill, centre;
  /// Where a body's centre sits `height` above the top face, 4 m uphill of the middle.
  Vec3 restingPlace(float height) const { return centre + up * (0.5f + height) + uphill * 4.0f; }
};

inline Ramp addRamp(World& w, float thetaDeg, float friction = 0.6f) {
  const float th = thetaDeg * kPi / 180.0f;
  Ramp r;
  r.q = Quat(Eigen::AngleAxisf(th, Vec3::UnitZ()));
  r.up = r.q * Vec3::UnitY();
  r.uphill = r.q * Vec3::UnitX();
  BodyDef d;
  d.kind = BodyKind::Static;
  d.shape = Shape::box(Vec3(10.0f, 0.5f, 3.0f));
  d.xf.p = Vec3(0.0f, 10.0f, 0.0f);
  d.xf.q = r.q;
  d.friction = friction;
  w.addBody(d);
  r.centre = d.xf.p;
  return r;
}

inline uint32_t addBox(World& w, const Vec3& p, const Vec3& half = Vec3::Constant(0.5f), float mass = 1.0f,
                       const Quat& q = Quat::Identity()) {
  BodyDef d;
  d.shape = Shape::box(half);
  d.xf.p = p;
  d.xf.q = q;
  d.mass = mass;
  return w.addBody(d);
}

/// A static box of half extents `half` at p.
inline uint32_t addStaticBox(World& w, const Vec3& p, const Vec3& half) {
  BodyDef d;
  d.kind = BodyKind::Static;
  d.shape = Shape::box(half);
  d.xf.p = p;
  return w.addBody(d);
}

/// A kinematic box of half extents `half` at p, moving at `velocity` and turning at `spin` (rad/s).
inline uint32_t addKinematicBox(World& w, const Vec3& p, const Vec3& half, const Vec3& velocity,
                                const Vec3& spin = Vec3::Zero()) {
  BodyDef d;
  d.kind = BodyKind::Kinematic;
  d.shape = Shape::box(half);
  d.xf.p = p;
  d.linearVelocity = velocity;
  d.angularVelocity = spin;
  return w.addBody(d);
}

inline uint32_t addSphere(World& w, const Vec3& p, float r = 0.5f, float mass = 1.0f) {
  BodyDef d;
  d.shape = Shape::sphere(r);
  d.xf.p = p;
  d.mass = mass;
  return w.addBody(d);
}

/// A column of `count` unit boxes (mass 1) on the ground at (x, z), box h at y = 0.5 + pitch·h
/// (pitch 1: touching; the reference stacks of docs/reference_scenes.md use 1.01). Returns the box ids, bottom first.
inline std::vector<uint32_t> addColumn(World& w, int count, float x = 0.0f, float z = 0.0f, float pitch = 1.0f) {
  std::vector<uint32_t> ids;
  for (int h = 0; h < count; ++h) ids.push_back(addBox(w, Vec3(x, 0.5f + pitch * float(h), z)));
  return ids;
}

/// A 20 t iron ball (r 1.2 m, friction 0.4, restitution 0.1) 1 m above a bed of bricks of 250 kg
/// (1 × 0.5 × 0.5 m), 5 × 8 in `layers` layers (80 bricks in two), 3 cm apart along x, 2 cm along
/// z, 1 cm between the layers, on the ground: a heavy body among light ones (a ratio of 80), as in
/// tower_collapse.
struct BallOnBrickBed {
  uint32_t ball = 0;
  std::vector<uint32_t> bricks;
};
inline BallOnBrickBed addBallOnBrickBed(World& w, const Vec3& ballVelocity = Vec3::Zero(), int layers = 2) {
  BallOnBrickBed s;
  addGround(w);
  for (int i = 0; i < 5; ++i)
    for (int layer = 0; layer < layers; ++layer)
      for (int k = 0; k < 8; ++k)
        s.bricks.push_back(addBox(w, Vec3(-2.06f + 1.03f * float(i), 0.25f + 0.51f * float(layer), -1.82f + 0.52f * float(k)),
                                  Vec3(0.5f, 0.25f, 0.25f), 250.0f));
  BodyDef d;
  d.shape = Shape::sphere(1.2f);
  d.xf.p = Vec3(0.3f, 0.51f * float(layers) + 2.18f, 0.2f);  // 1 m above the top layer
  d.linearVelocity = ballVelocity;
  d.mass = 20000.0f;
  d.friction = 0.4f;
  d.restitution = 0.1f;
  s.ball = w.addBody(d);
  return s;
}

/// The 2D pyramid of docs/reference_scenes.md (large_pyramid) with `base` boxes in the bottom row, centred on x = 0.
/// Ground and a 10-box column with 1 cm gaps between the boxes, as in stacks_N: the boxes land on
/// each other during the first steps.
inline void addGappedColumn(World& w) {
  addGround(w);
  addColumn(w, 10, 0.0f, 0.0f, 1.01f);
}

/// Steps a gapped column `steps` times at a fixed iteration count, the solve error measured every
/// step, calling f(world, step) after each.
template <class F>
void stepGappedColumn(int iterations, bool chainSolve, int steps, F&& f) {
  WorldSettings ws;
  ws.iterations = iterations;
  ws.chainSolve = chainSolve;
  World w(ws);
  addGappedColumn(w);
  w.setSolveErrorInterval(1);
  for (int s = 0; s < steps; ++s) {
    w.step();
    f(w, s);
  }
}

/// run(threads) returns a state hash; it must be the same on 1, 2 and 4 threads.
template <class Run>
void expectSameStateForThreadCounts(Run run) {
  const uint64_t one = run(1);
  EXPECT_EQ(run(2), one) << "2 threads";
  EXPECT_EQ(run(4), one) << "4 threads";
}

inline void addPyramid2d(World& w, int base) {
  for (int i = 0; i < base; ++i)
    for (int j = i; j < base; ++j) addBox(w, Vec3(0.5f * float(i + 1) + float(j - i) - 0.5f * float(base), 0.5f + float(i), 0.0f));
}

/// Deepest penetration (m) over the current contact points (speculative points have depth < 0).
inline float maxContactDepth(const World& w) {
  float deepest = 0.0f;
  for (const Contact& c : w.contacts())
    for (int i = 0; i < c.manifold.count; ++i) deepest = std::max(deepest, c.manifold.points[i].depth);
  return deepest;
}

/// World angular momentum about the centre of mass: L = R I_local R^T w.
inline Eigen::Vector3d angularMomentum(const World& w, uint32_t i) {
  const BodyStore& b = w.bodies();
  const Eigen::Matrix3d R = b.xf[i].q.toRotationMatrix().cast<double>();
  return R * b.inertiaLocal[i].cast<double>() * R.transpose() * b.w[i].cast<double>();
}

inline Eigen::Vector3d linearMomentum(const World& w) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  const BodyStore& b = w.bodies();
  for (uint32_t i = 0; i < w.bodyCount(); ++i)
    if (b.isDynamic(i)) p += double(b.mass[i]) * b.v[i].cast<double>();
  return p;
}

}  // namespace haif::test
