// A contact that exercises every term of a manifold's rows: two dynamic bodies with unequal,
// turned inertias touching on a tilted plane at four irregular points of different depths.
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"

namespace haif::test {

struct TiltedPatch {
  BodyStore bodies;  // body 0 (A) and body 1 (B)
  Contact contact;
  TiltedPatch() {
    Transform ta, tb;
    ta.p = Vec3(0.3f, -0.6f, 0.2f);
    ta.q = Quat(Eigen::AngleAxisf(0.7f, Vec3(1.0f, 2.0f, 0.5f).normalized()));
    tb.p = Vec3(-0.2f, 0.9f, 0.4f);
    tb.q = Quat(Eigen::AngleAxisf(-1.1f, Vec3(0.3f, 0.2f, 1.0f).normalized()));
    bodies.add(BodyKind::Dynamic, ta, 2.0f, Vec3(0.9f, 2.5f, 4.0f).asDiagonal());
    bodies.add(BodyKind::Dynamic, tb, 0.5f, Vec3(6.0f, 1.5f, 3.0f).asDiagonal());
    contact.a = 0;
    contact.b = 1;
    contact.friction = 0.5f;
    const Vec3 n = Vec3(0.2f, 1.0f, -0.3f).normalized();
    Vec3 u, w;
    orthonormalBasis(n, u, w);
    const float st[4][2] = {{-0.4f, -0.3f}, {0.6f, -0.2f}, {0.3f, 0.5f}, {-0.5f, 0.35f}};
    contact.manifold.count = 4;
    for (int i = 0; i < 4; ++i) {
      ContactPoint& p = contact.manifold.points[i];
      p.position = Vec3(0.05f, 0.1f, 0.3f) + st[i][0] * u + st[i][1] * w + 0.01f * float(i) * n;
      p.normal = n;
      p.depth = 0.002f * float(i);
      p.id = uint32_t(i);
    }
  }
};

}  // namespace haif::test
