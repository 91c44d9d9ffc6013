#include "dynamics/joint_solver.h"

#include "dynamics/joint_tree.h"

#include <algorithm>
#include <cmath>

namespace haif {

const char* jointTypeName(JointType t) {
  switch (t) {
    case JointType::Ball: return "ball";
    case JointType::Hinge: return "hinge";
    case JointType::Fixed: return "fixed";
    case JointType::Distance: return "distance";
    case JointType::Slider: return "slider";
    case JointType::ConeTwist: return "cone_twist";
    default: return "?";
  }
}

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kRedundantPivot = 1e-5;  // relative to the largest diagonal entry
constexpr float kMinStiffLength = 1e-3f;   // m: a shorter distance joint has no direction to turn
// Below this (omega h)^2 a rod's sideways mode is slow enough for the explicit step: no sideways rows.
constexpr double kSidewaysOmega2 = 2.0;

inline Transform transformOf(const BodyStore& b, uint32_t i) { return i == kWorldBody ? Transform{} : b.xf[i]; }

inline float wrapAngle(float a) {
  while (a > kPi) a -= 2.0f * kPi;
  while (a < -kPi) a += 2.0f * kPi;
  return a;
}

/// World-space anchors, lever arms and joint frames of a joint at the current transforms.
struct JointGeometry {
  Vec3 pA, pB;          // anchors
  Vec3 rA, rB;          // anchor minus centre of mass
  Quat fA, fB;          // joint frames
  Vec3 axisA, axisB;    // frame x
  Vec3 refA, refB;      // frame y
};

JointGeometry geometryOf(const BodyStore& bodies, const JointDef& d) {
  const Transform xa = transformOf(bodies, d.bodyA), xb = transformOf(bodies, d.bodyB);
  JointGeometry g;
  g.rA = xa.rotate(d.localAnchorA);
  g.rB = xb.rotate(d.localAnchorB);
  g.pA = xa.p + g.rA;
  g.pB = xb.p + g.rB;
  // Ball and distance joints hold points only: their frames are never read (the frames were a
  // seventh of a ball-joint grid's step).
  if (d.type == JointType::Ball || d.type == JointType::Distance) return g;
  g.fA = (xa.q * d.localFrameA).normalized();
  g.fB = (xb.q * d.localFrameB).normalized();
  g.axisA = g.fA * Vec3::UnitX();
  g.axisB = g.fB * Vec3::UnitX();
  g.refA = g.fA * Vec3::UnitY();
  g.refB = g.fB * Vec3::UnitY();
  return g;
}

/// Rotation (axis times angle, world) that carries frame A onto frame B.
Vec3 rotationError(const JointGeometry& g) {
  Quat e = g.fB * g.fA.conjugate();
  if (e.w() < 0.0f) e.coeffs() = -e.coeffs();
  const float s = e.vec().norm();
  if (s < 1e-6f) return 2.0f * e.vec();
  return (2.0f * std::atan2(s, e.w()) / s) * e.vec();
}

/// Twist of frame B about the axis of frame A (rad): the twist part of the relative rotation.
float twistAngle(const JointGeometry& g) {
  const Quat r = g.fA.conjugate() * g.fB;
  return wrapAngle(2.0f * std::atan2(r.x(), r.w()));
}

float hingeAngle(const JointGeometry& g) {
  return std::atan2(g.axisA.dot(g.refA.cross(g.refB)), g.refA.dot(g.refB));
}

float swingAngle(const JointGeometry& g) { return std::acos(std::clamp(g.axisA.dot(g.axisB), -1.0f, 1.0f)); }

/// Servo target position and speed at time t (piecewise linear through the keys).
void servoTarget(const JointDef& d, float t, float& position, float& speed) {
  const std::vector<ServoKey>& k = d.servo;
  const float end = k.back().time;
  if (d.servoLoop && end > 0.0f) t = std::fmod(std::max(t, 0.0f), end);
  if (t <= k.front().time) {
    position = k.front().position;
    speed = 0.0f;
    return;
  }
  for (size_t i = 1; i < k.size(); ++i) {
    if (t <= k[i].time) {
      const float span = k[i].time - k[i - 1].time;
      const float u = span > 0.0f ? (t - k[i - 1].time) / span : 1.0f;
      position = k[i - 1].position + u * (k[i].position - k[i - 1].position);
      speed = span > 0.0f ? (k[i].position - k[i - 1].position) / span : 0.0f;
      return;
    }
  }
  position = k.back().position;
  speed = 0.0f;
}

struct RowBuilder {
  float mA, mB;
  Mat3 iA, iB;

