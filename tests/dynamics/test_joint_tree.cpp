// JointTree: one solve over a tree of joints leaves every equality row with J v = 0.
#include "dynamics/joint_tree.h"
#include "haif/world.h"
#include "joint_test_util.h"

#include <random>

namespace haif {
namespace {

float maxRowVelocity(const BodyStore& b, const std::vector<JointConstraint>& js) {
  float worst = 0.0f;
  for (const JointConstraint& c : js) {
    const Vec3 va = c.a == kWorldBody ? Vec3::Zero() : b.v[c.a], wa = c.a == kWorldBody ? Vec3::Zero() : b.w[c.a];
    const Vec3 vb = c.b == kWorldBody ? Vec3::Zero() : b.v[c.b], wb = c.b == kWorldBody ? Vec3::Zero() : b.w[c.b];
    for (int i = 0; i < c.blockRows; ++i) {
      const JointRow& r = c.block[i];
      worst = std::max(worst, std::fabs(r.lin.dot(vb - va) + r.angB.dot(wb) - r.angA.dot(wa)));
    }
  }
  return worst;
}

TEST(JointTree, OneSolveSatisfiesAChain) {
  World w;
  test::addHeavyChain(w, Vec3(0, 10, 0), 6, 100.0f, true);
  BodyStore& b = w.bodies();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (uint32_t i = 0; i < w.bodyCount(); ++i) {
    b.v[i] = Vec3(u(rng), u(rng), u(rng));
    b.w[i] = Vec3(u(rng), u(rng), u(rng));
    // Turn the bodies a little so the rows are not axis-aligned.
    b.xf[i].q = (b.xf[i].q * Quat(Eigen::AngleAxisf(0.3f * u(rng), Vec3(u(rng), u(rng), 1).normalized()))).normalized();
    b.updateWorldInertia(i);
  }
  SolverParams sp;
  std::vector<JointConstraint> js(w.jointCount());
  for (uint32_t j = 0; j < w.jointCount(); ++j)
    prepareJoint(b, w.joint(j), j, sp, JointSolverParams{}, 0.0f, js[j]);
  JointTree tree;
  tree.build(js.data(), uint32_t(js.size()));
  EXPECT_EQ(tree.size(), w.jointCount());
  const float before = maxRowVelocity(b, js);
  tree.solve(b, js.data(), false);
  const float after = maxRowVelocity(b, js);
  EXPECT_LT(after, 1e-4f * before);
}

// A torso with five limbs of two links (every joint type), the torso pinned to the world twice (two
// pendant joints on one body: redundant rows), and one rod that closes a loop between two limbs.
TEST(JointTree, BranchingTreeWithRedundantPinsAndALoop) {
  World w;
  auto box = [&](const Vec3& p, float m) {
    BodyDef d;
    d.shape = Shape::box(Vec3(0.2f, 0.2f, 0.2f));
    d.xf.p = p;
    d.mass = m;
    return w.addBody(d);
  };
  const uint32_t torso = box(Vec3(0, 5, 0), 20.0f);
  const JointType types[] = {JointType::Ball, JointType::Hinge, JointType::Fixed, JointType::Slider,
                             JointType::ConeTwist};
  std::vector<uint32_t> tips;
  for (int k = 0; k < 5; ++k) {
    const Vec3 dir(std::cos(1.2f * float(k)), 0.3f, std::sin(1.2f * float(k)));
    uint32_t prev = torso;
    for (int i = 1; i <= 2; ++i) {
      const uint32_t link = box(Vec3(0, 5, 0) + 0.5f * float(i) * dir, 1.0f);
      test::addJointAt(w, types[(k + i) % 5], prev, link, Vec3(0, 5, 0) + (0.5f * float(i) - 0.25f) * dir, dir);
      prev = link;
    }
    tips.push_back(prev);
  }
  test::addJointAt(w, JointType::Ball, kWorldBody, torso, Vec3(0.1f, 5.2f, 0));
  test::addJointAt(w, JointType::Ball, kWorldBody, torso, Vec3(-0.1f, 5.2f, 0));
  const uint32_t loop = test::addJointAt(w, JointType::Distance, tips[0], tips[1], w.bodies().xf[tips[0]].p,
                                         Vec3::UnitX(), w.bodies().xf[tips[1]].p);
  BodyStore& b = w.bodies();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (uint32_t i = 0; i < w.bodyCount(); ++i) {
    b.v[i] = Vec3(u(rng), u(rng), u(rng));
    b.w[i] = Vec3(u(rng), u(rng), u(rng));
  }
  SolverParams sp;
  std::vector<JointConstraint> js(w.jointCount());
  for (uint32_t j = 0; j < w.jointCount(); ++j)
    prepareJoint(b, w.joint(j), j, sp, JointSolverParams{}, 0.0f, js[j]);
  JointTree tree;
  tree.build(js.data(), uint32_t(js.size()));
  EXPECT_EQ(tree.size(), w.jointCount() - 1);
  EXPECT_FALSE(js[loop].inTree);
  std::vector<JointConstraint> treeRows;
  for (const JointConstraint& c : js)
    if (c.inTree) treeRows.push_back(c);
  const float before = maxRowVelocity(b, treeRows);
  tree.solve(b, js.data(), false);
  EXPECT_LT(maxRowVelocity(b, treeRows), 1e-4f * before);
}

}  // namespace
}  // namespace haif
