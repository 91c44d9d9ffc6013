#include "dynamics/contact_chain.h"

#include "dynamics/joint_coupling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace haif {

namespace {

constexpr uint32_t kUnmarked = 0xffffffffu;
/// Solves per sweep: the first with the links that touch, then again after letting go of links or
/// points that came out pulling, or taking in links the solve made touch.
constexpr int kChainRounds = 8;
/// A row closing slower than this (m/s) counts as touching: a resting contact that pushes nothing yet
/// (a cold one under a landing) takes part from the first solve instead of joining a round later.
constexpr float kTouchingGap = 1e-3f;
/// A point let go of rejoins only when it closes faster than this (m/s): a lifted corner that merely
/// touches would otherwise be let go and taken back in turn, round after round.
constexpr float kRejoinGap = 1e-4f;
/// Impulses this far below 0, relative to the link's mean, count as 0 (float noise of the solve).
constexpr float kPullTolerance = 1e-4f;
/// A dense system's pivots below this fraction of its largest diagonal are its null space: impulses
/// that move no body (DenseSystem leaves ~1e-15 there; a 500 kg block on 1 kg cubes has ~1e-8).
constexpr double kDenseNullRatio = 1e-11;
/// Through joints, a row whose remaining diagonal is below this fraction of its own diagonal without
/// the joints is null: what the joints take back is known to the tolerance jointResponse checks
/// (1e-4 of the push), so a motion the joints forbid leaves about that much, not double's noise.
/// The rows this serves move 1/10-1/100 as much through joints as without (a car's wheels 1/53).
constexpr double kCoupledNullRatio = 1e-3;
/// A dense system's pivot is chosen by how much its link asks among the rows whose remaining
/// diagonal is at least this fraction of the largest remaining one.
constexpr double kDensePivotRatio = 1e-3;
static_assert(3 * DenseNormalSystem::kMaxLinks <= DenseNormalSystem::kMaxRows,
              "every active link's rows are numbered before the system's room is checked");

// The virtual rows of a link over its points in link.points, and their diagonal block.
void buildRows(const ContactConstraint& c, ChainLink& link) {
  double B[kMaxManifoldPoints][3];
  link.rank = pointBasis(link.coords, c.count, link.points, singlePlaceSpread(c), B);
  const double mSum = double(c.invMassA) + double(c.invMassB);
  for (int r = 0; r < 3; ++r) {
    double lin = 0.0;
    Vec3 angA = Vec3::Zero(), angB = Vec3::Zero(), invA = Vec3::Zero(), invB = Vec3::Zero();
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
      link.basis[i][r] = float(B[i][r]);
      if (i >= c.count) continue;
      const float w = float(B[i][r]);
      lin += B[i][r];
      angA += w * c.rAxn.row(i);
      angB += w * c.rBxn.row(i);
      invA += w * c.iAn.row(i);
      invB += w * c.iBn.row(i);
    }
    link.lin[r] = float(lin);
    link.angA[r] = angA;
    link.angB[r] = angB;
    link.invAngA[r] = invA;
    link.invAngB[r] = invB;
  }
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) {
      if (r >= link.rank || q >= link.rank) {
        link.diag[r][q] = r == q ? 1.0 : 0.0;  // an unused row: μ_r = 0
        continue;
      }
      link.diag[r][q] = double(link.lin[r]) * double(link.lin[q]) * mSum + double(link.angA[r].dot(link.invAngA[q])) +
                        double(link.angB[r].dot(link.invAngB[q]));
    }
}

// A link's rows over all its points; false when its normal rows have different normals (a mesh
// contact), which the reduction does not cover.
bool prepareLink(const Contact& contact, const ContactConstraint& c, ChainLink& link) {
  if (c.count == 0 || (c.count > 1 && !c.blockExact)) return false;
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < c.count; ++i) centre += contact.manifold.points[i].position;
  centre /= float(c.count);
  planarCoords(contact.manifold, centre, c.tangent1(), c.tangent2(), link.coords);
  link.points = (1u << c.count) - 1u;
  buildRows(c, link);
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) {
      link.next[r][q] = 0.0;
      link.nextF[r][q] = 0.0f;
    }
  link.active = link.factoredActive = false;
  return true;
}

// R_p M⁻¹ R_cᵀ through the one body link p shares with the next link c: p.sideToNext and
// c.sideFromPrev say whether it is body B (1) or body A (0) of each; a row acts on body A with the
// opposite sign.
void coupleLinks(const ContactConstraint& cp, const ContactConstraint& cc, ChainLink& p, const ChainLink& c) {
  const int sideP = p.sideToNext, sideC = c.sideFromPrev;
  const double sign = (sideP == 1 ? 1.0 : -1.0) * (sideC == 1 ? 1.0 : -1.0);
  const double invMass = sideP == 1 ? cp.invMassB : cp.invMassA;
  const double normals = double(cp.normal.row(0).dot(cc.normal.row(0)));
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) {
      p.next[r][q] = 0.0;
      p.nextF[r][q] = 0.0f;
    }
  for (int r = 0; r < p.rank; ++r) {
    const Vec3& ang = sideP == 1 ? p.angB[r] : p.angA[r];
    for (int q = 0; q < c.rank; ++q) {
      const Vec3& invAng = sideC == 1 ? c.invAngB[q] : c.invAngA[q];
      p.next[r][q] = sign * (double(p.lin[r]) * double(c.lin[q]) * invMass * normals + double(ang.dot(invAng)));
      p.nextF[r][q] = float(p.next[r][q]);
    }
  }
}

