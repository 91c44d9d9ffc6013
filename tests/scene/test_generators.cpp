// Generator layouts: determinism, counts, and the geometric promises each layout makes.
#include "scene_test_util.h"

#include "scene/generators.h"

namespace haif::test {
namespace {

bool sameBodies(const std::vector<BodyDesc>& a, const std::vector<BodyDesc>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].position != b[i].position || a[i].orientation.coeffs() != b[i].orientation.coeffs() ||
        a[i].shape.type != b[i].shape.type || a[i].shape.halfExtents != b[i].shape.halfExtents ||
        a[i].shape.radius != b[i].shape.radius || a[i].shape.points != b[i].shape.points || a[i].where != b[i].where)
      return false;
  }
  return true;
}

TEST(Generators, SplitMix64MatchesTheReferenceSequence) {
  // First outputs of splitmix64 seeded with 0 (the published reference values).
  SplitMix64 rng(0);
  EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
  SplitMix64 u(42);
  for (int i = 0; i < 1000; ++i) {
    const double x = u.uniform();
    ASSERT_GE(x, 0.0);
    ASSERT_LT(x, 1.0);
  }
}

TEST(Generators, RandomPileIsDeterministicAndSeedDependent) {
  RandomPileParams p;
  p.count = 200;
  p.lo = Vec3d(-4, 1, -4);
  p.hi = Vec3d(4, 9, 4);
  p.seed = 99;
  std::vector<BodyDesc> a, b, c;
  generateRandomPile(p, BodyPrototype{}, "g", a);
  generateRandomPile(p, BodyPrototype{}, "g", b);
  EXPECT_TRUE(sameBodies(a, b));
  p.seed = 100;
  generateRandomPile(p, BodyPrototype{}, "g", c);
  EXPECT_FALSE(sameBodies(a, c));
  // Golden values: the first body of seed 99 must not change across machines and versions.
  ASSERT_EQ(a.size(), 200u);
  EXPECT_EQ(a[0].position, Vec3(-3.71419358f, 1.2541492f, -3.40355444f));
  EXPECT_EQ(a[0].shape.type, ShapeType::ConvexHull);
  EXPECT_EQ(a[0].orientation.w(), 0.64610517f);
  EXPECT_EQ(a[0].where, "g #0");
  EXPECT_EQ(a[199].where, "g #199");
}

TEST(Generators, RandomPileMixesShapesWithoutInitialOverlap) {
  RandomPileParams p;
  p.count = 300;
  p.lo = Vec3d(-4, 1, -4);
  p.hi = Vec3d(4, 12, 4);
  std::vector<BodyDesc> out;
  generateRandomPile(p, BodyPrototype{}, "pile", out);
  int kinds[4] = {0, 0, 0, 0};
  for (const BodyDesc& b : out) {
    const ShapeType t = b.shape.type;
    kinds[t == ShapeType::Sphere ? 0 : t == ShapeType::Box ? 1 : t == ShapeType::Capsule ? 2 : 3]++;
    EXPECT_NEAR(b.orientation.norm(), 1.0f, 1e-5f);
    EXPECT_TRUE((b.position.array() >= p.lo.cast<float>().array()).all() && (b.position.array() <= p.hi.cast<float>().array()).all());
    if (t == ShapeType::ConvexHull) {
      EXPECT_GE(b.shape.points.size(), 4u);
    }
  }
  for (int k : kinds) EXPECT_GT(k, 30);
  // Bounding spheres never overlap at the start, and every size is in [minSize, maxSize].
  auto radius = [](const ShapeDesc& s) {
    switch (s.type) {
      case ShapeType::Sphere: return s.radius;
      case ShapeType::Box: return s.halfExtents.norm();
      case ShapeType::Capsule: return s.radius + s.halfHeight;
      default: {
        float r = 0.0f;
        for (const Vec3& q : s.points) r = std::max(r, q.norm());
        return r;
      }
    }
  };
  for (size_t i = 0; i < out.size(); ++i) {
    ASSERT_LE(radius(out[i].shape), static_cast<float>(p.maxSize) * 1.0001f);
    for (size_t j = i + 1; j < out.size(); ++j)
      ASSERT_GE((out[i].position - out[j].position).norm(), radius(out[i].shape) + radius(out[j].shape)) << i << " " << j;
  }
}

