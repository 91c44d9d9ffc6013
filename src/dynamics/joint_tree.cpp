#include "dynamics/joint_tree.h"

#include <algorithm>
#include <cmath>

namespace haif {

namespace {
// A pivot below this times its scale (scale_) is a redundant row and is dropped. Elimination leaves
// a joint to a heavy body a pivot of about its heavy side's share of the diagonal (world - 1 kg -
// 1e5 kg: 1e-5 of the diagonal, which a bound of 1e-5 times the whole diagonal dropped: the weight
// fell free), so the scale is that share. Nearly redundant rows (a bridge pinned at both ends) must
// still go: inverted, they pumped energy into it.
constexpr double kTreeRedundantPivot = 1e-5;
}  // namespace

uint64_t JointTree::pairKey(const JointConstraint& j) {
  const uint32_t lo = std::min(j.a, j.b), hi = std::max(j.a, j.b);
  return uint64_t(lo) << 32 | hi;
}

uint32_t JointTree::find(uint32_t x) {
  while (uf_[x] != x) {
    uf_[x] = uf_[uf_[x]];
    x = uf_[x];
  }
  return x;
}

bool JointTree::sameStructure(const JointConstraint* js, uint32_t n) {
  // Before the first build there is no structure: nothing to keep for n = 0 either.
  bool same = n == shape_.size();
  shape_.resize(n);
  for (uint32_t c = 0; c < n; ++c) {
    const JointShape now{js[c].a, js[c].b, uint8_t(js[c].dynA), uint8_t(js[c].dynB), int32_t(js[c].blockRows)};
    same = same && shape_[c] == now;
    shape_[c] = now;
  }
  return same;
}

void JointTree::build(JointConstraint* js, uint32_t n, bool mergeParallel) {
  if (mergeParallel) mergeParallelJoints(js, n, parallel_);
  // The structure (which joints form the tree, the elimination order, the cliques) depends only on
  // which bodies each joint ties and how many rows it has. Where that is as at the last build, only
  // the numbers are made again: a 30x30 grid of ball joints spent a fifth of its step finding, each
  // step, the same loops that drop its tree.
  if (sameStructure(js, n)) {
    for (uint32_t c = 0; c < n; ++c) js[c].inTree = inTree_[c] != 0;
  } else {
    buildStructure(js, n);
    inTree_.resize(n);
    for (uint32_t c = 0; c < n; ++c) inTree_[c] = js[c].inTree ? 1 : 0;
  }
  for (uint32_t c = 0; c < n; ++c)
    if (!js[c].inTree) prepareSoftBlock(js[c]);
  if (order_.empty()) return;
  assemble(js);
  factor();
}

void JointTree::buildStructure(JointConstraint* js, uint32_t n) {
  inc_.clear();
  bodies_.clear();
  order_.clear();
  clique_.clear();
  postOrder_.clear();
  loops_ = 0;
  for (uint32_t c = 0; c < n; ++c) {
    js[c].inTree = false;
    if (js[c].blockRows == 0) continue;
    if (js[c].dynA) inc_.push_back({js[c].a, c, -1});
    if (js[c].dynB) inc_.push_back({js[c].b, c, +1});
  }
  if (inc_.empty()) return;
  std::sort(inc_.begin(), inc_.end(), [](const Incidence& x, const Incidence& y) {
    return x.body != y.body ? x.body < y.body : x.joint < y.joint;
  });
  for (int s = 0; s < 2; ++s) bodyOfSide_[s].assign(n, -1);
  for (uint32_t i = 0; i < inc_.size(); ++i) {
    if (i == 0 || inc_[i].body != inc_[i - 1].body) {
      BodyNode b;
      b.id = inc_[i].body;
      b.firstInc = i;
      b.incCount = 0;
      bodies_.push_back(b);
    }
    BodyNode& b = bodies_.back();
    ++b.incCount;
    bodyOfSide_[inc_[i].side > 0][inc_[i].joint] = int32_t(bodies_.size() - 1);
  }

  // Tree edges in joint order: a joint between two bodies already connected would close a loop.
  const uint32_t nb = static_cast<uint32_t>(bodies_.size());
  uf_.resize(nb);
  for (uint32_t i = 0; i < nb; ++i) uf_[i] = i;
  treeEdge_.assign(n, 0);
  for (uint32_t c = 0; c < n; ++c) {
    if (js[c].blockRows == 0) continue;
    const int32_t A = bodyOfSide_[0][c], B = bodyOfSide_[1][c];
    if (A >= 0 && B >= 0) {
      const uint32_t ra = find(uint32_t(A)), rb = find(uint32_t(B));
      if (ra == rb) continue;
      uf_[std::max(ra, rb)] = std::min(ra, rb);
    }
    treeEdge_[c] = 1;
    js[c].inTree = true;
  }
  // A joint that closes a loop stays a soft row outside the tree. A joint beside a tree joint between
  // the same two bodies (a bridge plank held at both edges: together a hinge) is no real loop. Where
  // real loops are common (a net, a grid: about half its joints), the tree is dropped: its exact
  // solve and the soft loop rows then fight over every body, a sweep cost 8x more than all-soft rows,
  // and projecting the tree alone pulled the bodies off the loop joints (a 30x30 ball-joint grid tore
  // by 83 m in 200 steps).
  pairs_.clear();
  uint32_t equalities = 0;
  for (uint32_t c = 0; c < n; ++c) {
    if (js[c].blockRows == 0) continue;
    ++equalities;
    if (treeEdge_[c] && bodyOfSide_[0][c] >= 0 && bodyOfSide_[1][c] >= 0) pairs_.push_back(pairKey(js[c]));
  }
  std::sort(pairs_.begin(), pairs_.end());
  for (uint32_t c = 0; c < n; ++c) {
    if (js[c].blockRows == 0 || treeEdge_[c]) continue;
    if (!std::binary_search(pairs_.begin(), pairs_.end(), pairKey(js[c]))) ++loops_;
  }
  if (loops_ * kMaxLoopShare > equalities) {
    for (uint32_t c = 0; c < n; ++c) js[c].inTree = false;
    inc_.clear();
    return;
  }

  // Pre-order over each tree; its reverse visits every body after all of its children.
  for (uint32_t r = 0; r < nb; ++r) {
    if (bodies_[r].visited) continue;
    bodies_[r].visited = 1;
    stack_.assign(1, r);
    while (!stack_.empty()) {
      const uint32_t t = stack_.back();
      stack_.pop_back();
      postOrder_.push_back(t);
      const BodyNode& bt = bodies_[t];
      for (uint32_t i = bt.firstInc; i < bt.firstInc + bt.incCount; ++i) {
        const uint32_t c = inc_[i].joint;
        if (!treeEdge_[c] || int32_t(c) == bt.parentJoint) continue;
        const int32_t other = bodyOfSide_[inc_[i].side < 0 ? 1 : 0][c];
        if (other < 0 || bodies_[other].visited) continue;
        bodies_[other].visited = 1;
        bodies_[other].parentJoint = int32_t(c);
        stack_.push_back(uint32_t(other));
      }
    }
  }
  std::reverse(postOrder_.begin(), postOrder_.end());

  // Elimination order: at each body (children first) its own joints, i.e. all but the one to its parent.
  // The clique of a body lists them and then the parent joint, which its parent eliminates later.
  nodeOfJoint_.assign(n, 0);
  uint32_t blockCount = 0;
  for (uint32_t bi : postOrder_) {
    BodyNode& b = bodies_[bi];
    b.cliqueStart = static_cast<uint32_t>(clique_.size());
    for (uint32_t i = b.firstInc; i < b.firstInc + b.incCount; ++i) {
      const uint32_t c = inc_[i].joint;
      if (!treeEdge_[c] || int32_t(c) == b.parentJoint) continue;
      JointNode node;
      node.c = c;
      node.m = js[c].blockRows;
      node.owner = bi;
      node.pos = static_cast<uint32_t>(clique_.size()) - b.cliqueStart;
      nodeOfJoint_[c] = static_cast<uint32_t>(order_.size());
      order_.push_back(node);
      clique_.push_back(c);
    }
    if (b.parentJoint >= 0) clique_.push_back(uint32_t(b.parentJoint));
    b.cliqueSize = static_cast<uint32_t>(clique_.size()) - b.cliqueStart;
    b.blockStart = blockCount;
    blockCount += b.cliqueSize * (b.cliqueSize - 1) / 2;
  }
  uint32_t widest = 1;
  for (const BodyNode& b : bodies_) widest = std::max(widest, b.cliqueSize);
  tmp_.resize(widest);
  diag_.resize(order_.size());
  scale_.resize(order_.size());
  blocks_.resize(blockCount);
  rhs_.resize(kJointBlockRows * order_.size());
}

namespace {

// Rows of joint c as seen from one of its bodies: sign, linear part, angular part and I^-1 times it.
struct Side {
  float sign, invMass;
  const JointRow* rows;
  bool isB;
  Vec3 ang(int i) const { return isB ? rows[i].angB : rows[i].angA; }
  Vec3 iAng(int i) const { return isB ? rows[i].iAngB : rows[i].iAngA; }
};

}  // namespace

void JointTree::assemble(const JointConstraint* js) {
  pulls_ = false;
  for (uint32_t e = 0; e < order_.size(); ++e) {
    const JointConstraint& jc = js[order_[e].c];
    const int m = jc.blockRows;
    pulls_ = pulls_ || jc.pullRows != 0;
    scale_[e] = 0.0;
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < m; ++k) {
        const JointRow& x = jc.block[i];
        const JointRow& y = jc.block[k];
        const double fromA = double(jc.invMassA) * double(x.lin.dot(y.lin)) + double(x.angA.dot(y.iAngA));
        const double fromB = double(jc.invMassB) * double(x.lin.dot(y.lin)) + double(x.angB.dot(y.iAngB));
        diag_[e].a[i * m + k] = fromA + fromB;
        // The scale of a pivot is the lighter-responding side's share (the heavy body's), so a mass
        // ratio is not taken for a redundant row.
        if (i == k) scale_[e] = std::max(scale_[e], fromA > 0.0 && fromB > 0.0 ? std::min(fromA, fromB) : fromA + fromB);
      }
    for (int i = m - jc.sidewaysRows; i < m; ++i) diag_[e].a[i * m + i] += double(jc.blockCompliance[i]);
  }
  // Off-diagonal blocks couple two joints through the one body they share.
  for (uint32_t bi = 0; bi < bodies_.size(); ++bi) {
    const BodyNode& b = bodies_[bi];
    auto sideOf = [&](uint32_t c) {
      const JointConstraint& jc = js[c];
      Side s;
      s.isB = bodyOfSide_[1][c] == int32_t(bi);
      s.sign = s.isB ? 1.0f : -1.0f;
      s.invMass = s.isB ? jc.invMassB : jc.invMassA;
      s.rows = jc.block;
      return s;
    };
    for (uint32_t q = 1; q < b.cliqueSize; ++q) {
      const uint32_t u = clique_[b.cliqueStart + q];
      const Side su = sideOf(u);
      const int mu = js[u].blockRows;
      for (uint32_t r = 0; r < q; ++r) {
        const uint32_t w = clique_[b.cliqueStart + r];
        const Side sw = sideOf(w);
        const int mw = js[w].blockRows;
        double* A = block(b, q, r);
        const double sgn = double(su.sign * sw.sign);
        for (int i = 0; i < mu; ++i)
          for (int k = 0; k < mw; ++k)
            A[i * mw + k] = sgn * (double(su.invMass) * double(su.rows[i].lin.dot(sw.rows[k].lin)) +
                                   double(su.ang(i).dot(sw.iAng(k))));
      }
    }
  }
}