  JointRow linear(const Vec3& dir, const Vec3& armA, const Vec3& armB) const {
    JointRow r;
    r.lin = dir;
    r.angA = armA.cross(dir);
    r.angB = armB.cross(dir);
    r.iAngA = iA * r.angA;
    r.iAngB = iB * r.angB;
    return r;
  }
  JointRow angular(const Vec3& axis) const {
    JointRow r;
    r.lin = Vec3::Zero();
    r.angA = r.angB = axis;
    r.iAngA = iA * axis;
    r.iAngB = iB * axis;
    return r;
  }
  double k(const JointRow& x, const JointRow& y) const {
    return double(mA + mB) * double(x.lin.dot(y.lin)) + double(x.angA.dot(y.iAngA)) + double(x.angB.dot(y.iAngB));
  }
  static JointRow negated(JointRow r) {
    r.lin = -r.lin;
    r.angA = -r.angA;
    r.angB = -r.angB;
    r.iAngA = -r.iAngA;
    r.iAngB = -r.iAngB;
    return r;
  }
};

/// Inverse of the block's effective mass J M^-1 J^T, in double precision.
void invertBlock(const RowBuilder& rb, JointConstraint& jc) {
  const int m = jc.blockRows;
  double K[kJointBlockRows * kJointBlockRows] = {}, inv[kJointBlockRows * kJointBlockRows];
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) K[i * m + j] = K[j * m + i] = rb.k(jc.block[i], jc.block[j]);
  double maxDiag = 0.0;
  for (int i = 0; i < m; ++i) maxDiag = std::max(maxDiag, K[i * m + i]);
  invertSymmetric(K, m, kRedundantPivot * maxDiag, inv);
  for (int i = 0; i < m * m; ++i) jc.blockInvK[i] = float(inv[i]);
}

}  // namespace

JointDef jointAtWorld(JointType type, uint32_t bodyA, uint32_t bodyB, const Transform& xfA, const Transform& xfB,
                      const Vec3& anchor, const Vec3& axis, const Vec3& anchorB) {
  JointDef d;
  d.type = type;
  d.bodyA = bodyA;
  d.bodyB = bodyB;
  d.localAnchorA = xfA.applyInverse(anchor);
  d.localAnchorB = xfB.applyInverse(type == JointType::Distance ? anchorB : anchor);
  // World joint frame: x along the axis, y any perpendicular; expressed in each body's frame.
  const Vec3 x = axis.squaredNorm() > 0.0f ? Vec3(axis.normalized()) : Vec3::UnitX();
  Vec3 y, z;
  orthonormalBasis(x, y, z);
  Mat3 R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = x.cross(y);
  const Quat world(R);
  d.localFrameA = (xfA.q.conjugate() * world).normalized();
  d.localFrameB = (xfB.q.conjugate() * world).normalized();
  if (type == JointType::Distance) d.minDistance = d.maxDistance = (anchorB - anchor).norm();
  return d;
}

void invertSymmetric(const double* K, int m, double tol, double* inverse) {
  // Only the entries written below are read (L on and below its diagonal, X likewise): no zeroing
  // of the 6 x 6 arrays for a ball joint's 3 x 3 block.
  double L[kJointBlockRows][kJointBlockRows], D[kJointBlockRows];
  for (int k = 0; k < m; ++k) {
    double d = K[k * m + k];
    for (int j = 0; j < k; ++j) d -= L[k][j] * L[k][j] * D[j];
    D[k] = d > tol ? d : 0.0;
    L[k][k] = 1.0;
    for (int i = k + 1; i < m; ++i) {
      double s = K[i * m + k];
      for (int j = 0; j < k; ++j) s -= L[i][j] * L[k][j] * D[j];
      L[i][k] = D[k] > 0.0 ? s / D[k] : 0.0;
    }
  }
  // X = L^-1 (unit lower triangular), then K^+ = X^T D^+ X.
  double X[kJointBlockRows][kJointBlockRows];
  for (int c = 0; c < m; ++c) {
    X[c][c] = 1.0;
    for (int i = c + 1; i < m; ++i) {
      double s = 0.0;
      for (int j = c; j < i; ++j) s -= L[i][j] * X[j][c];
      X[i][c] = s;
    }
  }
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      double s = 0.0;
      for (int k = std::max(i, j); k < m; ++k)
        if (D[k] > 0.0) s += X[k][i] * X[k][j] / D[k];
      inverse[i * m + j] = s;
    }
}

