// Small random worlds for the randomized stress test: random shapes (sphere, box, capsule, convex
// hull, and compounds of them when asked), sizes, masses, velocities and overlaps above a ground box. Everything comes from one
// std::mt19937 seeded with the world's seed, so a failing world is reproduced from its seed alone.
#pragma once

#include "collision/compound.h"
#include "collision/convex_hull.h"
#include "dynamics/joint.h"
#include "haif/world.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace haif::test {

/// What the checks need to know about a random world besides the World itself.
struct RandomWorld {
  std::unique_ptr<World> world;
  std::string description;      ///< one line per body, for failure messages
  double maxStartSpeed = 0.0;   ///< m/s, fastest body at the start (angular motion of its extent included)
  double maxStartHeight = 0.0;  ///< m, highest centre
  double maxRadius = 0.0;       ///< m, largest bounding radius
  double overlapAllowance = 0.0;  ///< J: energy pushing bodies out of their initial overlaps may add
  double kinematicSpeed = 0.0;    ///< m/s, fastest point of a kinematic mover (0: none)
};

inline float uniform(std::mt19937& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}
/// Log-uniform: sizes and masses spread evenly over orders of magnitude.
inline float logUniform(std::mt19937& rng, float lo, float hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

inline Vec3 randomUnit(std::mt19937& rng) {
  for (;;) {
    const Vec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    const float n = v.norm();
    if (n > 0.1f && n <= 1.0f) return v / n;
  }
}

inline Quat randomRotation(std::mt19937& rng) {
  Quat q(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  if (q.norm() < 1e-3f) return Quat::Identity();
  q.normalize();
  return q;
}

/// What a random world holds besides the ground and its free bodies.
struct RandomWorldKinds {
  bool joints = false;     ///< ball and hinge joints: chains, loops (a closed ring, a body joined twice)
  bool kinematic = false;  ///< a kinematic paddle sweeping through the bodies
  bool compounds = false;  ///< some bodies are compounds of 2 to 4 parts (spheres, boxes, capsules)
};

/// A random world: ground, 2 to 12 bodies in a 3 m x 3 m x 3 m region (so many start overlapping),
/// sizes 0.05 to 1.5 m, masses 0.1 to 100 kg (ratios to 1:1000), speeds up to 10 m/s and 10 rad/s.
inline RandomWorld makeRandomWorld(uint32_t seed, RandomWorldKinds kinds = {}) {
  std::mt19937 rng(seed);
  RandomWorld rw;
  WorldSettings ws;  // defaults: 60 Hz, 10 iterations, fixed mode
  rw.world = std::make_unique<World>(ws);
  World& w = *rw.world;
  BodyDef ground;
  ground.kind = BodyKind::Static;
  ground.shape = Shape::box(Vec3(500.0f, 1.0f, 500.0f));
  ground.xf.p = Vec3(0.0f, -1.0f, 0.0f);
  w.addBody(ground);

  const int count = std::uniform_int_distribution<int>(2, 12)(rng);
  const char* names[] = {"sphere", "box", "capsule", "hull", "compound"};
  std::vector<uint32_t> ids;
  for (int k = 0; k < count; ++k) {
    BodyDef d;
    const int type = std::uniform_int_distribution<int>(0, kinds.compounds ? 4 : 3)(rng);
    const float size = logUniform(rng, 0.05f, 1.5f);  // bounding radius
    float radius = size;
    switch (type) {
      case 0: d.shape = Shape::sphere(size); break;
      case 1: {
        const Vec3 h = size * Vec3(uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f));
        d.shape = Shape::box(h);
        radius = h.norm();
        break;
      }
      case 2: {
        const float r = size * uniform(rng, 0.2f, 1.0f), hh = size * uniform(rng, 0.0f, 1.0f);
        d.shape = Shape::capsule(r, hh);
        radius = r + hh;
        break;
      }
      case 4: {
        // 2 to 4 parts within the bounding radius, at random poses: bars, dumbbells, odd clusters.
        const int n = std::uniform_int_distribution<int>(2, 4)(rng);
        std::vector<Shape> parts;
        std::vector<Transform> poses;
        radius = 0.0f;
        for (int i = 0; i < n; ++i) {
          const float part = size * uniform(rng, 0.2f, 0.5f);
          const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
          parts.push_back(kind == 0   ? Shape::sphere(part)
                          : kind == 1 ? Shape::box(part * Vec3(uniform(rng, 0.3f, 1.0f), uniform(rng, 0.3f, 1.0f), 1.0f))
                                      : Shape::capsule(0.4f * part, part));
          poses.push_back(Transform{randomUnit(rng) * (size - 2.0f * part) * uniform(rng, 0.0f, 1.0f), randomRotation(rng)});
          radius = std::max(radius, poses.back().p.norm() + 2.0f * part);
        }
        auto c = buildCompound(parts, poses, nullptr);
        d.shape = Shape::compoundOf(std::move(c));
        radius *= 2.0f;  // the centre of mass moves from the origin the parts were placed about
        break;
      }
      default: {
        // 6 to 16 points on a random ellipsoid: flat, long and irregular hulls alike.
        const Vec3 axes = size * Vec3(uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f));
        const int n = std::uniform_int_distribution<int>(6, 16)(rng);
        std::vector<Vec3> pts;
        for (int i = 0; i < n; ++i) pts.push_back(randomUnit(rng).cwiseProduct(axes));
        auto hull = buildConvexHull(pts, nullptr);
        if (!hull) {  // a degenerate draw: use a box of the same size instead
          d.shape = Shape::box(axes);
          radius = axes.norm();
          break;
        }
        radius = 0.0f;
        for (const Vec3& p : pts) radius = std::max(radius, (p - hull->centroid).norm());
        d.shape = Shape::convexHull(std::move(hull));
        break;
      }
    }
    d.xf.p = Vec3(uniform(rng, -1.5f, 1.5f), uniform(rng, 0.0f, 3.0f) + std::min(radius, 1.0f) * 0.5f,
                  uniform(rng, -1.5f, 1.5f));
    d.xf.q = randomRotation(rng);
    d.mass = logUniform(rng, 0.1f, 100.0f);
    d.linearVelocity = randomUnit(rng) * uniform(rng, 0.0f, 10.0f);
    d.angularVelocity = randomUnit(rng) * uniform(rng, 0.0f, 10.0f);
    d.friction = uniform(rng, 0.0f, 1.0f);
    d.restitution = uniform(rng, 0.0f, 1.0f) < 0.7f ? 0.0f : uniform(rng, 0.0f, 0.8f);
    ids.push_back(w.addBody(d));

    rw.maxStartSpeed = std::max(rw.maxStartSpeed, double(d.linearVelocity.norm() + d.angularVelocity.norm() * radius));
    rw.maxStartHeight = std::max(rw.maxStartHeight, double(d.xf.p.y()));
    rw.maxRadius = std::max(rw.maxRadius, double(radius));
    // Pushed out of an overlap, a body may rise by its own size and keep a little push-out speed.
    rw.overlapAllowance += d.mass * (9.81 * 2.0 * radius + 0.5 * 1.0 * 1.0);
    char line[256];
    std::snprintf(line, sizeof line,
                  "  %s r=%.3f m=%.3f p=(%.2f %.2f %.2f) v=(%.2f %.2f %.2f) w=(%.2f %.2f %.2f) mu=%.2f e=%.2f\n",
                  names[type], radius, d.mass, d.xf.p.x(), d.xf.p.y(), d.xf.p.z(), d.linearVelocity.x(),
                  d.linearVelocity.y(), d.linearVelocity.z(), d.angularVelocity.x(), d.angularVelocity.y(),
                  d.angularVelocity.z(), d.friction, d.restitution);
    rw.description += line;
  }

  if (kinds.joints) {
    // A chain through the bodies in order, closed into a ring half the time, one extra joint across it
    // (a loop), and the first body pinned to the world a third of the time. Anchors at the midpoint of
    // the two centres: the joints start satisfied, the bodies start far from the anchors.
    auto join = [&](uint32_t a, uint32_t b, const Vec3& anchor) {
      const bool hinge = uniform(rng, 0.0f, 1.0f) < 0.3f;
      const Transform xa = a == kWorldBody ? Transform{} : w.bodies().xf[a], xb = w.bodies().xf[b];
      w.addJoint(jointAtWorld(hinge ? JointType::Hinge : JointType::Ball, a, b, xa, xb, anchor, randomUnit(rng), Vec3::Zero()));
      char line[128];
      std::snprintf(line, sizeof line, "  %s joint %d-%d\n", hinge ? "hinge" : "ball", a == kWorldBody ? -1 : int(a),
                    int(b));
      rw.description += line;
    };
    auto mid = [&](uint32_t a, uint32_t b) -> Vec3 { return 0.5f * (w.bodies().xf[a].p + w.bodies().xf[b].p); };
    for (size_t i = 1; i < ids.size(); ++i) join(ids[i - 1], ids[i], mid(ids[i - 1], ids[i]));
    if (ids.size() >= 3 && uniform(rng, 0.0f, 1.0f) < 0.5f) join(ids.back(), ids.front(), mid(ids.back(), ids.front()));
    if (ids.size() >= 4) join(ids[0], ids[2], mid(ids[0], ids[2]));
    if (uniform(rng, 0.0f, 1.0f) < 0.33f) join(kWorldBody, ids[0], w.bodies().xf[ids[0]].p + Vec3(0.0f, 0.5f, 0.0f));
  }
  if (kinds.kinematic) {
    // A paddle turning about y through the region, or sliding across it.
    BodyDef k;
    k.kind = BodyKind::Kinematic;
    const Vec3 h(uniform(rng, 0.5f, 2.0f), uniform(rng, 0.1f, 0.5f), uniform(rng, 0.1f, 0.5f));
    k.shape = Shape::box(h);
    k.xf.p = Vec3(0.0f, uniform(rng, 0.2f, 1.5f), 0.0f);
    if (uniform(rng, 0.0f, 1.0f) < 0.5f) {
      k.angularVelocity = Vec3(0.0f, uniform(rng, 0.5f, 4.0f), 0.0f);
      rw.kinematicSpeed = double(k.angularVelocity.norm() * h.norm());
    } else {
      k.xf.p.x() = -3.0f;
      k.linearVelocity = Vec3(uniform(rng, 0.5f, 5.0f), 0.0f, 0.0f);
      rw.kinematicSpeed = double(k.linearVelocity.norm());
    }
    w.addBody(k);
    char line[128];
    std::snprintf(line, sizeof line, "  kinematic paddle half=(%.2f %.2f %.2f) speed %.2f m/s\n", h.x(), h.y(), h.z(),
                  rw.kinematicSpeed);
    rw.description += line;
  }
  return rw;
}

}  // namespace haif::test
