#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace haif {

void prepareContact(const BodyStore& bodies, const Contact& contact, uint32_t ci, const SolverParams& p,
                    ContactConstraint& cc) {
  const uint32_t a = contact.a, b = contact.b;
  cc.a = a;
  cc.b = b;
  cc.contact = ci;
  cc.dynA = bodies.kind[a] == BodyKind::Dynamic && !bodies.asleep[a];
  cc.dynB = bodies.kind[b] == BodyKind::Dynamic && !bodies.asleep[b];
  cc.invMassA = cc.dynA ? bodies.invMass[a] : 0.0f;
  cc.invMassB = cc.dynB ? bodies.invMass[b] : 0.0f;
  const Mat3 iA = cc.dynA ? bodies.invInertiaWorld[a] : Mat3::Zero();
  const Mat3 iB = cc.dynB ? bodies.invInertiaWorld[b] : Mat3::Zero();
  cc.friction = contact.friction;
  cc.count = contact.manifold.count;

  const Vec3 pA = bodies.xf[a].p, pB = bodies.xf[b].p;
  const Vec3 vA = bodies.v[a], wA = bodies.w[a], vB = bodies.v[b], wB = bodies.w[b];
  const float invDt = 1.0f / p.dt;

  for (int i = 0; i < cc.count; ++i) {
    const ContactPoint& mp = contact.manifold.points[i];
    ContactConstraint::Point& cp = cc.points[i];
    // Each point carries its own normal (mesh contacts may differ per point).
    cp.normal = mp.normal;
    orthonormalBasis(cp.normal, cp.tangent1, cp.tangent2);
    const Vec3 n = cp.normal, t1 = cp.tangent1, t2 = cp.tangent2;
    const Vec3 rA = mp.position - pA;
    const Vec3 rB = mp.position - pB;
    auto row = [&](const Vec3& d, Vec3& rAx, Vec3& rBx, Vec3& iAx, Vec3& iBx) {
      rAx = rA.cross(d);
      rBx = rB.cross(d);
      iAx = iA * rAx;
      iBx = iB * rBx;
      const float k = cc.invMassA + cc.invMassB + rAx.dot(iAx) + rBx.dot(iBx);
      return k > 0.0f ? 1.0f / k : 0.0f;
    };
    cp.normalMass = row(n, cp.rAxn, cp.rBxn, cp.iAn, cp.iBn);
    cp.tangentMass1 = row(t1, cp.rAxt1, cp.rBxt1, cp.iAt1, cp.iBt1);
    cp.tangentMass2 = row(t2, cp.rAxt2, cp.rBxt2, cp.iAt2, cp.iBt2);

    // Velocity bias: close a speculative gap exactly, push out penetration beyond the slop
    // (Baumgarte), or bounce when approaching fast enough.
    const float vn = n.dot(vB - vA) + cp.rBxn.dot(wB) - cp.rAxn.dot(wA);
    // Main sweeps: close a speculative gap exactly, push penetration beyond the slop out (Baumgarte).
    // Relax sweeps (after positions moved): no push-out, so it does not become kinetic energy; a
    // contact that pushed this step and was approached fast enough bounces, from where it now is.
    const float speculative = mp.depth < 0.0f ? mp.depth * invDt : 0.0f;  // approach by the gap, no faster
    cp.bias = mp.depth < 0.0f ? -speculative : -p.beta * invDt * std::max(0.0f, mp.depth - p.slop);
    cp.relaxBias = -speculative;
    cp.restitutionBias = contact.restitution > 0.0f && vn < -p.restitutionThreshold ? contact.restitution * vn : 0.0f;

    if (p.warmStart) {
      cp.normalImpulse = contact.normalImpulse[i];
      cp.tangentImpulse1 = contact.frictionImpulse[i].dot(t1);
      cp.tangentImpulse2 = contact.frictionImpulse[i].dot(t2);
    } else {
      cp.normalImpulse = cp.tangentImpulse1 = cp.tangentImpulse2 = 0.0f;
    }
  }
}

namespace {

inline void apply(BodyStore& bodies, const ContactConstraint& c, const Vec3& P, const Vec3& angA,
                  const Vec3& angB, float lambda) {
  if (c.dynA) {
    bodies.v[c.a] -= (c.invMassA * lambda) * P;
    bodies.w[c.a] -= lambda * angA;
  }
  if (c.dynB) {
    bodies.v[c.b] += (c.invMassB * lambda) * P;
    bodies.w[c.b] += lambda * angB;
  }
}

}  // namespace

