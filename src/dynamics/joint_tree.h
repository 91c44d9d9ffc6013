// Exact solve of an island's joint equality rows when its joints form a tree (chains, ragdolls, rope
// bridges, arms). Plain PGS needs about as many sweeps as a chain has links to carry a heavy load from
// one end to the other, and at a 1:100 mass ratio it stretches by metres at 10 sweeps. Over a tree the
// system J M^-1 J^T λ = -(J v + b) factors without fill-in: eliminating the joints body by body from the
// leaves inwards only ever couples joints that already share a body (the joints at one body form a
// clique). So each SOR-PGS sweep treats the whole tree as one block, solved in linear time; limits,
// motors, slack ropes, joints that close a loop and contacts stay ordinary PGS rows around it. A taut
// rope is a row of the tree that may only pull, and joints between the same two bodies one node
// (mergeParallelJoints).
#pragma once

#include "core/body_store.h"
#include "dynamics/joint_solver.h"

#include <cstdint>
#include <vector>

namespace haif {

class JointTree {
 public:
  /// Picks the joints of `js` whose equality blocks form a forest over the dynamic bodies (a joint that
  /// would close a loop is left to the per-joint sweep: its `inTree` stays false), orders them and factors
  /// the system at the prepared rows. Buffers are kept between calls: no allocation once warm.
  /// `mergeParallel`: first merge the rows of joints between the same two bodies (mergeParallelJoints).
  void build(JointConstraint* js, uint32_t n, bool mergeParallel = false);
  /// One exact solve of the tree rows against the current velocities: λ += A^-1 (-(J v + b)), applied
  /// to the bodies. `useBias` false: the relax sweep (no position correction). Returns max |J v + b|.
  float solve(BodyStore& bodies, JointConstraint* js, bool useBias);
  /// Post-stabilisation: moves the bodies (positions and orientations, not velocities) by one linearised
  /// exact step onto the tree's constraints, J M^-1 J^T Δ = -C at the rows as prepared. Integration
  /// leaves a drift of about r ω² h² / 2 per step at a spinning link that Baumgarte only removes a
  /// fraction of per step; this takes it out to second order.
  void project(BodyStore& bodies, const JointConstraint* js);
  uint32_t size() const { return static_cast<uint32_t>(order_.size()); }
  /// Joints of the last build that close a loop through other bodies (solved softly, outside the
  /// tree); a second joint between two bodies already joined is not counted.
  uint32_t loops() const { return loops_; }
  /// Some joint in the tree has a row that may only pull (a taut rope) this step.
  bool pulls() const { return pulls_; }
  /// The tree is dropped when more than one joint in this many closes a loop (a grid: one in two).
  static constexpr uint32_t kMaxLoopShare = 8;
  /// For solves against other right-hand sides (dynamics/joint_coupling.h): the e-th joint of the
  /// elimination order (an index into js), its rows of the right-hand side, and the solve in place,
  /// x = K⁻¹ g over the tree's rows. The next solve() or project() overwrites them.
  uint32_t jointAt(uint32_t e) const { return order_[e].c; }
  double* rowsOf(uint32_t e) { return &rhs_[kJointBlockRows * e]; }
  void solveRows() { solveInPlace(); }
  /// Adds the rows (as solved) to the joints' impulses and applies them to the bodies, as solve() does.
  void applyRows(BodyStore& bodies, JointConstraint* js) const;

 private:
  struct Block {
    double a[kJointBlockRows * kJointBlockRows];  // row-major, m_u x m_j used
  };
  struct Incidence {
    uint32_t body;   // global body id
    uint32_t joint;  // index into js
    int8_t side;     // -1: the joint's body A, +1: body B
  };
  struct BodyNode {
    uint32_t id;                  // global body id
    uint32_t firstInc, incCount;  // range in inc_ (sorted by body)
    int32_t parentJoint = -1;     // tree joint to the parent body (index into js), -1 at a root
    uint32_t cliqueStart = 0, cliqueSize = 0;  // range in clique_
    uint32_t blockStart = 0;      // lower-triangular off-diagonal blocks of the clique in blocks_
    uint8_t visited = 0;
  };
  struct JointNode {
    uint32_t c;       // index into js
    int m;            // equality rows
    uint32_t owner;   // BodyNode whose clique eliminates it
    uint32_t pos;     // position in that clique
  };

  uint32_t find(uint32_t x);
  static uint64_t pairKey(const JointConstraint& j);  // the two body ids, smaller first
  double* block(const BodyNode& b, uint32_t row, uint32_t col) {
    return blocks_[b.blockStart + row * (row - 1) / 2 + col].a;
  }
  int rowsAt(const BodyNode& b, uint32_t pos) const { return order_[nodeOfJoint_[clique_[b.cliqueStart + pos]]].m; }
  // What the structure of the tree depends on, per joint: its bodies, which of them are solved, rows.
  struct JointShape {
    uint32_t a = 0, b = 0;
    uint8_t dynA = 0, dynB = 0;
    int32_t rows = 0;
    bool operator==(const JointShape& o) const {
      return a == o.a && b == o.b && dynA == o.dynA && dynB == o.dynB && rows == o.rows;
    }
  };
  /// Records js's shapes; true when they are those of the last build.
  bool sameStructure(const JointConstraint* js, uint32_t n);
  /// Picks the tree joints (sets inTree), orders them and sizes the factor buffers.
  void buildStructure(JointConstraint* js, uint32_t n);
  void assemble(const JointConstraint* js);
  void factor();
  void solveInPlace();  // rhs_ <- A^-1 rhs_ with the factors

  uint32_t loops_ = 0;
  bool pulls_ = false;
  std::vector<std::pair<uint64_t, uint32_t>> parallel_;  // mergeParallelJoints' scratch
  std::vector<JointShape> shape_;   // per joint of the last build
  std::vector<uint8_t> inTree_;     // per joint of the last build: its inTree
  std::vector<Incidence> inc_;
  std::vector<BodyNode> bodies_;
  std::vector<uint32_t> uf_;
  std::vector<uint8_t> treeEdge_;      // per joint in js
  std::vector<uint64_t> pairs_;        // pairKey of each tree joint between two dynamic bodies, sorted
  std::vector<int32_t> bodyOfSide_[2]; // per joint: BodyNode of its A / B end, -1 if not dynamic
  std::vector<uint32_t> stack_;
  std::vector<uint32_t> postOrder_;
  std::vector<JointNode> order_;       // elimination order
  std::vector<uint32_t> nodeOfJoint_;  // js index -> order_ index
  std::vector<uint32_t> clique_;       // per BodyNode: order_ indices of its joints, parent joint last
  std::vector<Block> diag_;            // per order_ entry: D_j, then its pseudo-inverse
  std::vector<double> scale_;          // per order_ entry: largest diagonal share of its heavier body
  std::vector<Block> blocks_;
  std::vector<Block> tmp_;             // L blocks of the joint being eliminated
  std::vector<double> rhs_;            // 6 per node
};

/// Post-stabilisation of one island's joints after integration: prepares the rows of joints `ids` at the
/// bodies' new positions into `scratch` (n entries), factors the tree and projects (JointTree::project).
/// Joints outside the tree are left to the next step's soft rows.
void projectJointPositions(BodyStore& bodies, const Joint* joints, const uint32_t* ids, uint32_t n,
                           const SolverParams& p, const JointSolverParams& jp, JointConstraint* scratch,
                           JointTree& tree, bool mergeParallel);

}  // namespace haif