uint32_t jointRowCount(const JointDef& d) {
  const uint32_t motor = d.motorEnabled ? 1u : 0u, limits = d.limitEnabled ? 2u : 0u;
  switch (d.type) {
    case JointType::Ball: return 3;
    case JointType::Hinge: return 5 + motor + limits;
    case JointType::Fixed: return 6;
    case JointType::Slider: return 5 + motor + limits;
    case JointType::Distance: return d.minDistance == d.maxDistance || d.minDistance <= 0.0f ? 1 : 2;
    case JointType::ConeTwist:
      return 3 + (d.swingLimit < kPi ? 1u : 0u) + (d.twistLower > -kPi || d.twistUpper < kPi ? 2u : 0u);
    default: return 0;
  }
}

float motorAim(const JointDef& d, float position, float time, float dt) {
  if (d.servo.empty()) return d.motorSpeed;
  // Aim at the trajectory: its speed plus the position error closed in servoTime.
  float target, slope;
  servoTarget(d, time - dt, target, slope);
  const float err = d.type == JointType::Hinge ? wrapAngle(target - position) : target - position;
  return slope + err / std::max(d.servoTime, dt);
}

float jointPosition(const BodyStore& bodies, const JointDef& d) {
  const JointGeometry g = geometryOf(bodies, d);
  if (d.type == JointType::Hinge) return hingeAngle(g);
  if (d.type == JointType::Slider) return g.axisA.dot(g.pB - g.pA);
  return 0.0f;
}

void accumulateJointStiffness(const BodyStore& bodies, const Joint& j, float* angular) {
  const float f = j.heldForce;
  if (j.broken || !(f > 0.0f)) return;
  const JointDef& d = j.def;
  const Transform xa = transformOf(bodies, d.bodyA), xb = transformOf(bodies, d.bodyB);
  const Vec3 rA = xa.rotate(d.localAnchorA), rB = xb.rotate(d.localAnchorB);
  if (d.bodyA != kWorldBody) angular[d.bodyA] += f * rA.norm();
  if (d.bodyB != kWorldBody) angular[d.bodyB] += f * rB.norm();
}

float sidewaysStiffness(const Joint& j, const Vec3& separation) {
  const float len = separation.norm();
  if (j.def.type != JointType::Distance || j.broken || !(j.heldForce > 0.0f) || !(len > kMinStiffLength)) return 0.0f;
  if (j.lastForce.dot(separation) > 0.0f) return 0.0f;  // a strut: pushed, it would buckle, not stiffen
  return j.heldForce / len;
}

void prepareSoftBlock(JointConstraint& jc) {
  jc.blockRows -= jc.sidewaysRows;
  jc.sidewaysRows = 0;
  RowBuilder rb;
  rb.mA = jc.invMassA;
  rb.mB = jc.invMassB;
  if (jc.blockRows > 0) invertBlock(rb, jc);
}

void stiffenInertia(BodyStore& bodies, uint32_t body, float stiffness, float dt) {
  const float k = stiffness * dt * dt;
  if (!(k > 0.0f) || bodies.kind[body] != BodyKind::Dynamic) return;
  const Mat3 I = bodies.invInertiaWorld[body].inverse();
  bodies.invInertiaWorld[body] = (I + k * Mat3::Identity()).inverse();
}

void mergeParallelJoints(JointConstraint* js, uint32_t n, std::vector<std::pair<uint64_t, uint32_t>>& order) {
  order.clear();
  for (uint32_t c = 0; c < n; ++c)
    if (js[c].blockRows - js[c].sidewaysRows == 1 && js[c].dynA && js[c].dynB)
      order.emplace_back(uint64_t(std::min(js[c].a, js[c].b)) << 32 | std::max(js[c].a, js[c].b), c);
  std::sort(order.begin(), order.end());  // by pair, then joint index: the first joint of a pair hosts
  for (size_t i = 0; i < order.size();) {
    size_t e = i + 1;
    while (e < order.size() && order[e].first == order[i].first) ++e;
    JointConstraint& host = js[order[i].second];
    for (size_t k = i + 1; k < e; ++k) {
      JointConstraint& c = js[order[k].second];
      if (host.blockRows + 1 > kJointBlockRows) continue;
      c.hostReversed = c.a != host.a;
      auto seenFromHost = [&](JointRow row) {  // the same velocity seen from the host's A and B (RowBuilder::k's terms)
        if (!c.hostReversed) return row;
        std::swap(row.angA, row.angB);
        std::swap(row.iAngA, row.iAngB);
        return RowBuilder::negated(row);
      };
      // The length row goes after the host's length rows; sideways rows stay last (prepareSoftBlock).
      const int h = host.blockRows - host.sidewaysRows;
      for (int r = host.blockRows; r-- > h;) {
        host.block[r + 1] = host.block[r];
        host.blockError[r + 1] = host.blockError[r];
        host.blockImpulse[r + 1] = host.blockImpulse[r];
        host.blockCompliance[r + 1] = host.blockCompliance[r];
      }
      host.block[h] = seenFromHost(c.block[0]);
      host.blockError[h] = c.blockError[0];
      host.blockImpulse[h] = c.blockImpulse[0];
      host.blockCompliance[h] = 0.0f;
      if (c.pullRows & 1) host.pullRows = uint8_t(host.pullRows | 1u << h);
      ++host.blockRows;
      for (int r = 1; r <= c.sidewaysRows && host.blockRows < kJointBlockRows; ++r) {
        const int s = host.blockRows++;
        host.block[s] = seenFromHost(c.block[r]);
        host.blockError[s] = 0.0f;
        host.blockImpulse[s] = 0.0f;
        host.blockCompliance[s] = c.blockCompliance[r];
        ++host.sidewaysRows;
      }
      c.host = int32_t(order[i].second);
      c.hostRow = int8_t(h);
      c.blockRows = 0;
      c.sidewaysRows = 0;
      c.pullRows = 0;
    }
    i = e;
  }
}