void JointTree::factor() {
  for (uint32_t e = 0; e < order_.size(); ++e) {
    const JointNode& node = order_[e];
    const BodyNode& b = bodies_[node.owner];
    const int m = node.m;
    double K[kJointBlockRows * kJointBlockRows];
    std::copy(diag_[e].a, diag_[e].a + m * m, K);
    invertSymmetric(K, m, kTreeRedundantPivot * scale_[e], diag_[e].a);  // D_j^+; near-zero pivots: redundant rows
    const double* Dinv = diag_[e].a;
    const uint32_t later = b.cliqueSize - node.pos - 1;
    // L_uj = A_uj D_j^+ for the joints u after j in the clique.
    for (uint32_t k = 0; k < later; ++k) {
      const uint32_t q = node.pos + 1 + k;
      const int mu = rowsAt(b, q);
      const double* A = block(b, q, node.pos);
      for (int i = 0; i < mu; ++i)
        for (int c = 0; c < m; ++c) {
          double s = 0.0;
          for (int t = 0; t < m; ++t) s += A[i * m + t] * Dinv[t * m + c];
          tmp_[k].a[i * m + c] = s;
        }
    }
    // Schur complement within the clique: A_uw -= L_uj A_wj^T (u == w: the diagonal block of u).
    for (uint32_t k = 0; k < later; ++k) {
      const uint32_t q = node.pos + 1 + k;
      const int mu = rowsAt(b, q);
      for (uint32_t k2 = 0; k2 <= k; ++k2) {
        const uint32_t r = node.pos + 1 + k2;
        const int mw = rowsAt(b, r);
        const double* Aw = block(b, r, node.pos);
        double* target = q == r ? diag_[nodeOfJoint_[clique_[b.cliqueStart + q]]].a : block(b, q, r);
        for (int i = 0; i < mu; ++i)
          for (int c = 0; c < mw; ++c) {
            double s = 0.0;
            for (int t = 0; t < m; ++t) s += tmp_[k].a[i * m + t] * Aw[c * m + t];
            target[i * mw + c] -= s;
          }
      }
    }
    for (uint32_t k = 0; k < later; ++k) {
      const uint32_t q = node.pos + 1 + k;
      std::copy(tmp_[k].a, tmp_[k].a + rowsAt(b, q) * m, block(b, q, node.pos));
    }
  }
}