// After link j's rows changed: its coupling blocks with both neighbours.
void recouple(const ContactConstraint* cs, ChainLink* links, uint32_t n, uint32_t j) {
  if (j > 0 && links[j - 1].coupledToNext()) coupleLinks(cs[j - 1], cs[j], links[j - 1], links[j]);
  if (j + 1 < n && links[j].coupledToNext()) coupleLinks(cs[j], cs[j + 1], links[j], links[j + 1]);
}

// Block elimination down the chain for the links marked active (inactive links cut it in pieces).
// Reuses the factors while the active links are those they were made for.
bool factorChain(ChainLink* links, uint32_t n, bool rowsChanged) {
  bool same = !rowsChanged;
  for (uint32_t j = 0; j < n && same; ++j) same = links[j].active == links[j].factoredActive;
  if (same) return true;
  for (uint32_t j = 0; j < n; ++j) {
    ChainLink& link = links[j];
    link.factoredActive = link.active;
    if (!link.active) continue;
    double pivot[3][3];
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q) pivot[r][q] = link.diag[r][q];
    if (j > 0 && links[j - 1].active && links[j - 1].coupledToNext()) {
      const ChainLink& prev = links[j - 1];
      // lower = Cᵀ P_prev⁻¹, pivot −= lower C, with C = prev.next.
      for (int q = 0; q < 3; ++q)
        for (int r = 0; r < 3; ++r) {
          double s = 0.0;
          for (int t = 0; t < 3; ++t) s += prev.next[t][q] * prev.pivotInverse[t][r];
          link.lower[q][r] = s;
        }
      for (int q = 0; q < 3; ++q)
        for (int t = 0; t < 3; ++t) {
          double s = 0.0;
          for (int r = 0; r < 3; ++r) s += link.lower[q][r] * prev.next[r][t];
          pivot[q][t] -= s;
        }
    }
    if (!invertSymmetric3(pivot, link.pivotInverse, 1e-9)) {
      for (uint32_t i = 0; i < n; ++i) links[i].factoredActive = !links[i].active;  // nothing valid kept
      return false;
    }
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q) {
        link.pivotInverseF[r][q] = float(link.pivotInverse[r][q]);
        link.lowerF[r][q] = float(link.lower[r][q]);
      }
  }
  return true;
}

// μ from the factors: forward through `lower`, back through `next` (μ holds y on the way down).
void substituteChain(ChainLink* links, uint32_t n) {
  for (uint32_t j = 0; j < n; ++j) {
    ChainLink& link = links[j];
    if (!link.active) continue;
    for (int r = 0; r < 3; ++r) link.mu[r] = link.rhs[r];
    if (j > 0 && links[j - 1].active && links[j - 1].coupledToNext())
      for (int r = 0; r < 3; ++r)
        for (int t = 0; t < 3; ++t) link.mu[r] -= link.lowerF[r][t] * links[j - 1].mu[t];
  }
  for (uint32_t j = n; j-- > 0;) {
    ChainLink& link = links[j];
    if (!link.active) continue;
    float t[3] = {link.mu[0], link.mu[1], link.mu[2]};
    if (j + 1 < n && link.coupledToNext() && links[j + 1].active)
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) t[r] -= link.nextF[r][q] * links[j + 1].mu[q];
    for (int r = 0; r < 3; ++r)
      link.mu[r] = link.pivotInverseF[r][0] * t[0] + link.pivotInverseF[r][1] * t[1] + link.pivotInverseF[r][2] * t[2];
  }
}

// Impulse change of point i of a link from its μ.
inline float pointChange(const ChainLink& link, int i, float omega) {
  return omega * (link.basis[i][0] * link.mu[0] + link.basis[i][1] * link.mu[1] + link.basis[i][2] * link.mu[2]);
}

// J v + b of a normal row at the given body velocities: < 0 where the row is violated.
inline float rowGap(const ContactConstraint& c, int i, const Vec3& va, const Vec3& wa, const Vec3& vb, const Vec3& wb,
                    bool useBias) {
  return rowVelocity(c, i, va, wa, vb, wb) + rowBias(c, i, useBias);
}

// rhs = −Bᵀ (J v + b) of the active links at the bodies' current velocities.
void computeRhs(const BodyStore& bodies, const ContactConstraint* cs, ChainLink* links, uint32_t n, bool useBias) {
  for (uint32_t j = 0; j < n; ++j) {
    ChainLink& link = links[j];
    if (!link.active) continue;
    const ContactConstraint& c = cs[j];
    const Vec3 &va = bodies.v[c.a], &wa = bodies.w[c.a], &vb = bodies.v[c.b], &wb = bodies.w[c.b];
    float rhs[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < c.count; ++i) {
      const float g = rowGap(c, i, va, wa, vb, wb, useBias);
      for (int r = 0; r < 3; ++r) rhs[r] -= link.basis[i][r] * g;
    }
    for (int r = 0; r < 3; ++r) link.rhs[r] = rhs[r];
  }
}

}  // namespace