TEST(Generators, SceneFileGeneratorsAreDeterministic) {
  const std::string text = R"({"generators": [
    {"type": "random_pile", "count": 150, "min": [-3, 1, -3], "max": [3, 8, 3], "seed": 5},
    {"type": "domino_run", "count": 12, "arc": {"radius": 4}},
    {"type": "wall", "rows": 5, "cols": 6, "yaw_deg": 30}]})";
  const SceneDesc a = parseOk(text), b = parseOk(text);
  EXPECT_TRUE(sameBodies(a.bodies, b.bodies));
  EXPECT_EQ(a.bodies.size(), 150u + 12u + (3 * 6 + 2 * 7));
  EXPECT_EQ(a.bodies[150].where, "generators[1] #0");
}

TEST(Generators, StackGapAndBase) {
  std::vector<BodyDesc> out;
  StackParams p;
  p.count = 4;
  p.base = Vec3d(1, 2, 3);
  p.halfExtents = Vec3d(0.5, 0.25, 0.5);
  p.gap = 0.1;
  generateStack(p, BodyPrototype{}, "s", out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].position, Vec3(1, 2.25f, 3));
  EXPECT_EQ(out[3].position, Vec3(1, static_cast<float>(2.25 + 3 * 0.6), 3));
}

TEST(Generators, StacksGridSideFollowsTheDesignFormula) {
  EXPECT_EQ(stacksGridSide(100, 10), 4);
  EXPECT_EQ(stacksGridSide(500, 10), 8);
  EXPECT_EQ(stacksGridSide(1000, 10), 10);
  EXPECT_EQ(stacksGridSide(2000, 10), 15);
  EXPECT_EQ(stacksGridSide(95, 10), 4);  // ten stacks, the last one partial
  std::vector<BodyDesc> out;
  StacksParams p;
  p.count = 95;
  generateStacks(p, BodyPrototype{}, "s", out);
  EXPECT_EQ(out.size(), 95u);
  EXPECT_EQ(out[94].position, Vec3(3.0f, static_cast<float>(0.5 + 1.01 * 4), 6.0f));
}

TEST(Generators, RunningBondWallHasFlushEnds) {
  WallParams p;
  p.rows = 4;
  p.cols = 5;
  p.gap = 0.02;
  std::vector<BodyDesc> out;
  generateWall(p, BodyPrototype{}, "w", out);
  ASSERT_EQ(out.size(), 2u * 5 + 2u * 6);
  for (int row = 0; row < 4; ++row) {
    float lo = 1e9f, hi = -1e9f;
    for (const BodyDesc& b : out)
      if (std::abs(b.position.y() - (0.25f + row * 0.52f)) < 1e-4f) {
        lo = std::min(lo, b.position.x() - b.shape.halfExtents.x());
        hi = std::max(hi, b.position.x() + b.shape.halfExtents.x());
      }
    const float width = 5 * 1.0f + 4 * 0.02f;
    EXPECT_NEAR(lo, -0.5f * width, 1e-5f) << "row " << row;
    EXPECT_NEAR(hi, 0.5f * width, 1e-5f) << "row " << row;
  }
  // Stack bond: every row identical.
  p.runningBond = false;
  out.clear();
  generateWall(p, BodyPrototype{}, "w", out);
  EXPECT_EQ(out.size(), 20u);
}

