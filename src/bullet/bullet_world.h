// The Bullet 3 baseline: a scene file's bodies in a btDiscreteDynamicsWorld set up like HAIF's world
// (same time step, gravity, iteration count, Baumgarte factor, slop, friction and restitution
// combine, mass and inertia, no sleeping unless the scene asks), stepped on one thread.
// This is the only code that includes Bullet's headers; they stay behind a pointer to the inside.
#pragma once

#include "core/math.h"
#include "scene/scene_desc.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace haif {

/// One contact point of Bullet's last collision pass, between bodies a and b (scene order).
struct BulletContactPoint {
  uint32_t a = 0, b = 0;
  float depth = 0.0f;  ///< penetration (m), -distance of the point; <= 0: separated
};

class BulletWorld {
 public:
  BulletWorld();
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  /// Builds the world from a loaded scene. `iterations` <= 0: the scene's count. One error line
  /// naming the scene file and body when something cannot be expressed in Bullet (e.g. water).
  bool build(const SceneDesc& scene, int iterations, std::string& error);

  /// One step of scene.settings.dt, as one Bullet substep.
  void step();

  int iterations() const;
  uint32_t bodyCount() const;
  bool isDynamic(uint32_t body) const;
  /// Pose of the body's centre of mass in HAIF's body frame (the frame of the scene's shapes).
  Transform pose(uint32_t body) const;
  Vec3 linearVelocity(uint32_t body) const;
  Vec3 angularVelocity(uint32_t body) const;
  /// Smallest extent of the body's shape (m), as HAIF measures it (1e30 for planes and meshes).
  float smallestExtent(uint32_t body) const;
  /// Contact points of every manifold of the last collision pass (reuses `out`'s storage).
  void readContactPoints(std::vector<BulletContactPoint>& out) const;

  /// The friction and restitution Bullet used at the first contact point between two bodies in the
  /// last collision pass (NaN when they do not touch): tests check the combine rules with these.
  float combinedFriction(uint32_t a, uint32_t b) const;
  float combinedRestitution(uint32_t a, uint32_t b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace haif