namespace {

void updateTautness(const BodyStore& bodies, Joint& j, const JointGeometry& g, float dt) {
  const JointDef& d = j.def;
  if (d.type != JointType::Distance || !(d.minDistance < d.maxDistance)) {
    j.taut = false;
    return;
  }
  const Vec3 sep = g.pB - g.pA;
  const float len = sep.norm();
  if (!(len > 1e-6f)) {
    j.taut = false;
    return;
  }
  auto pointVelocity = [&](uint32_t body, const Vec3& r) -> Vec3 {
    return body == kWorldBody ? Vec3::Zero() : Vec3(bodies.v[body] + bodies.w[body].cross(r));
  };
  const float stretching = (sep / len).dot(pointVelocity(d.bodyB, g.rB) - pointVelocity(d.bodyA, g.rA));
  // A rope that pulled last step and is still at its length stays taut though its ends approach: its
  // pull may stop them within the step (the tree lets go of it if not). Judged slack, it left a
  // plank bridge nudged at 1 m/s as two trees joined by a swept limit row, and it sagged by metres.
  const bool pulled = len > d.maxDistance - kRopeTautSlop && j.lastForce.dot(sep) < 0.0f;
  j.taut = pulled || len + dt * stretching > d.maxDistance - kRopeTautSlop;
}

void prepareRows(const BodyStore& bodies, const Joint& j, const JointGeometry& g, uint32_t ji, const SolverParams& p,
                 const JointSolverParams& jp, float time, JointConstraint& jc) {
  const JointDef& d = j.def;
  const uint32_t a = d.bodyA, b = d.bodyB;
  jc.a = a;
  jc.b = b;
  jc.joint = ji;
  jc.dynA = a != kWorldBody && bodies.kind[a] == BodyKind::Dynamic && !bodies.asleep[a];
  jc.dynB = b != kWorldBody && bodies.kind[b] == BodyKind::Dynamic && !bodies.asleep[b];
  jc.pullRows = 0;
  jc.host = -1;
  jc.hostRow = 0;
  jc.hostReversed = false;
  RowBuilder rb;
  rb.mA = jc.invMassA = jc.dynA ? bodies.invMass[a] : 0.0f;
  rb.mB = jc.invMassB = jc.dynB ? bodies.invMass[b] : 0.0f;
  rb.iA = jc.dynA ? bodies.invInertiaWorld[a] : Mat3::Zero();
  rb.iB = jc.dynB ? bodies.invInertiaWorld[b] : Mat3::Zero();
  const float invDt = 1.0f / p.dt;
  const float beta = jp.beta * invDt;
  const Vec3 sep = g.pB - g.pA;

  int m = 0;
  float C[kJointBlockRows];
  auto pointRows = [&] {
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = Vec3::Unit(k);
      jc.block[m] = rb.linear(e, g.rA, g.rB);
      C[m++] = sep[k];
    }
  };
  auto lockRotation = [&] {
    const Vec3 e = rotationError(g);
    for (int k = 0; k < 3; ++k) {
      jc.block[m] = rb.angular(Vec3::Unit(k));
      C[m++] = e[k];
    }
  };
  switch (d.type) {
    case JointType::Ball:
    case JointType::ConeTwist: pointRows(); break;
    case JointType::Hinge: {
      pointRows();
      Vec3 t1, t2;
      orthonormalBasis(g.axisA, t1, t2);
      const Vec3 e = g.axisA.cross(g.axisB);  // rotation carrying A's axis onto B's
      jc.block[m] = rb.angular(t1);
      C[m++] = e.dot(t1);
      jc.block[m] = rb.angular(t2);
      C[m++] = e.dot(t2);
      break;
    }
    case JointType::Fixed:
      pointRows();
      lockRotation();
      break;
    case JointType::Slider: {
      // B's anchor stays on A's axis: the arm on A reaches to B's anchor.
      Vec3 t1, t2;
      orthonormalBasis(g.axisA, t1, t2);
      const Vec3 armA = g.rA + sep;
      jc.block[m] = rb.linear(t1, armA, g.rB);
      C[m++] = sep.dot(t1);
      jc.block[m] = rb.linear(t2, armA, g.rB);
      C[m++] = sep.dot(t2);
      lockRotation();
      break;
    }
    case JointType::Distance: {
      const float len = sep.norm();
      if (d.minDistance == d.maxDistance && len > 1e-6f) {
        jc.block[m] = rb.linear(sep / len, g.rA, g.rB);
        C[m++] = len - d.minDistance;
      } else if (j.taut && len > 1e-6f) {
        // A rope within its slop of taut holds its length; stretched, it is pulled back.
        jc.block[m] = rb.linear(sep / len, g.rA, g.rB);
        C[m++] = std::max(len - d.maxDistance, 0.0f);
        jc.pullRows = 1;
      }
      break;
    }
    default: break;
  }
  jc.ownRows = int8_t(m);
  jc.inTree = false;
  jc.treeBiasRate = beta;
  setSoftness(jc, jp.softHertz, jp.softDampingRatio, p.dt);
  for (int i = 0; i < m; ++i) {
    jc.blockError[i] = C[i];
    jc.blockImpulse[i] = p.warmStart ? j.blockImpulse[i] : 0.0f;
    jc.blockCompliance[i] = 0.0f;
  }
  // A rope's tension carries over between its two forms (one of the two impulses is zero).
  if (jc.pullRows) jc.blockImpulse[0] = p.warmStart ? std::min(j.blockImpulse[0] - j.extraImpulse[1], 0.0f) : 0.0f;
  // A taut rod's or rope's sideways rows: no error to correct and nothing carried over (the pull
  // is along the new direction), only the stiffness of the step's turn. Kept only in a tree; made
  // only for a joint that was in one last step (a net's joints never are: no rows to take out).
  jc.sidewaysRows = 0;
  const float sideways = d.type == JointType::Distance && m == 1 && j.inTree && jp.treeSolve && jp.geometricStiffness
                             ? sidewaysStiffness(j, sep)
                             : 0.0f;
  if (sideways > 0.0f) {
    Vec3 t[2];
    orthonormalBasis(sep.normalized(), t[0], t[1]);
    JointRow rows[2] = {rb.linear(t[0], g.rA, g.rB), rb.linear(t[1], g.rA, g.rB)};
    // (omega h)^2 of the sideways mode at the two bodies alone (an upper bound: the rest of the tree
    // only adds mass), and the share s of its stiffness taken implicitly. Taken whole, the rows damp
    // every swing by Omega^2 a step (a Newton's cradle lost 1 % of its momentum, a chain swinging a
    // load came to rest within the minute). With the rows' explicit turn from step to step, any s
    // above 1/2 - 2 / Omega^2 is stable (a step of one such mode); (Omega^2 - 2) / (Omega^2 + 2) is,
    // with room, and none below Omega^2 = 2, where the explicit step is stable alone.
    double omega2[2];
    for (int r = 0; r < 2; ++r) omega2[r] = double(sideways) * rb.k(rows[r], rows[r]) * double(p.dt) * double(p.dt);
    if (std::max(omega2[0], omega2[1]) > kSidewaysOmega2) {
      for (int r = 0; r < 2; ++r) {
        const double share = std::max(0.0, (omega2[r] - kSidewaysOmega2) / (omega2[r] + kSidewaysOmega2));
        jc.block[m] = rows[r];
        jc.blockError[m] = 0.0f;
        jc.blockImpulse[m] = 0.0f;
        // A direction whose mode is slow keeps its row (the block's shape), with no stiffness.
        jc.blockCompliance[m++] = share > 0.0 ? float(1.0 / (double(sideways) * p.dt * p.dt * share)) : 1e30f;
      }
      jc.sidewaysRows = 2;
    }
  }
  jc.blockRows = m;  // a joint left out of the tree is inverted then (prepareSoftBlock)