bool prepareChain(const Contact* contacts, const ContactConstraint* cs, uint32_t n, uint32_t* mark,
                  ChainLink* links) {
  if (n < 2) return false;
  for (uint32_t j = 0; j < n; ++j) {
    if (cs[j].dynA) mark[cs[j].a] = kUnmarked;
    if (cs[j].dynB) mark[cs[j].b] = kUnmarked;
  }
  // The shape first, which most islands that are not chains fail within a few links: mark is 2j
  // when a body was first met at link j, odd once it was met at a second, consecutive link. A link
  // is cleared only when the walk reaches it: a link is ~700 bytes, and clearing every one cost a
  // cache line per contact of every island that is not a chain (2.5% of `many_pyramids`' step).
  for (uint32_t j = 0; j < n; ++j) {
    const ContactConstraint& c = cs[j];
    links[j].sideToNext = links[j].sideFromPrev = -1;
    for (int side = 0; side < 2; ++side) {
      const bool dyn = side == 0 ? c.dynA : c.dynB;
      if (!dyn) continue;
      const uint32_t body = side == 0 ? c.a : c.b;
      const uint32_t m = mark[body];
      if (m == kUnmarked) {
        mark[body] = 2 * j;
        continue;
      }
      if (j == 0 || m != 2 * (j - 1) || links[j - 1].coupledToNext()) return false;  // not a chain
      links[j - 1].sideToNext = int8_t(cs[j - 1].b == body ? 1 : 0);
      links[j].sideFromPrev = int8_t(side);
      mark[body] = 2 * j + 1;
    }
  }
  // A body pinched between two immovable ones (haif/pinch.h) is a chain whose block is singular:
  // its two rows push the same direction from both ends. So is any chain held at both ends by
  // bodies that cannot move, overlapping or not: a hull the swept pit's bar had run over, its bar
  // contact 0.2 m deep and its ground contact 4 mm short of touching, took 2e8 N s in one step. Such
  // chains are swept, not solved exactly.
  uint32_t immovableEnds = 0;
  for (uint32_t j = 0; j < n; ++j) immovableEnds += cs[j].dynA && cs[j].dynB ? 0u : 1u;
  if (immovableEnds > 1) return false;
  for (uint32_t j = 0; j < n; ++j)
    if (contacts[cs[j].contact].pinched || !prepareLink(contacts[cs[j].contact], cs[j], links[j])) return false;
  for (uint32_t j = 0; j + 1 < n; ++j)
    if (links[j].coupledToNext()) coupleLinks(cs[j], cs[j + 1], links[j], links[j + 1]);
  return true;
}

