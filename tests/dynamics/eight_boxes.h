// Eight boxes, each alone on the static ground (body 0) with its own manifold and motion: one of
// each branch a sweep can take. Shared by the tests of the wide and the paired sweeps.
#pragma once

#include "dynamics/contact_solver.h"

namespace haif::test {

struct EightBoxes {
  static constexpr int kBoxes = 8;
  BodyStore bodies;
  Contact contacts[kBoxes];
  EightBoxes() {
    bodies.add(BodyKind::Static, Transform{}, 0.0f, Mat3::Zero());
    const float corners[4][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
    // Per box: linear velocity, angular velocity, points, friction, restitution, depth.
    struct Case {
      Vec3 v, w;
      int points;
      float friction, restitution, depth;
    };
    const Case cases[kBoxes] = {
        {{0.0f, -0.1f, 0.0f}, {0.0f, 0.0f, 0.0f}, 4, 0.6f, 0.0f, 0.01f},     // resting, exact block
        {{0.1f, -2.0f, 0.0f}, {0.7f, 0.0f, -0.4f}, 4, 0.0f, 0.0f, 0.0f},     // tilted impact, exact
        {{0.0f, -0.5f, 0.0f}, {3.0f, 0.0f, 0.0f}, 4, 0.5f, 0.0f, 0.002f},    // lifting edge: passes
        {{4.0f, -0.2f, 1.0f}, {0.0f, 0.0f, 0.0f}, 4, 0.3f, 0.0f, 0.0f},      // sliding: friction circle
        {{0.0f, -0.3f, 0.0f}, {0.0f, 6.0f, 0.0f}, 4, 0.4f, 0.0f, 0.0f},      // spinning: twist limit
        {{0.0f, -3.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 4, 0.2f, 0.5f, 0.0f},      // bounce in relax sweeps
        {{0.2f, -1.0f, 0.0f}, {0.0f, 0.0f, 0.5f}, 2, 0.5f, 0.0f, -0.003f},   // two points, speculative
        {{0.0f, -1.0f, 0.3f}, {0.0f, 0.0f, 0.0f}, 1, 0.5f, 0.0f, 0.0f}};     // one point
    for (int l = 0; l < kBoxes; ++l) {
      Transform t;
      t.p = Vec3(3.0f * float(l), 0.5f, 0.0f);
      const uint32_t id = bodies.add(BodyKind::Dynamic, t, 1.0f + 0.25f * float(l), Mat3::Identity() * 0.2f);
      bodies.v[id] = cases[l].v;
      bodies.w[id] = cases[l].w;
      Contact& c = contacts[l];
      c.a = 0;
      c.b = id;
      c.friction = cases[l].friction;
      c.restitution = cases[l].restitution;
      c.manifold.count = cases[l].points;
      for (int i = 0; i < cases[l].points; ++i) {
        ContactPoint& p = c.manifold.points[i];
        p.position = t.p + Vec3(corners[i][0], -0.5f, corners[i][1]);
        p.normal = Vec3::UnitY();
        p.depth = cases[l].depth;
        p.id = uint32_t(i);
      }
    }
  }
  /// The rows of the first `lanes` contacts, from cold (no warm start unless `sp` says so).
  void prepare(ContactConstraint* cs, int lanes = kBoxes, SolverParams sp = coldParams()) const {
    for (int l = 0; l < lanes; ++l) prepareContact(bodies, contacts[l], uint32_t(l), sp, cs[l]);
  }
  static SolverParams coldParams() {
    SolverParams sp;
    sp.warmStart = false;
    return sp;
  }
};

}  // namespace haif::test