  // Limit and motor rows. A limit is a one-sided row on the distance to it, C >= 0: while C > 0 the
  // bound may be approached by at most C this step (speculative, no bounce), past it Baumgarte pushes back.
  int e = 0;
  jc.motor = false;
  jc.motorThroughTree = false;
  auto addRow = [&](const JointRow& row, int slot, float bias, float relaxBias, float lo, float hi) {
    jc.extra[e] = row;
    const double k = rb.k(row, row);
    jc.extraMass[e] = k > 0.0 ? float(1.0 / k) : 0.0f;
    jc.extraBias[e] = bias;
    jc.extraRelaxBias[e] = relaxBias;
    jc.extraLo[e] = lo;
    jc.extraHi[e] = hi;
    jc.extraImpulse[e] = p.warmStart ? std::clamp(j.extraImpulse[slot], lo, hi) : 0.0f;
    jc.extraSlot[e] = int8_t(slot);
    ++e;
  };
  auto addLimit = [&](const JointRow& row, int slot, float c) {
    const float bias = c > 0.0f ? c * invDt : beta * c;
    addRow(row, slot, bias, c > 0.0f ? c * invDt : 0.0f, 0.0f, kInf);
  };
  auto addMotor = [&](const JointRow& row, float position) {
    const float speed = motorAim(d, position, time, p.dt);
    const float maxImpulse = d.maxMotorForce * p.dt;
    addRow(row, 0, -speed, -speed, -maxImpulse, maxImpulse);
    jc.motor = true;
  };
  switch (d.type) {
    case JointType::Hinge: {
      const JointRow row = rb.angular(g.axisA);
      const float angle = hingeAngle(g);
      if (d.motorEnabled) addMotor(row, angle);
      if (d.limitEnabled) {
        addLimit(row, 1, angle - d.lower);
        addLimit(rb.negated(row), 2, d.upper - angle);
      }
      break;
    }
    case JointType::Slider: {
      const JointRow row = rb.linear(g.axisA, g.rA + sep, g.rB);
      const float s = g.axisA.dot(sep);
      if (d.motorEnabled) addMotor(row, s);
      if (d.limitEnabled) {
        addLimit(row, 1, s - d.lower);
        addLimit(rb.negated(row), 2, d.upper - s);
      }
      break;
    }
    case JointType::Distance: {
      const float len = sep.norm();
      if (d.minDistance < d.maxDistance && len > 1e-6f) {
        const JointRow row = rb.linear(sep / len, g.rA, g.rB);
        if (d.minDistance > 0.0f) addLimit(row, 0, len - d.minDistance);
        if (!j.taut) {
          addLimit(rb.negated(row), 1, d.maxDistance - len);
          if (p.warmStart) jc.extraImpulse[e - 1] = std::max(j.extraImpulse[1] - j.blockImpulse[0], 0.0f);
        }
      }
      break;
    }
    case JointType::ConeTwist: {
      const Vec3 s = g.axisA.cross(g.axisB);
      const float swing = swingAngle(g);
      if (d.swingLimit < kPi && s.norm() > 1e-5f) addLimit(rb.angular(-s.normalized()), 0, d.swingLimit - swing);
      const Vec3 mid = g.axisA + g.axisB;
      if ((d.twistLower > -kPi || d.twistUpper < kPi) && mid.norm() > 1e-3f) {
        const JointRow row = rb.angular(mid.normalized());
        const float twist = twistAngle(g);
        addLimit(row, 1, twist - d.twistLower);
        addLimit(rb.negated(row), 2, d.twistUpper - twist);
      }
      break;
    }
    default: break;
  }
  jc.extraRows = e;
}

}  // namespace