namespace {

// One sweep of an exact normal solve (see the header): friction rows contact by contact, then the
// active set's rounds, each solving the normal rows of the active links together through `system`:
// system.factor(rowsChanged) factors them (false: singular), system.substitute() sets each active
// link's mu from its rhs, system.rowsRebuilt(j) is told when link j's rows changed.
template <class System>
SweepResult solveExactIteration(BodyStore& bodies, ContactConstraint* cs, ChainLink* links, uint32_t n, float omega,
                                bool useBias, System& system) {
  auto load = [&](const ContactConstraint& c, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb) {
    va = bodies.v[c.a];
    wa = bodies.w[c.a];
    vb = bodies.v[c.b];
    wb = bodies.w[c.b];
  };
  auto store = [&](const ContactConstraint& c, const Vec3& va, const Vec3& wa, const Vec3& vb, const Vec3& wb) {
    storeVelocities(bodies, c, va, wa, vb, wb);
  };
  // Adds `applied` to a link's impulses and velocities; c.delta sums what the sweep changed.
  auto commit = [&](ContactConstraint& c, const float* applied) {
    float before[kMaxManifoldPoints];
    for (int i = 0; i < c.count; ++i) {
      before[i] = c.delta[i];
      c.normalImpulse[i] += applied[i];
    }
    Vec3 va, wa, vb, wb;
    load(c, va, wa, vb, wb);
    applyNormalChange(c, applied, va, wa, vb, wb);
    store(c, va, wa, vb, wb);
    system.committed(c, applied);
    for (int i = 0; i < c.count; ++i) c.delta[i] += before[i];
  };
  auto release = [&](ContactConstraint& c) {
    float applied[kMaxManifoldPoints] = {};
    bool any = false;
    for (int i = 0; i < c.count; ++i) {
      applied[i] = -c.normalImpulse[i];
      any |= applied[i] != 0.0f;
    }
    if (any) commit(c, applied);
  };
  // The points of a manifold whose rows close faster than `gap` (negative: into each other), as a mask:
  // below -kRejoinGap the solve drives them in, below kTouchingGap they touch.
  auto pointsClosing = [&](const ContactConstraint& c, float gap) {
    const Vec3 &va = bodies.v[c.a], &wa = bodies.w[c.a], &vb = bodies.v[c.b], &wb = bodies.w[c.b];
    unsigned mask = 0;
    for (int i = 0; i < c.count; ++i)
      if (rowGap(c, i, va, wa, vb, wb, useBias) < gap) mask |= 1u << i;
    return mask;
  };
  auto drivenIn = [&](const ContactConstraint& c) { return pointsClosing(c, -kRejoinGap) != 0; };
  // A link all of whose points are apart (a speculative gap), that pushes, and that the solution
  // leaves opening at every point: it carries what it need not.
  auto slackGap = [&](const ContactConstraint& c) {
    bool pushes = false;
    for (int i = 0; i < c.count; ++i) {
      if (!(c.bias[i] > 0.0f)) return false;
      pushes |= c.normalImpulse[i] > 0.0f;
    }
    return pushes && pointsClosing(c, kTouchingGap) == 0;
  };
  auto touches = [&](const ContactConstraint& c) { return pointsClosing(c, kTouchingGap) != 0; };

  // A chain link that let go of lifted points in the last sweep starts again from all of them (the
  // chain's factors cost little to make again). A small island keeps them out until the solve drives
  // them in (the rejoin below), and a link it let go of rejoins only so, not when it merely touches:
  // an unloaded contact at rest that the least-squares solve gives a pull of float noise was let go
  // and taken back round after round, and 7 of 10 sweeps of tower_collapse's small islands ended
  // unsettled (and factored their system five times).
  system.beginSweep(bodies, useBias);
  bool rowsChanged = false;
  for (uint32_t j = 0; j < n; ++j) {
    links[j].letGo = false;
    links[j].releases = 0;
  }
  for (uint32_t j = 0; j < n && !System::kKeepsWhatItLetGo; ++j) {
    const unsigned all = (1u << cs[j].count) - 1u;
    if (links[j].points == all) continue;
    links[j].points = all;
    buildRows(cs[j], links[j]);
    system.rowsRebuilt(j);
    rowsChanged = true;
  }
  for (uint32_t j = 0; j < n; ++j) {
    ContactConstraint& c = cs[j];
    Vec3 va, wa, vb, wb;
    load(c, va, wa, vb, wb);
    const Vec3 va0 = va, wa0 = wa, vb0 = vb, wb0 = wb;
    solveFrictionRows(c, va, wa, vb, wb, omega, useBias);
    store(c, va, wa, vb, wb);
    if (system.noteChanges()) {
      if (c.dynA) system.changed(c.a, va - va0, wa - wa0);
      if (c.dynB) system.changed(c.b, vb - vb0, wb - wb0);
    }
    for (int i = 0; i < kMaxManifoldPoints; ++i) c.delta[i] = 0.0f;
    // Links take part that touch or still push; more join when the solve makes them touch. A
    // pushing link that separates (a box that was landing and now rises, a speculative contact
    // that started from a weight estimate) is solved with the others and let go only if the
    // solution pulls on it: letting go of all of its impulse up front can be a large kick, and
    // under a heavy load that friction keeps disturbing, it fed back sweep after sweep until a
    // small box between two heavy balls left at 1700 m/s (pile_10000).
    bool pushes = false;
    for (int i = 0; i < c.count; ++i) pushes |= c.normalImpulse[i] > 0.0f;
    links[j].active = touches(c) || pushes;
    // Through joints, a link takes part with its points that touch or push; the others join when
    // the solve drives them in. Solved exactly, its rows would also fit the gaps of points apart
    // and turn a body to close them: a plank hinged over a fulcrum, meeting its edge, was spun back
    // at 5.8 rad/s to close the 2 cm gap at the other edge within the step (the force row that
    // would have lifted it instead went into the hinge, null through the joints).
    if (system.noteChanges() && links[j].active) {
      unsigned part = pointsClosing(c, kTouchingGap);
      for (int i = 0; i < c.count; ++i)
        if (c.normalImpulse[i] > 0.0f) part |= 1u << i;
      if (part != 0 && part != links[j].points) {
        links[j].points = part;
        buildRows(c, links[j]);
        system.rowsRebuilt(j);
        rowsChanged = true;
      }
    }
  }

  bool solved = false;
  for (int round = 0; round < kChainRounds && !solved; ++round) {
    system.holdChange(bodies);  // each round starts from velocities its rows were factored for
    computeRhs(bodies, cs, links, n, useBias);
    if (!system.factor(rowsChanged)) break;
    rowsChanged = false;
    system.substitute();
    bool pulling = false;
    for (uint32_t j = 0; j < n; ++j) {
      ChainLink& link = links[j];
      if (!link.active) continue;
      ContactConstraint& c = cs[j];
      float total = 0.0f, size = 0.0f, lowest = 0.0f;
      for (int i = 0; i < c.count; ++i) {
        const float next = c.normalImpulse[i] + pointChange(link, i, omega);
        lowest = std::min(lowest, next);
        total += next;
        size += std::fabs(next);
      }
      link.slack = kPullTolerance * size / float(c.count);
      if (lowest >= -link.slack) continue;
      pulling = true;
      if (total >= 0.0f) {
        // A corner lifts (a tilt): the points that would pull let go, and the link is solved
        // again on the basis of the others.
        float applied[kMaxManifoldPoints] = {};
        for (int i = 0; i < c.count; ++i)
          if (c.normalImpulse[i] + pointChange(link, i, omega) < -link.slack) {
            applied[i] = -c.normalImpulse[i];
            link.points &= ~(1u << i);
          }
        commit(c, applied);
        if (link.points != 0) {
          buildRows(c, link);
          system.rowsRebuilt(j);
          rowsChanged = true;
          continue;
        }
      } else {
        // The whole contact wants to separate: let it go (λ = 0, applied now, so the next round
        // solves the others against it). If that was wrong, it touches again and rejoins below.
        release(c);
        link.letGo = true;
        ++link.releases;
      }
      link.active = false;
    }
    if (pulling) {
      // Through joints, rows that depend on each other (a motion the joints allow only together)
      // share the least impulse that serves them, which can pull on one asking for a different
      // push-out; let go, it is driven in again, round after round. Let go twice, the rounds give
      // way to the manifolds' passes at once instead of after kChainRounds factors.
      bool cycling = false;
      for (uint32_t j = 0; j < n && system.noteChanges(); ++j) cycling |= links[j].releases >= 2;
      if (cycling) break;
      continue;
    }
    for (uint32_t j = 0; j < n; ++j) {
      if (!links[j].active) continue;
      float applied[kMaxManifoldPoints] = {};
      for (int i = 0; i < cs[j].count; ++i) {
        const float old = cs[j].normalImpulse[i];
        applied[i] = std::max(0.0f, old + pointChange(links[j], i, omega)) - old;
      }
      commit(cs[j], applied);
    }
    system.holdChange(bodies);
    // Links left out that the solve now pushes into join, as do points a link let go of, and the
    // chain is solved again from here.
    solved = true;
    for (uint32_t j = 0; j < n; ++j) {
      ChainLink& link = links[j];
      ContactConstraint& c = cs[j];
      if (!link.active) {
        if (System::kKeepsWhatItLetGo && link.letGo ? drivenIn(c) : touches(c)) {
          link.active = true;
          solved = false;
        }
        continue;
      }
      if (slackGap(c)) {
        // Rows that depend on each other share a load by the least change of impulse, so a gap
        // link the warm start had pushing (from a landing) keeps its share though the solution
        // opens it: a 60 kg ball on a 6 mm plate on the ground held 51 % of its weight on its
        // contact with the ground 6 mm below, and when sweeps took over the island, that row let
        // go and the ball fell through the plate, every 30 steps. Let go, the others carry it.
        release(c);
        link.letGo = true;
        link.active = false;
        solved = false;
        continue;
      }
      const unsigned all = (1u << c.count) - 1u;
      if (link.points == all) continue;
      const unsigned rejoining = pointsClosing(c, -kRejoinGap) & ~link.points;
      if (rejoining == 0) continue;
      link.points |= rejoining;
      buildRows(c, link);
      system.rowsRebuilt(j);
      rowsChanged = true;
      solved = false;
    }
  }
  if (!solved) system.unsettled();
  system.holdChange(bodies);  // what the last round let go of
  // When the rounds did not settle, the manifolds' own passes.
  for (uint32_t j = 0; j < n && !solved; ++j) {
    ContactConstraint& c = cs[j];
    float before[kMaxManifoldPoints];
    for (int i = 0; i < kMaxManifoldPoints; ++i) before[i] = c.delta[i];
    Vec3 va, wa, vb, wb;
    load(c, va, wa, vb, wb);
    solveNormalRows(c, va, wa, vb, wb, omega, useBias);
    store(c, va, wa, vb, wb);
    for (int i = 0; i < kMaxManifoldPoints; ++i) c.delta[i] += before[i];
  }

  float residual = 0.0f;
  double change = 0.0;
  for (uint32_t j = 0; j < n; ++j) {
    const ContactConstraint& c = cs[j];
    // |Δλ| K_ii (K_ii = 1 / normalMass): the velocity correction of the row over the whole sweep.
    for (int i = 0; i < c.count; ++i)
      if (c.normalMass[i] > 0.0f)
        residual = std::max(residual, std::fabs(c.delta[i]) / c.normalMass[i]);
    change += squaredChange(c);
  }
  return {residual, change};
}

// The chain's system: block tridiagonal, factored down the chain.
struct ChainSystem {
  static constexpr bool kKeepsWhatItLetGo = false;
  const ContactConstraint* cs;
  ChainLink* links;
  uint32_t n;
  bool factor(bool rowsChanged) { return factorChain(links, n, rowsChanged); }
  void substitute() { substituteChain(links, n); }
  void rowsRebuilt(uint32_t j) { recouple(cs, links, n, j); }
  void beginSweep(BodyStore&, bool) {}
  void holdChange(BodyStore&) {}
  void committed(const ContactConstraint&, const float*) {}
  void unsettled() {}
  void changed(uint32_t, const Vec3&, const Vec3&) {}
  bool noteChanges() const { return false; }
};

// R_j M⁻¹ R_lᵀ through every dynamic body links j and l share (j == l: its diagonal block), added
// into `out`. In double from the body's own inverse inertia, not the rows' float I⁻¹ (r × n): the
// system is then positive semidefinite to double precision, and its null space (impulses that move
// nothing) shows as eigenvalues ~1e-15 of the largest instead of float noise at ~1e-10.
void addCoupling(const BodyStore& bodies, const ContactConstraint& cj, const ContactConstraint& cl, const ChainLink& j,
                 const ChainLink& l, double out[3][3]) {
  for (int sj = 0; sj < 2; ++sj) {
    if (!(sj == 0 ? cj.dynA : cj.dynB)) continue;
    const uint32_t body = sj == 0 ? cj.a : cj.b;
    for (int sl = 0; sl < 2; ++sl) {
      if (!(sl == 0 ? cl.dynA : cl.dynB) || (sl == 0 ? cl.a : cl.b) != body) continue;
      const double sign = (sj == 1 ? 1.0 : -1.0) * (sl == 1 ? 1.0 : -1.0);
      const double invMass = bodies.invMass[body];
      const double normals = cj.normal.row(0).cast<double>().dot(cl.normal.row(0).cast<double>());
      const Eigen::Matrix3d invInertia = bodies.invInertiaWorld[body].cast<double>();
      for (int q = 0; q < l.rank; ++q) {
        const Eigen::Vector3d turn = invInertia * (sl == 1 ? l.angB[q] : l.angA[q]).cast<double>();
        for (int r = 0; r < j.rank; ++r) {
          const Eigen::Vector3d ang = (sj == 1 ? j.angB[r] : j.angA[r]).cast<double>();
          out[r][q] += sign * (double(j.lin[r]) * double(l.lin[q]) * invMass * normals + ang.dot(turn));
        }
      }
    }
  }
}

// A row-major square matrix in flat storage: m[i][j].
struct RowMajor {
  double* data;
  int stride;
  double* operator[](int i) const { return data + size_t(i) * size_t(stride); }
};

}  // namespace