void warmStart(BodyStore& bodies, const ContactConstraint* cs, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    const ContactConstraint& c = cs[k];
    for (int i = 0; i < c.count; ++i) {
      const ContactConstraint::Point& p = c.points[i];
      const Vec3 P = p.normalImpulse * p.normal + p.tangentImpulse1 * p.tangent1 + p.tangentImpulse2 * p.tangent2;
      const Vec3 angA = p.normalImpulse * p.iAn + p.tangentImpulse1 * p.iAt1 + p.tangentImpulse2 * p.iAt2;
      const Vec3 angB = p.normalImpulse * p.iBn + p.tangentImpulse1 * p.iBt1 + p.tangentImpulse2 * p.iBt2;
      apply(bodies, c, P, angA, angB, 1.0f);
    }
  }
}

float solveIteration(BodyStore& bodies, ContactConstraint* cs, size_t n, float omega, bool useBias) {
  float residual = 0.0f;
  for (size_t k = 0; k < n; ++k) {
    ContactConstraint& c = cs[k];
    // Static and kinematic bodies are read (their velocity is given) but never written, so
    // islands that share a static body can be solved concurrently.
    Vec3 va = bodies.v[c.a], wa = bodies.w[c.a], vb = bodies.v[c.b], wb = bodies.w[c.b];
    const float mA = c.invMassA, mB = c.invMassB;

    // Friction first, bounded by the normal impulses of the previous sweep.
    for (int i = 0; i < c.count; ++i) {
      ContactConstraint::Point& p = c.points[i];
      // Both tangent rows together, clamped to the friction circle |λt| <= μ λn: clamping each axis
      // alone (a box) lets friction reach √2 μ λn and pushes a sliding body sideways.
      const float limit = c.friction * p.normalImpulse;
      const Vec3 dv = vb - va;
      const float vt1 = p.tangent1.dot(dv) + p.rBxt1.dot(wb) - p.rAxt1.dot(wa);
      const float vt2 = p.tangent2.dot(dv) + p.rBxt2.dot(wb) - p.rAxt2.dot(wa);
      const float old1 = p.tangentImpulse1, old2 = p.tangentImpulse2;
      float n1 = old1 - omega * p.tangentMass1 * vt1;
      float n2 = old2 - omega * p.tangentMass2 * vt2;
      const float len2 = n1 * n1 + n2 * n2;
      if (len2 > limit * limit) {
        const float scale = len2 > 0.0f ? limit / std::sqrt(len2) : 0.0f;
        n1 *= scale;
        n2 *= scale;
      }
      p.tangentImpulse1 = n1;
      p.tangentImpulse2 = n2;
      const float a1 = n1 - old1, a2 = n2 - old2;
      const Vec3 P = a1 * p.tangent1 + a2 * p.tangent2;
      va -= mA * P;
      wa -= a1 * p.iAt1 + a2 * p.iAt2;
      vb += mB * P;
      wb += a1 * p.iBt1 + a2 * p.iBt2;
    }
    // Normal rows last: non-penetration matters more than friction, so each sweep ends with the
    // normal rows satisfied (friction last left tilting torques that rocked stacks apart).
    for (int i = 0; i < c.count; ++i) {
      ContactConstraint::Point& p = c.points[i];
      const float vn = p.normal.dot(vb - va) + p.rBxn.dot(wb) - p.rAxn.dot(wa);
      const float b = useBias ? p.bias : (p.restitutionBias < 0.0f && p.normalImpulse > 0.0f ? p.restitutionBias : p.relaxBias);
      const float dl = -omega * p.normalMass * (vn + b);
      const float old = p.normalImpulse;
      p.normalImpulse = std::max(0.0f, old + dl);
      const float applied = p.normalImpulse - old;
      va -= (mA * applied) * p.normal;
      wa -= applied * p.iAn;
      vb += (mB * applied) * p.normal;
      wb += applied * p.iBn;
      if (p.normalMass > 0.0f) residual = std::max(residual, std::fabs(applied) / p.normalMass);
    }
    if (c.dynA) {
      bodies.v[c.a] = va;
      bodies.w[c.a] = wa;
    }
    if (c.dynB) {
      bodies.v[c.b] = vb;
      bodies.w[c.b] = wb;
    }
  }
  return residual;
}

void storeImpulses(const ContactConstraint* cs, size_t n, Contact* contacts) {
  for (size_t k = 0; k < n; ++k) {
    const ContactConstraint& c = cs[k];
    Contact& ct = contacts[c.contact];
    for (int i = 0; i < c.count; ++i) {
      ct.normalImpulse[i] = c.points[i].normalImpulse;
      const ContactConstraint::Point& p = c.points[i];
      ct.frictionImpulse[i] = p.tangentImpulse1 * p.tangent1 + p.tangentImpulse2 * p.tangent2;
    }
  }
}

}  // namespace haif