float JointTree::solve(BodyStore& bodies, JointConstraint* js, bool useBias) {
  const uint32_t n = size();
  float residual = 0.0f;
  auto vel = [&](uint32_t body, bool angular) -> Vec3 {
    if (body == kWorldBody) return Vec3::Zero();
    return angular ? bodies.w[body] : bodies.v[body];
  };
  for (uint32_t e = 0; e < n; ++e) {
    const JointConstraint& c = js[order_[e].c];
    const Vec3 va = vel(c.a, false), wa = vel(c.a, true), vb = vel(c.b, false), wb = vel(c.b, true);
    for (int i = 0; i < c.blockRows; ++i) {
      const JointRow& r = c.block[i];
      const float cdot = r.lin.dot(vb - va) + r.angB.dot(wb) - r.angA.dot(wa);
      float v = cdot + (useBias ? c.treeBiasRate * c.blockError[i] : 0.0f);
      // A soft row's impulse is its spring's (J v + compliance * impulse = 0), in every sweep.
      if (c.blockCompliance[i] > 0.0f) v += c.blockCompliance[i] * c.blockImpulse[i];
      residual = std::max(residual, std::fabs(v));
      rhs_[kJointBlockRows * e + i] = -double(v);
    }
  }
  solveInPlace();
  applyRows(bodies, js);
  return residual;
}

