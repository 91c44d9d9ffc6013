// Jointed scenes shared by the joint tests.
#pragma once

#include "haif/world.h"

#include <gtest/gtest.h>

#include <vector>

namespace haif::test {

inline Transform bodyXf(const World& w, uint32_t b) { return b == kWorldBody ? Transform{} : w.bodies().xf[b]; }

/// A joint placed at world `anchor` with world `axis`, from the bodies' current poses.
inline uint32_t addJointAt(World& w, JointType type, uint32_t a, uint32_t b, const Vec3& anchor,
                           const Vec3& axis = Vec3::UnitX(), const Vec3& anchorB = Vec3::Zero()) {
  return w.addJoint(jointAtWorld(type, a, b, bodyXf(w, a), bodyXf(w, b), anchor, axis, anchorB));
}

/// The chain_heavy layout: `links` capsule links of 1 kg and length 0.5 m along +x from a pivot at
/// `pivot`, pinned to the world there by a ball joint, and a sphere of `endMass` kg at the far end.
/// Returns the ids of the joints.
inline std::vector<uint32_t> addHeavyChain(World& w, const Vec3& pivot, int links = 30, float endMass = 100.0f,
                                           bool horizontal = true) {
  const float len = 0.5f, radius = 0.08f, ballRadius = 0.5f;
  const Vec3 dir = horizontal ? Vec3::UnitX() : Vec3(-Vec3::UnitY());
  const Quat q = Quat::FromTwoVectors(Vec3::UnitY(), dir);
  std::vector<uint32_t> joints;
  uint32_t prev = kWorldBody;
  for (int i = 0; i < links; ++i) {
    BodyDef d;
    d.shape = Shape::capsule(radius, 0.5f * len - radius);
    d.xf.p = pivot + (len * (float(i) + 0.5f)) * dir;
    d.xf.q = q;
    d.mass = 1.0f;
    const uint32_t id = w.addBody(d);
    joints.push_back(addJointAt(w, JointType::Ball, prev, id, pivot + (len * float(i)) * dir));
    prev = id;
  }
  BodyDef d;
  d.shape = Shape::sphere(ballRadius);
  d.xf.p = pivot + (len * float(links) + ballRadius) * dir;
  d.mass = endMass;
  const uint32_t ball = w.addBody(d);
  joints.push_back(addJointAt(w, JointType::Ball, prev, ball, pivot + (len * float(links)) * dir));
  return joints;
}

/// Largest anchor (m) and angular (rad) error over all joints now.
inline JointError worstJointError(const World& w) {
  JointError worst;
  for (uint32_t j = 0; j < w.jointCount(); ++j) {
    const JointError e = w.jointError(j);
    worst.linear = std::max(worst.linear, e.linear);
    worst.angular = std::max(worst.angular, e.angular);
  }
  return worst;
}

}  // namespace haif::test
