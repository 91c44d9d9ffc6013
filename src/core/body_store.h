// Body storage: structure of arrays, indexed by body id (ids are dense and never reused within a World).
#pragma once

#include "core/math.h"

#include <cstdint>
#include <vector>

namespace haif {

enum class BodyKind : uint8_t { Static = 0, Kinematic, Dynamic };

struct BodyStore {
  // Hot state, touched every step.
  std::vector<Transform> xf;          ///< position = centre of mass, orientation
  std::vector<Vec3> v;                ///< linear velocity (m/s)
  std::vector<Vec3> w;                ///< angular velocity (rad/s, world)
  std::vector<float> invMass;         ///< 0 for static/kinematic
  std::vector<Mat3> inertiaLocal;     ///< body frame (kg m^2); zero for static/kinematic
  std::vector<Mat3> invInertiaLocal;  ///< body frame; zero for static/kinematic
  std::vector<Mat3> invInertiaWorld;  ///< refreshed after every position update
  std::vector<Vec3> force;            ///< user force accumulated for the next step (N)
  std::vector<Vec3> torque;           ///< user torque accumulated for the next step (N m)
  // Per-body parameters.
  std::vector<BodyKind> kind;
  std::vector<float> mass;
  std::vector<float> linearDamping, angularDamping;
  std::vector<float> friction, restitution;
  /// Rolling resistance coefficient, and the radius it acts at: a sphere's or capsule's (the shapes
  /// that roll), 0 for every other shape.
  std::vector<float> rollingResistance, rollingRadius;
  /// 1: the body was given a joint (World::addJoint): its gyroscopic term is integrated implicitly, and
  /// the turn projection never moves it (haif/turn_projection.h).
  std::vector<uint8_t> implicitGyro;
  /// 1: the body hangs from one fixed point by its only joint, a ball joint to the world or a static
  /// body (World::findPinnedBodies): it turns about that point (integratePinned), not about its centre.
  std::vector<uint8_t> pinned;
  // Sleep bookkeeping.
  std::vector<float> restTime;        ///< seconds the body has been slower than the sleep thresholds
  std::vector<uint8_t> asleep;
  std::vector<int32_t> sleepSet;      ///< while asleep: index of the sleeping island it belongs to

  size_t size() const { return xf.size(); }
  bool isDynamic(uint32_t i) const { return kind[i] == BodyKind::Dynamic; }
  /// Dynamic and awake: a body the solver moves (static, kinematic and sleeping ones it only reads).
  bool isAwakeDynamic(uint32_t i) const { return kind[i] == BodyKind::Dynamic && !asleep[i]; }
  /// Velocity of the material point of body i now at `point` (world frame).
  Vec3 velocityAt(uint32_t i, const Vec3& point) const { return v[i] + w[i].cross(point - xf[i].p); }

  /// Appends a body and returns its id.
  uint32_t add(BodyKind k, const Transform& t, float m, const Mat3& inertia) {
    const uint32_t id = static_cast<uint32_t>(xf.size());
    xf.push_back(t);
    v.push_back(Vec3::Zero());
    w.push_back(Vec3::Zero());
    const bool dyn = k == BodyKind::Dynamic;
    invMass.push_back(dyn && m > 0.0f ? 1.0f / m : 0.0f);
    inertiaLocal.push_back(dyn ? inertia : Mat3::Zero());
    // Inverted in double: the determinant of a float tensor under- or overflows for bodies below a
    // millimetre or above a kilometre (a 0.5 mm sphere's is 1e-40), and the inverse came out NaN.
    invInertiaLocal.push_back(dyn ? Mat3(inertia.cast<double>().inverse().cast<float>()) : Mat3::Zero());
    invInertiaWorld.push_back(Mat3::Zero());
    force.push_back(Vec3::Zero());
    torque.push_back(Vec3::Zero());
    kind.push_back(k);
    mass.push_back(dyn ? m : 0.0f);
    linearDamping.push_back(0.0f);
    angularDamping.push_back(0.0f);
    friction.push_back(0.6f);
    restitution.push_back(0.0f);
    rollingResistance.push_back(0.0f);
    rollingRadius.push_back(0.0f);
    implicitGyro.push_back(0);
    pinned.push_back(0);
    restTime.push_back(0.0f);
    asleep.push_back(0);
    sleepSet.push_back(-1);
    updateWorldInertia(id);
    return id;
  }

  void updateWorldInertia(uint32_t i) {
    const Mat3 R = xf[i].q.toRotationMatrix();
    invInertiaWorld[i] = R * invInertiaLocal[i] * R.transpose();
  }
};

}  // namespace haif
