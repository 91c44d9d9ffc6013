// What the engine simulates without NaN, checked by the scene loader (scene/scene_validate.cpp) and
// run at its corners by tests/dynamics/test_body_sizes.cpp and the joint mass-ratio tests.
#pragma once

namespace haif {

/// A moving body's longest edge (of its bounding box), m.
constexpr float kMinBodySize = 1e-3f, kMaxBodySize = 1e3f;
/// A dynamic body's mass, kg.
constexpr float kMinBodyMass = 1e-9f, kMaxBodyMass = 1e12f;
/// A moving body's start speed (m/s) and spin (rad/s): a bullet flies at 1000 m/s; at 1e20 m/s
/// kinetic energies overflow the engine's floats and every metric of the run turns NaN.
constexpr float kMaxBodySpeed = 1e4f, kMaxBodySpin = 1e4f;
/// Heavier over lighter mass of two dynamic bodies a joint joins: the joint tree's pivots fall with
/// it (dynamics/joint_tree.cpp); at 1:1e6 a swinging chain tore.
constexpr float kMaxJointMassRatio = 1e5f;

}  // namespace haif