void solveFactored(const DenseNormalSystem& d, const double* b, double* x, double* c) {
  const int rows = d.rows, r = d.rank, free = rows - r;
  const RowMajor S{d.factor, d.stride};
  // The independent rows: L11 D L11ᵀ x1 = b1, in pivot order.
  for (int k = 0; k < r; ++k) {
    double v = b[d.order[k]];
    for (int m = 0; m < k; ++m) v -= S[k][m] * x[m];
    x[k] = v;
  }
  for (int k = 0; k < r; ++k) x[k] /= S[k][k];
  for (int k = r; k-- > 0;)
    for (int m = k + 1; m < r; ++m) x[k] -= S[m][k] * x[m];
  for (int f = 0; f < free; ++f) x[r + f] = 0.0;
  if (free == 0) return;
  // Least norm: x − N (NᵀN)⁻¹ Nᵀ x with N = [T; I] and x's free part 0.
  const RowMajor Tt{d.nullBasis, d.stride}, G{d.nullGram, d.stride};
  for (int f = 0; f < free; ++f) {
    double v = 0.0;
    for (int i = 0; i < r; ++i) v += Tt[f][i] * x[i];
    for (int m = 0; m < f; ++m) v -= G[f][m] * c[m];
    c[f] = v / G[f][f];
  }
  for (int f = free; f-- > 0;) {
    for (int m = f + 1; m < free; ++m) c[f] -= G[m][f] * c[m];
    c[f] /= G[f][f];
  }
  for (int f = 0; f < free; ++f)  // each x[i] takes the terms in the order of f, as before
    for (int i = 0; i < r; ++i) x[i] -= Tt[f][i] * c[f];
  for (int f = 0; f < free; ++f) x[r + f] = -c[f];
}

