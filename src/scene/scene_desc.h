// Plain description of a scene, as read from a JSON scene file (generators already expanded).
// The loader fills it and validates it; buildWorld() (scene/build_world.h) turns it into a World.
#pragma once

#include "collision/shape.h"
#include "core/math.h"
#include "dynamics/joint.h"
#include "haif/world_settings.h"
#include "scene/stress_desc.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

enum class MotionType : uint8_t { Static = 0, Kinematic, Dynamic };

struct MaterialDesc {
  std::string name = "default";
  float friction = 0.6f;
  float restitution = 0.0f;
  float rollingResistance = 0.0f;  ///< ≥ 0; see BodyDef::rollingResistance
  float density = 1000.0f;  ///< kg/m^3, used when a body gives no mass
};

struct CompoundPartDesc;

struct ShapeDesc {
  ShapeType type = ShapeType::Box;
  Vec3 halfExtents = Vec3::Constant(0.5f);  ///< box
  float radius = 0.5f;                      ///< sphere, capsule
  float halfHeight = 0.5f;                  ///< capsule
  Vec3 planeNormal = Vec3::UnitY();         ///< plane
  float planeOffset = 0.0f;
  std::vector<Vec3> points;                 ///< convex hull: input points (body frame)
  std::vector<Vec3> meshVertices;           ///< triangle mesh (inline or loaded from an asset)
  std::vector<uint32_t> meshIndices;
  std::string asset;                        ///< asset path as written in the scene file (empty: none)
  Vec3 assetScale = Vec3::Ones();
  std::vector<CompoundPartDesc> parts;      ///< compound: its parts (sphere, box, capsule or hull)
};

/// One part of a compound shape, placed in the body's frame (as the scene file places the body).
struct CompoundPartDesc {
  ShapeDesc shape;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  bool draw = true;  ///< false: collides but is not drawn (the glass front of a drum, to see inside)
};

/// A mesh drawn in place of a body's collision shape (the body still collides as its shape).
struct RenderMeshDesc {
  std::string asset;             ///< as written in the scene file; empty: draw the collision shape
  Vec3 scale = Vec3::Ones();
  std::vector<Vec3> vertices;    ///< body frame (the scene body's position and orientation)
  std::vector<uint32_t> indices;
};

struct BodyDesc {
  std::string name;
  MotionType motion = MotionType::Dynamic;
  ShapeDesc shape;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 linearVelocity = Vec3::Zero();   ///< initial (dynamic) or constant (kinematic) velocity
  Vec3 angularVelocity = Vec3::Zero();
  float mass = 0.0f;                    ///< > 0: given mass; 0: from material density
  uint32_t material = 0;                ///< index into SceneDesc::materials
  float linearDamping = 0.0f;           ///< 1/s
  float angularDamping = 0.0f;          ///< 1/s
  RenderMeshDesc renderMesh;
  std::string where;                    ///< place in the scene file, e.g. "bodies[3]" or "generators[1] box 17"
};

/// A box-shaped volume of water: buoyancy and drag act on the submerged part of dynamic bodies.
struct WaterDesc {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  ///< world AABB of the volume (surface at hi.y)
  float density = 1000.0f;
  float linearDrag = 1.0f;   ///< 1/s, scaled by submerged fraction
  float angularDrag = 0.5f;  ///< 1/s
};

/// A joint as the scene file gives it. The joint's rest pose is the bodies' initial pose: fixed and
/// slider joints keep the relative orientation they start with, hinge and twist angles count from it.
struct JointDesc {
  std::string name;
  int32_t bodyA = -1, bodyB = -1;  ///< index into SceneDesc::bodies; -1: the world
  bool localAnchors = false;       ///< false: world points; true: points in each body's frame (scene body origin)
  Vec3 anchorA = Vec3::Zero();     ///< where the joint sits on A (and on B unless anchorB differs: distance joints)
  Vec3 anchorB = Vec3::Zero();
  bool localAxis = false;          ///< false: world direction; true: in body A's frame
  Vec3 axis = Vec3::UnitX();       ///< hinge axis, slider direction, cone-twist twist axis
  /// Type, limits, motor, servo, break thresholds and collideConnected; bodies, anchors and frames are
  /// filled when the World is built. A negative min/max distance stands for the initial anchor distance.
  JointDef params;
  std::string where;               ///< place in the scene file, e.g. "joints[3]"
};

/// The scene file's "settings": the World's own settings (haif/world_settings.h), which the file sets
/// a part of, and how many steps `haif run` takes.
struct SimSettings {
  WorldSettings world;
  int frames = 300;  ///< default number of steps for `haif run`
};

struct CameraDesc {
  bool given = false;  ///< false: frame the scene automatically
  Vec3 eye = Vec3(10.0f, 8.0f, 10.0f);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3::UnitY();
  float fovYDeg = 45.0f;
};

struct SceneDesc {
  std::string name;        ///< scene name (file stem unless the file says otherwise)
  std::string sourcePath;  ///< file it was read from
  /// FNV-1a of the file's bytes: a run records it, and replaying the run's log checks it (a log
  /// of another scene, or of an edited one, would replay iteration counts that mean nothing).
  uint64_t sourceHash = 0;
  SimSettings settings;
  std::vector<MaterialDesc> materials;  ///< materials[0] always exists ("default")
  std::vector<BodyDesc> bodies;
  std::vector<WaterDesc> water;
  std::vector<JointDesc> joints;
  CameraDesc camera;
  StressDesc stress;  ///< for `haif stress` only (docs/stress.md)
};

}  // namespace haif