void JointTree::applyRows(BodyStore& bodies, JointConstraint* js) const {
  for (uint32_t e = 0; e < size(); ++e) {
    JointConstraint& c = js[order_[e].c];
    const double* x = &rhs_[kJointBlockRows * e];
    Vec3 P = Vec3::Zero(), angA = Vec3::Zero(), angB = Vec3::Zero();
    for (int i = 0; i < c.blockRows; ++i) {
      const float l = float(x[i]);
      c.blockImpulse[i] += l;
      P += l * c.block[i].lin;
      angA += l * c.block[i].iAngA;
      angB += l * c.block[i].iAngB;
    }
    if (c.dynA) {
      bodies.v[c.a] -= c.invMassA * P;
      bodies.w[c.a] -= angA;
    }
    if (c.dynB) {
      bodies.v[c.b] += c.invMassB * P;
      bodies.w[c.b] += angB;
    }
  }
}

void JointTree::project(BodyStore& bodies, const JointConstraint* js) {
  const uint32_t n = size();
  for (uint32_t e = 0; e < n; ++e) {
    const JointConstraint& c = js[order_[e].c];
    for (int i = 0; i < c.blockRows; ++i) rhs_[kJointBlockRows * e + i] = -double(c.blockError[i]);
  }
  solveInPlace();
  auto turn = [&](uint32_t body, const Vec3& angle) {
    Quat& q = bodies.xf[body].q;
    const Quat dq(0.0f, 0.5f * angle.x(), 0.5f * angle.y(), 0.5f * angle.z());
    q.coeffs() += (dq * q).coeffs();
    q.normalize();
  };
  for (uint32_t e = 0; e < n; ++e) {
    const JointConstraint& c = js[order_[e].c];
    const double* x = &rhs_[kJointBlockRows * e];
    Vec3 P = Vec3::Zero(), angA = Vec3::Zero(), angB = Vec3::Zero();
    for (int i = 0; i < c.blockRows; ++i) {
      const float l = float(x[i]);
      P += l * c.block[i].lin;
      angA += l * c.block[i].iAngA;
      angB += l * c.block[i].iAngB;
    }
    if (c.dynA) {
      bodies.xf[c.a].p -= c.invMassA * P;
      turn(c.a, -angA);
    }
    if (c.dynB) {
      bodies.xf[c.b].p += c.invMassB * P;
      turn(c.b, angB);
    }
  }
  for (const BodyNode& b : bodies_) bodies.updateWorldInertia(b.id);
}