namespace {

// A small island's system: every pair of links sharing a body couples, so it is dense. It is solved
// in the least-squares sense: a table on four legs has more normal rows than its bodies have ways
// to move, and rows that ask for what no motion gives (legs pressed to slightly different depths)
// would otherwise fight with impulses that move nothing. A pivoted LDLᵀ (largest diagonal first)
// stops where what is left of the system is null: the rows eliminated by then are independent and
// solved exactly, the rest follow from them (they ask for what the others' motion gives, or what no
// motion gives, and are not fought for). Of all the impulses that solve it, the smallest is taken,
// projecting out the null space: that shares a load evenly among supports that could each carry it.
struct DenseSystem {
  static constexpr bool kKeepsWhatItLetGo = true;
  const BodyStore& bodies;
  const ContactConstraint* cs;
  ChainLink* links;
  uint32_t n;
  DenseNormalSystem& d;
  const JointCoupling* joints;  // the island's joint tree, or null

  // Solved through joints, the rows see what the tree leaves: the first sweep of the main and of the
  // relax sweeps starts from velocities the tree holds (later ones: the sweep before ended with it),
  // and each round's change is answered by the joints as the rows were factored for.
  void beginSweep(BodyStore& moving, bool useBias) {
    if (!joints) return;
    if (d.jointsHeld && d.heldWithBias == useBias) return;
    joints->tree->solve(moving, joints->joints, useBias);
    d.jointsHeld = true;
    d.heldWithBias = useBias;
  }
  void holdChange(BodyStore& moving) {
    if (joints) holdJointChange(moving, *joints);
  }
  void committed(const ContactConstraint& c, const float* applied) {
    if (joints) addContactChange(*joints, c, applied);
  }
  void changed(uint32_t body, const Vec3& dv, const Vec3& dw) {
    if (joints) addBodyChange(*joints, body, dv, dw);
  }
  bool noteChanges() const { return joints != nullptr; }
  void unsettled() { ++d.unsettledSweeps; }

