// HAIF shapes as Bullet collision shapes, with the same geometry: Bullet's collision margin must
// not make a shape bigger than HAIF's, or every contact would sit a margin apart.
#pragma once

#include "collision/shape.h"

#include <memory>
#include <string>
#include <vector>

class btCollisionShape;
class btTriangleMesh;

namespace haif {

/// Owns the Bullet shapes (and triangle data) of one Bullet world.
class BulletShapeStore {
 public:
  BulletShapeStore();
  ~BulletShapeStore();
  BulletShapeStore(const BulletShapeStore&) = delete;
  BulletShapeStore& operator=(const BulletShapeStore&) = delete;

  /// A Bullet shape equal to `shape` expressed in a frame rotated by `frame` (a body's principal
  /// axes: x_body = frame · x_shape). Null with `error` set when Bullet cannot express it.
  btCollisionShape* add(const Shape& shape, const Quat& frame, std::string& error);

 private:
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
};

}  // namespace haif