void setSoftness(JointConstraint& jc, float hertz, float dampingRatio, float dt) {
  const float omega = 2.0f * kPi * std::min(hertz, 0.5f / dt), h = dt;
  const float a1 = 2.0f * dampingRatio + h * omega, a2 = h * omega * a1, a3 = 1.0f / (1.0f + a2);
  jc.softBiasRate = omega / a1;
  jc.massScale = a2 * a3;
  jc.impulseScale = a3;
}

void prepareJoint(const BodyStore& bodies, const Joint& j, uint32_t ji, const SolverParams& p,
                  const JointSolverParams& jp, float time, JointConstraint& jc) {
  prepareRows(bodies, j, geometryOf(bodies, j.def), ji, p, jp, time, jc);
}

void prepareJointForStep(const BodyStore& bodies, Joint& j, uint32_t ji, const SolverParams& p,
                         const JointSolverParams& jp, float time, JointConstraint& jc) {
  const JointGeometry g = geometryOf(bodies, j.def);
  updateTautness(bodies, j, g, p.dt);
  prepareRows(bodies, j, g, ji, p, jp, time, jc);
}

namespace {

struct Velocities {
  Vec3 va, wa, vb, wb;
};

inline Velocities load(const BodyStore& bodies, const JointConstraint& c) {
  Velocities s;
  s.va = c.a != kWorldBody ? bodies.v[c.a] : Vec3::Zero();
  s.wa = c.a != kWorldBody ? bodies.w[c.a] : Vec3::Zero();
  s.vb = c.b != kWorldBody ? bodies.v[c.b] : Vec3::Zero();
  s.wb = c.b != kWorldBody ? bodies.w[c.b] : Vec3::Zero();
  return s;
}

inline void storeBack(BodyStore& bodies, const JointConstraint& c, const Velocities& s) {
  if (c.dynA) {
    bodies.v[c.a] = s.va;
    bodies.w[c.a] = s.wa;
  }
  if (c.dynB) {
    bodies.v[c.b] = s.vb;
    bodies.w[c.b] = s.wb;
  }
}

inline float rowVelocity(const JointRow& r, const Velocities& s) {
  return r.lin.dot(s.vb - s.va) + r.angB.dot(s.wb) - r.angA.dot(s.wa);
}

inline void applyRow(const JointConstraint& c, const JointRow& r, float lambda, Velocities& s) {
  s.va -= (c.invMassA * lambda) * r.lin;
  s.wa -= lambda * r.iAngA;
  s.vb += (c.invMassB * lambda) * r.lin;
  s.wb += lambda * r.iAngB;
}

}  // namespace