  bool factor(bool rowsChanged) {
    bool same = !rowsChanged;
    for (uint32_t j = 0; j < n && same; ++j) same = links[j].active == links[j].factoredActive;
    if (same) return true;
    ++d.factors;
    int rows = 0;
    for (uint32_t j = 0; j < n; ++j) {
      links[j].factoredActive = links[j].active;
      d.rowOf[j] = links[j].active ? rows : -1;
      if (!links[j].active) continue;
      for (int q = 0; q < links[j].rank; ++q, ++rows) {
        d.linkOf[rows] = uint8_t(j);
        d.partOf[rows] = uint8_t(q);
      }
    }
    // A factor that fails keeps nothing: the next call with the same links must not substitute
    // what an earlier system left.
    auto failed = [&] {
      for (uint32_t j = 0; j < n; ++j) links[j].factoredActive = !links[j].active;
      d.rows = d.rank = 0;
      return false;
    };
    if (rows > d.stride) return failed();  // more links touch than the system was given room for
    d.rows = d.rank = rows;
    if (rows == 0) return true;
    const RowMajor S{d.factor, d.stride};
    for (uint32_t j = 0; j < n; ++j) {
      if (d.rowOf[j] < 0) continue;
      for (uint32_t l = j; l < n; ++l) {
        if (d.rowOf[l] < 0) continue;
        double block[3][3] = {};
        addCoupling(bodies, cs[j], cs[l], links[j], links[l], block);
        for (int r = 0; r < links[j].rank; ++r)
          for (int q = 0; q < links[l].rank; ++q)
            S[d.rowOf[j] + r][d.rowOf[l] + q] = S[d.rowOf[l] + q][d.rowOf[j] + r] = block[r][q];
      }
    }
    // Below its floor a row's remaining diagonal is null: a share of the largest one, or through
    // joints a share of its own before the joints' part.
    double floor[DenseNormalSystem::kMaxRows];
    if (joints) {
      for (int i = 0; i < rows; ++i) floor[i] = kCoupledNullRatio * S[i][i];
      // Less what the joints take back: column by column, symmetric up to the tree's float rows.
      for (uint32_t l = 0; l < n; ++l) {
        if (d.rowOf[l] < 0) continue;
        for (int q = 0; q < links[l].rank; ++q) {
          if (!jointResponse(bodies, *joints, cs[l], links[l], q)) {
            clearJointResponse(*joints);
            d.jointsUnsound = true;  // the tree cannot carry these rows: swept from here on this step
            return failed();
          }
          for (uint32_t j = 0; j < n; ++j) {
            if (d.rowOf[j] < 0) continue;
            for (int r = 0; r < links[j].rank; ++r)
              S[d.rowOf[j] + r][d.rowOf[l] + q] += rowAtResponse(*joints, cs[j], links[j], r);
          }
          clearJointResponse(*joints);
        }
      }
      for (int i = 0; i < rows; ++i)
        for (int k = 0; k < i; ++k) S[i][k] = S[k][i] = 0.5 * (S[i][k] + S[k][i]);
    }
    double largest = 0.0;
    for (int i = 0; i < rows; ++i) {
      d.order[i] = i;
      largest = std::max(largest, S[i][i]);
    }
    if (!(largest > 0.0)) return failed();
    if (!joints)
      for (int i = 0; i < rows; ++i) floor[i] = kDenseNullRatio * largest;
    // How much each active link asks: its most demanding point's bias (push-out negative, a
    // speculative gap positive). Where rows depend on each other, the ones eliminated first are
    // solved and the last follow from them, so the most demanding go first: a 100 kg box 1 cm into
    // the top board of a stack also had a speculative contact with the board below, 3 cm away
    // through the top one, and when the three rows were solved the other way round it fell into the
    // stack at 1.8 m/s (the speculative row's allowance) for tens of steps, held up only by the turn
    // projection. The rows that follow then ask less than the others give (they are slack).
    for (uint32_t j = 0; j < n; ++j) {
      if (d.rowOf[j] < 0) continue;
      float asks = std::numeric_limits<float>::max();
      for (int i = 0; i < cs[j].count; ++i)
        if (links[j].points & (1u << i)) asks = std::min(asks, cs[j].bias[i]);
      d.asks[j] = asks;
    }
    // Outer-product LDLᵀ on the lower triangle, rows and columns swapped to the pivot: the row of the
    // most demanding link among those whose remaining diagonal is within kDensePivotRatio of the
    // largest remaining (small pivots would amplify rounding), the larger diagonal between rows of
    // one link. Only the lower triangle is updated (the upper one holds Lᵀ afterwards, below):
    // updating and mirroring the whole matrix, read down its columns, was a third of a 136-row
    // factor's time (a small Jenga tower at 4 iterations: ~1 ms a step).
    for (int k = 0; k < rows; ++k) {
      double remaining = 0.0;
      for (int i = k; i < rows; ++i)
        if (S[i][i] > floor[d.order[i]]) remaining = std::max(remaining, S[i][i]);
      if (!(remaining > 0.0)) {
        d.rank = k;
        break;
      }
      int p = -1;
      for (int i = k; i < rows; ++i) {
        if (!(S[i][i] >= kDensePivotRatio * remaining) || (joints && !(S[i][i] > floor[d.order[i]]))) continue;
        if (p < 0) {
          p = i;
          continue;
        }
        const float ai = d.asks[d.linkOf[d.order[i]]], ap = d.asks[d.linkOf[d.order[p]]];
        if (ai < ap || (ai == ap && S[i][i] > S[p][p])) p = i;
      }
      if (p != k) {
        // The symmetric swap of rows and columns k and p, as the lower triangle holds them: the
        // rows of L so far, the diagonals, the part between (a row of one is a column of the
        // other) and the columns below p. Element (p, k) is its own mirror.
        std::swap(d.order[k], d.order[p]);
        for (int m = 0; m < k; ++m) std::swap(S[k][m], S[p][m]);
        std::swap(S[k][k], S[p][p]);
        for (int i = k + 1; i < p; ++i) std::swap(S[i][k], S[p][i]);
        for (int i = p + 1; i < rows; ++i) std::swap(S[i][k], S[i][p]);
      }
      const double pivot = S[k][k];
      double* column = d.c;  // column k of L, in a row (substitute's scratch, free while factoring)
      for (int i = k + 1; i < rows; ++i) column[i] = S[i][k] /= pivot;
      for (int i = k + 1; i < rows; ++i) {
        const double li = S[i][k] * pivot;
        double* row = S[i];
        for (int j = k + 1; j <= i; ++j) row[j] -= li * column[j];
      }
    }
    const int r = d.rank, free = rows - r;
    if (free == 0) return true;
    // Null space [T; I] with L11ᵀ T = −L21ᵀ, and the Cholesky factor of its Gram matrix I + TᵀT.
    // Both walk columns of L11 and of T: L11 is copied into the upper triangle (Lᵀ by rows) and T
    // is kept transposed (Tᵗ by rows), so every sum runs along a row. Read down the columns, these
    // two sums were half of a 136-row factor's time.
    for (int i = 0; i < r; ++i)
      for (int m = i + 1; m < r; ++m) S[i][m] = S[m][i];
    const RowMajor Tt{d.nullBasis, d.stride};
    for (int f = 0; f < free; ++f)
      for (int i = r; i-- > 0;) {
        double t = -S[r + f][i];
        for (int m = i + 1; m < r; ++m) t -= S[i][m] * Tt[f][m];
        Tt[f][i] = t;
      }
    const RowMajor G{d.nullGram, d.stride};
    for (int a = 0; a < free; ++a)
      for (int b = 0; b <= a; ++b) {
        double g = a == b ? 1.0 : 0.0;
        for (int i = 0; i < r; ++i) g += Tt[a][i] * Tt[b][i];
        for (int m = 0; m < b; ++m) g -= G[a][m] * G[b][m];
        G[a][b] = a == b ? std::sqrt(g) : g / G[b][b];
      }
    return true;
  }