void JointTree::solveInPlace() {
  const uint32_t n = size();
  // Forward: L y = r.
  for (uint32_t e = 0; e < n; ++e) {
    const JointNode& node = order_[e];
    const BodyNode& b = bodies_[node.owner];
    const double* y = &rhs_[kJointBlockRows * e];
    for (uint32_t q = node.pos + 1; q < b.cliqueSize; ++q) {
      const uint32_t eu = nodeOfJoint_[clique_[b.cliqueStart + q]];
      const int mu = order_[eu].m;
      const double* L = block(b, q, node.pos);
      double* yu = &rhs_[kJointBlockRows * eu];
      for (int i = 0; i < mu; ++i)
        for (int t = 0; t < node.m; ++t) yu[i] -= L[i * node.m + t] * y[t];
    }
  }
  // Diagonal: z = D^+ y.
  for (uint32_t e = 0; e < n; ++e) {
    const int m = order_[e].m;
    double* y = &rhs_[kJointBlockRows * e];
    double z[kJointBlockRows];
    for (int i = 0; i < m; ++i) {
      double s = 0.0;
      for (int t = 0; t < m; ++t) s += diag_[e].a[i * m + t] * y[t];
      z[i] = s;
    }
    std::copy(z, z + m, y);
  }
  // Backward: L^T x = z.
  for (uint32_t e = n; e-- > 0;) {
    const JointNode& node = order_[e];
    const BodyNode& b = bodies_[node.owner];
    double* x = &rhs_[kJointBlockRows * e];
    for (uint32_t q = node.pos + 1; q < b.cliqueSize; ++q) {
      const uint32_t eu = nodeOfJoint_[clique_[b.cliqueStart + q]];
      const int mu = order_[eu].m;
      const double* L = block(b, q, node.pos);
      const double* xu = &rhs_[kJointBlockRows * eu];
      for (int t = 0; t < node.m; ++t)
        for (int i = 0; i < mu; ++i) x[t] -= L[i * node.m + t] * xu[i];
    }
  }
}

void projectJointPositions(BodyStore& bodies, const Joint* joints, const uint32_t* ids, uint32_t n,
                           const SolverParams& p, const JointSolverParams& jp, JointConstraint* scratch,
                           JointTree& tree, bool mergeParallel) {
  for (uint32_t j = 0; j < n; ++j) prepareJoint(bodies, joints[ids[j]], ids[j], p, jp, 0.0f, scratch[j]);
  tree.build(scratch, n, mergeParallel);
  // Projecting the tree moves bodies without seeing the joints that close loops: it would open them.
  if (tree.loops() == 0) tree.project(bodies, scratch);
}

}  // namespace haif