void warmStartJoints(BodyStore& bodies, const JointConstraint* js, size_t n) {
  for (size_t k = 0; k < n; ++k) {
    const JointConstraint& c = js[k];
    Velocities s = load(bodies, c);
    for (int i = 0; i < c.blockRows; ++i) applyRow(c, c.block[i], c.blockImpulse[i], s);
    for (int i = 0; i < c.extraRows; ++i) applyRow(c, c.extra[i], c.extraImpulse[i], s);
    storeBack(bodies, c, s);
  }
}

namespace {

float solveExtraRow(BodyStore& bodies, JointConstraint& c, int i, float omega, bool useBias) {
  Velocities s = load(bodies, c);
  const float cdot = rowVelocity(c.extra[i], s);
  const float b = useBias ? c.extraBias[i] : c.extraRelaxBias[i];
  const float old = c.extraImpulse[i];
  c.extraImpulse[i] = std::clamp(old - omega * c.extraMass[i] * (cdot + b), c.extraLo[i], c.extraHi[i]);
  const float applied = c.extraImpulse[i] - old;
  applyRow(c, c.extra[i], applied, s);
  storeBack(bodies, c, s);
  return c.extraMass[i] > 0.0f ? std::fabs(applied) / c.extraMass[i] : 0.0f;
}

float solveBlock(BodyStore& bodies, JointConstraint& c, float omega, bool useBias) {
  Velocities s = load(bodies, c);
  const int m = c.blockRows;
  float rhs[kJointBlockRows];
  float residual = 0.0f;
  for (int i = 0; i < m; ++i) {
    rhs[i] = -(rowVelocity(c.block[i], s) + (useBias ? c.softBiasRate * c.blockError[i] : 0.0f));
    residual = std::max(residual, std::fabs(rhs[i]));
  }
  for (int i = 0; i < m; ++i) {
    float dl = 0.0f;
    for (int j = 0; j < m; ++j) dl += c.blockInvK[i * m + j] * rhs[j];
    dl = useBias ? omega * (c.massScale * dl - c.impulseScale * c.blockImpulse[i]) : omega * dl;
    if (c.pullRows >> i & 1) dl = std::min(c.blockImpulse[i] + dl, 0.0f) - c.blockImpulse[i];
    c.blockImpulse[i] += dl;
    applyRow(c, c.block[i], dl, s);
  }
  storeBack(bodies, c, s);
  return residual;
}

}  // namespace