  void substitute() {
    const int rows = d.rows;
    if (rows == 0) return;
    double b[DenseNormalSystem::kMaxRows];
    for (int row = 0; row < rows; ++row) b[row] = links[d.linkOf[row]].rhs[d.partOf[row]];
    solveFactored(d, b, d.x, d.c);
    for (uint32_t j = 0; j < n; ++j) {
      if (d.rowOf[j] < 0) continue;
      for (int q = 0; q < 3; ++q) links[j].mu[q] = 0.0f;
    }
    for (int k = 0; k < rows; ++k) links[d.linkOf[d.order[k]]].mu[d.partOf[d.order[k]]] = float(d.x[k]);
  }
  void rowsRebuilt(uint32_t) {}
};

}  // namespace

SweepResult solveChainIteration(BodyStore& bodies, ContactConstraint* cs, ChainLink* links, uint32_t n, float omega,
                                bool useBias) {
  ChainSystem system{cs, links, n};
  return solveExactIteration(bodies, cs, links, n, omega, useBias, system);
}

bool prepareSmallIsland(const Contact* contacts, const ContactConstraint* cs, uint32_t n, ChainLink* links,
                        int rowsHeld, uint32_t minLinks) {
  if (n < minLinks || n > uint32_t(DenseNormalSystem::kMaxLinks)) return false;
  // An island of up to kCheapLinks contacts counts the rows of all of them, one larger (taken only
  // at a larger mass ratio) those of the links that touch or push now: contacts apart by a gap (a
  // pyramid's neighbours a centimetre to the side) take part only when the solve drives them in, and
  // when more do than the system has room for, that sweep's rounds give way to the manifolds' passes.
  const bool large = n > uint32_t(DenseNormalSystem::kCheapLinks);
  int rows = 0;
  for (uint32_t j = 0; j < n; ++j) {
    const ContactConstraint& c = cs[j];
    if (contacts[c.contact].pinched || !prepareLink(contacts[c.contact], c, links[j])) return false;
    bool takesPart = !large;
    for (int i = 0; i < c.count; ++i) takesPart |= c.bias[i] < kTouchingGap || c.normalImpulse[i] > 0.0f;
    if (takesPart) rows += links[j].rank;
  }
  return rows <= std::min(rowsHeld, DenseNormalSystem::kMaxRows);
}

SweepResult solveSmallIslandIteration(BodyStore& bodies, ContactConstraint* cs, ChainLink* links, uint32_t n,
                                      float omega, bool useBias, DenseNormalSystem& system,
                                      const JointCoupling* joints) {
  DenseSystem dense{bodies, cs, links, n, system, joints};
  return solveExactIteration(bodies, cs, links, n, omega, useBias, dense);
}

}  // namespace haif