TEST(Generators, DominoesStandOnTheGroundAlongTheirPath) {
  DominoParams p;
  p.count = 10;
  p.spacing = 1.0;
  p.start = Vec3d(0, 0, 0);
  p.direction = Vec3d(0, 0, 2);
  std::vector<BodyDesc> out;
  generateDominoes(p, BodyPrototype{}, "d", out);
  ASSERT_EQ(out.size(), 10u);
  for (int k = 0; k < 10; ++k) {
    EXPECT_TRUE(out[static_cast<size_t>(k)].position.isApprox(Vec3(0, 0.6f, static_cast<float>(k)), 1e-5f));
    // The thin local x axis points along the run (+z).
    EXPECT_TRUE((out[static_cast<size_t>(k)].orientation * Vec3::UnitX()).isApprox(Vec3::UnitZ(), 1e-5f));
  }
  // Arc: every domino at the radius, consecutive ones `spacing` apart along the arc.
  p.arc = true;
  p.radius = 5.0;
  p.center = Vec3d(1, 0, 1);
  p.firstTiltDeg = 20.0;
  out.clear();
  generateDominoes(p, BodyPrototype{}, "d", out);
  for (size_t k = 1; k < out.size(); ++k) {
    const Vec3 flat = out[k].position - Vec3(1, 0.6f, 1);
    EXPECT_NEAR(flat.norm(), 5.0f, 1e-4f);
    EXPECT_NEAR((out[k].position - out[k - 1].position).norm(), 2 * 5 * std::sin(0.5 / 5.0), k == 1 ? 0.5 : 1e-4);
  }
  // The tilted first domino leans towards the run and still touches the ground with its front edge.
  const Vec3 up = out[0].orientation * Vec3::UnitY();
  const Vec3 runDir(0, 0, 1);  // tangent at angle 0, growing from +x towards +z
  EXPECT_GT(up.dot(runDir), 0.3f);
  EXPECT_LT(out[0].position.y(), 0.6f);
}

TEST(Generators, PyramidCountsAndGround) {
  std::vector<BodyDesc> out;
  generatePyramid3d(Pyramid3dParams{}, BodyPrototype{}, "p", out);
  EXPECT_EQ(out.size(), 1240u);
  out.clear();
  Pyramid2dParams p2;
  p2.base = 10;
  generatePyramid2d(p2, BodyPrototype{}, "p", out);
  EXPECT_EQ(out.size(), 55u);
  out.clear();
  generateManyPyramids(ManyPyramidsParams{}, BodyPrototype{}, "m", out);
  EXPECT_EQ(out.size(), 10780u);
  out.clear();
  generateGround(GroundParams{}, BodyPrototype{}, "g", out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].motion, MotionType::Static);
  EXPECT_EQ(out[0].shape.halfExtents, Vec3(500, 1, 500));
  EXPECT_EQ(out[0].position, Vec3(0, -1, 0));
}

TEST(Generators, CustomGroundSitsBelowYZero) {
  const SceneDesc s = parseOk(R"({"generators": [{"type": "ground", "half_extents": [20, 0.5, 20], "material": "default"}]})");
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].position, Vec3(0, -0.5f, 0));
  EXPECT_EQ(s.bodies[0].where, "generators[0] #0");
}

TEST(Generators, GridCopiesTheShapeAndCommonKeys) {
  const SceneDesc s = parseOk(R"({"materials": {"rubber": {"restitution": 0.5}}, "generators": [
    {"type": "grid", "counts": [2, 3, 4], "spacing": [1, 2, 3], "origin": [10, 1, 0],
     "shape": {"type": "capsule", "radius": 0.2, "half_height": 0.3}, "material": "rubber", "mass": 2, "damping": 0.1}]})");
  ASSERT_EQ(s.bodies.size(), 24u);
  EXPECT_EQ(s.bodies[0].position, Vec3(10, 1, 0));
  EXPECT_EQ(s.bodies[1].position, Vec3(11, 1, 0));       // x fastest
  EXPECT_EQ(s.bodies[2].position, Vec3(10, 1, 3));       // then z
  EXPECT_EQ(s.bodies[23].position, Vec3(11, 5, 9));
  for (const BodyDesc& b : s.bodies) {
    EXPECT_EQ(b.shape.type, ShapeType::Capsule);
    EXPECT_EQ(b.material, 1u);
    EXPECT_EQ(b.mass, 2.0f);
    EXPECT_FLOAT_EQ(b.linearDamping, 0.1f);
  }
}

}  // namespace
}  // namespace haif::test