float solveJointIteration(BodyStore& bodies, JointConstraint* js, size_t n, JointTree* tree, float omega,
                          bool useBias) {
  float residual = 0.0f;
  // Motors first (those solved together through the tree were, just before: solveTreeMotors), then
  // the equality blocks (the tree at once, the others joint by joint), limits last so that they have
  // the final word in each sweep.
  for (size_t k = 0; k < n; ++k)
    if (js[k].motor && !js[k].motorThroughTree)
      residual = std::max(residual, solveExtraRow(bodies, js[k], 0, omega, useBias));
  if (tree && tree->size() > 0) {
    residual = std::max(residual, tree->solve(bodies, js, useBias));
    // The tree solves a taut rope as a rod: one that pushed (its ends closing) lets go.
    for (size_t k = 0; tree->pulls() && k < n; ++k) {
      JointConstraint& c = js[k];
      if (!c.pullRows || !c.inTree) continue;
      for (int i = 0; i < c.blockRows; ++i)
        if ((c.pullRows >> i & 1) && c.blockImpulse[i] > 0.0f) {
          Velocities s = load(bodies, c);
          applyRow(c, c.block[i], -c.blockImpulse[i], s);
          storeBack(bodies, c, s);
          c.blockImpulse[i] = 0.0f;
        }
    }
  }
  for (size_t k = 0; k < n; ++k) {
    JointConstraint& c = js[k];
    if (c.blockRows > 0 && !c.inTree) residual = std::max(residual, solveBlock(bodies, c, omega, useBias));
    for (int i = c.motor ? 1 : 0; i < c.extraRows; ++i)
      residual = std::max(residual, solveExtraRow(bodies, c, i, omega, useBias));
  }
  return residual;
}

void storeJointImpulses(const JointConstraint* js, size_t n, float dt, float stiffnessHold, Joint* joints) {
  const float invDt = 1.0f / dt;
  for (size_t k = 0; k < n; ++k) {
    const JointConstraint& c = js[k];
    Joint& j = joints[c.joint];
    // A joint merged into another (mergeParallelJoints) finds its rows there; the host's own are its first.
    const JointConstraint& rows = c.host >= 0 ? js[c.host] : c;
    const int first = c.host >= 0 ? c.hostRow : 0;
    const float sign = c.hostReversed ? -1.0f : 1.0f;  // the host's force on its B is this one's on its A
    j.inTree = rows.inTree;
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    for (int i = 0; i < kJointBlockRows; ++i) j.blockImpulse[i] = i < c.ownRows ? rows.blockImpulse[first + i] : 0.0f;
    for (int i = 0; i < kJointExtraRows; ++i) j.extraImpulse[i] = 0.0f;
    auto accumulate = [&](const JointRow& r, float lambda) {
      if (r.lin.squaredNorm() > 0.0f) force += lambda * r.lin;
      else torque += lambda * r.angB;
    };
    for (int i = 0; i < c.ownRows; ++i) accumulate(rows.block[first + i], sign * rows.blockImpulse[first + i]);
    for (int i = 0; i < c.extraRows; ++i) {
      j.extraImpulse[c.extraSlot[i]] = c.extraImpulse[i];
      accumulate(c.extra[i], c.extraImpulse[i]);
    }
    j.lastForce = invDt * force;
    j.lastTorque = invDt * torque;
    j.heldForce = std::max(j.lastForce.norm(), stiffnessHold * j.heldForce);
  }
}

JointError measureJointError(const BodyStore& bodies, const Joint& j) {
  const JointDef& d = j.def;
  const JointGeometry g = geometryOf(bodies, d);
  const Vec3 sep = g.pB - g.pA;
  JointError err;
  auto outside = [](float x, float lo, float hi) { return std::max(0.0f, std::max(lo - x, x - hi)); };
  switch (d.type) {
    case JointType::Ball: err.linear = sep.norm(); break;
    case JointType::Hinge: {
      err.linear = sep.norm();
      err.angular = std::acos(std::clamp(g.axisA.dot(g.axisB), -1.0f, 1.0f));
      if (d.limitEnabled) err.angular += outside(hingeAngle(g), d.lower, d.upper);
      break;
    }
    case JointType::Fixed:
      err.linear = sep.norm();
      err.angular = rotationError(g).norm();
      break;
    case JointType::Slider: {
      const float s = g.axisA.dot(sep);
      err.linear = (sep - s * g.axisA).norm();
      if (d.limitEnabled) err.linear += outside(s, d.lower, d.upper);
      err.angular = rotationError(g).norm();
      break;
    }
    case JointType::Distance: err.linear = outside(sep.norm(), d.minDistance, d.maxDistance); break;
    case JointType::ConeTwist:
      err.linear = sep.norm();
      err.angular = std::max(0.0f, swingAngle(g) - d.swingLimit) + outside(twistAngle(g), d.twistLower, d.twistUpper);
      break;
    default: break;
  }
  return err;
}

}  // namespace haif
