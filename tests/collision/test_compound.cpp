// Compound shapes: mass properties against closed forms, and the narrow phase over parts.
#include "collision/compound.h"
#include "collision/convex_hull.h"
#include "collision_test_util.h"

#include <random>

namespace haif::test {
namespace {

std::shared_ptr<CompoundShape> compound(const std::vector<Shape>& shapes, const std::vector<Transform>& poses) {
  std::string why;
  auto c = buildCompound(shapes, poses, &why);
  EXPECT_TRUE(c) << why;
  return c;
}

void expectMatNear(const Mat3& a, const Mat3& b, float relTol) {
  const float scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), relTol * scale) << "\n" << a << "\nvs\n" << b;
}

// Two spheres of radius r at x = 1 and x = 3: centre at x = 2, each sphere's own 2/5 m r² plus m d²
// about the axes across the bar (d = 1), nothing more about the bar.
TEST(CompoundMass, DumbbellMatchesParallelAxes) {
  const float r = 0.3f;
  auto c = compound({Shape::sphere(r), Shape::sphere(r)}, {xf(Vec3(1, 0, 0)), xf(Vec3(3, 0, 0))});
  const float m = (4.0f / 3.0f) * kPi * r * r * r;
  EXPECT_NEAR(c->volume, 2.0f * m, 1e-6f);
  expectVecNear(c->centroid, Vec3(2, 0, 0), 1e-6f);
  expectVecNear(c->parts[0].local.p, Vec3(-1, 0, 0), 1e-6f);
  expectVecNear(c->parts[1].local.p, Vec3(1, 0, 0), 1e-6f);
  const float own = 0.4f * m * r * r;
  const Mat3 expected = Vec3(2 * own, 2 * (own + m), 2 * (own + m)).asDiagonal();
  expectMatNear(c->inertiaPerDensity, expected, 1e-5f);
  const MassProperties mp = computeMassProperties(Shape::compoundOf(c), 500.0f);
  EXPECT_NEAR(mp.mass, 500.0f * 2.0f * m, 1e-3f);
}

// A box cut into two halves, each turned by a quarter turn that maps its own box onto itself:
// the same mass and tensor as the whole box (the parallel-axis terms and the turns must all be right).
TEST(CompoundMass, BoxCutInTwoIsTheWholeBox) {
  const Vec3 whole(1.0f, 0.4f, 0.6f);
  const Vec3 half(0.5f, 0.4f, 0.6f);
  const Quat turn = axisAngle(Vec3::UnitX(), kPi);  // maps the half box onto itself
  auto c = compound({Shape::box(half), Shape::box(half)}, {xf(Vec3(-0.5f, 0, 0), turn), xf(Vec3(0.5f, 0, 0))});
  const MassProperties a = computeMassProperties(Shape::compoundOf(c), 1.0f);
  const MassProperties b = computeMassProperties(Shape::box(whole), 1.0f);
  EXPECT_NEAR(a.mass, b.mass, 1e-5f * b.mass);
  expectMatNear(a.inertia, b.inertia, 1e-5f);
  // Off-diagonal terms: two equal bars at (1, 0) and (0, 1) sit at ±(0.5, -0.5) from their centre,
  // so I_xy = -Σ m dx dy = 2 m / 4 (each bar's own tensor is diagonal), symmetric.
  auto l = compound({Shape::box(Vec3(1, 0.1f, 0.1f)), Shape::box(Vec3(0.1f, 1, 0.1f))},
                    {xf(Vec3(1, 0, 0)), xf(Vec3(0, 1, 0))});
  const float bar = 2.0f * 0.2f * 0.2f;
  EXPECT_NEAR(l->inertiaPerDensity(0, 1), 0.5f * bar, 1e-6f);
  EXPECT_NEAR(l->inertiaPerDensity(1, 0), 0.5f * bar, 1e-6f);
}

// A hull part sits where its points say: its own re-centring is folded into its pose.
TEST(CompoundMass, HullPartSitsWhereItsPointsSay) {
  std::vector<Vec3> pts{{2, 0, 0}, {3, 0, 0}, {2, 1, 0}, {2, 0, 1}};  // a corner tetrahedron off the origin
  auto hull = buildConvexHull(pts, nullptr);
  ASSERT_TRUE(hull);
  auto c = compound({Shape::convexHull(hull)}, {xf(Vec3(0, 5, 0))});
  const Aabb box = computeAabb(Shape::compoundOf(c), xf(c->centroid));  // the body placed as the scene would
  expectVecNear(box.lo, Vec3(2, 5, 0), 1e-5f);
  expectVecNear(box.hi, Vec3(3, 6, 1), 1e-5f);
}

TEST(CompoundMass, RefusesWhatCannotBeAPart) {
  std::string why;
  EXPECT_FALSE(buildCompound({}, {}, &why));
  EXPECT_NE(why.find("at least one part"), std::string::npos) << why;
  EXPECT_FALSE(buildCompound({Shape::box(Vec3::Ones()), Shape::plane(Vec3::UnitY(), 0)}, {xf(Vec3::Zero()), xf(Vec3::Zero())}, &why));
  EXPECT_NE(why.find("parts[1]: a plane cannot be a part"), std::string::npos) << why;
  auto inner = compound({Shape::box(Vec3::Ones())}, {xf(Vec3::Zero())});
  EXPECT_FALSE(buildCompound({Shape::compoundOf(inner)}, {xf(Vec3::Zero())}, &why));
  EXPECT_NE(why.find("a compound cannot be a part"), std::string::npos) << why;
  Transform nan = xf(Vec3::Zero());
  nan.p.x() = std::nanf("");
  EXPECT_FALSE(buildCompound({Shape::box(Vec3::Ones())}, {nan}, &why));
}

// One part at the centre: the very manifold the part alone makes, in both argument orders.
TEST(CompoundCollide, OnePartIsThePart) {
  const Shape box = Shape::box(Vec3(0.5f, 0.3f, 0.4f));
  const Shape one = Shape::compoundOf(compound({box}, {xf(Vec3::Zero())}));
  const Shape others[] = {Shape::box(Vec3(3, 0.5f, 3)), Shape::sphere(0.4f), Shape::capsule(0.2f, 0.5f)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int touching = 0;
  for (const Shape& other : others)
    for (int k = 0; k < 200; ++k) {
      const Transform xa = xf(Vec3(u(rng), 0.8f + 0.3f * u(rng), u(rng)), axisAngle(Vec3(u(rng), u(rng), u(rng)) + Vec3(0, 0.01f, 0), u(rng)));
      const Transform xb = xf(Vec3::Zero(), axisAngle(Vec3(0.1f, 1, 0), 0.3f * u(rng)));
      Manifold plain, comp;
      const int n = collide(box, xa, other, xb, 0.05f, plain);
      ASSERT_EQ(collideBoth(one, xa, other, xb, 0.05f, comp), n);
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(comp.points[i].id, plain.points[i].id);
        EXPECT_EQ(comp.points[i].depth, plain.points[i].depth);
        EXPECT_EQ(comp.points[i].position, plain.points[i].position);
      }
      touching += n > 0;
    }
  EXPECT_GT(touching, 100);  // the poses are mostly touching: the check above compared real manifolds
}

// A table (top and four legs) standing on the ground: four legs touch, and the manifold keeps a
// point under each (the deepest of every part pair before any second point of one leg).
TEST(CompoundCollide, TableKeepsAPointUnderEveryLeg) {
  std::vector<Shape> shapes{Shape::box(Vec3(1.0f, 0.05f, 0.6f))};
  std::vector<Transform> poses{xf(Vec3(0, 0.75f, 0))};
  const Vec3 legs[4] = {{-0.9f, 0.35f, -0.5f}, {0.9f, 0.35f, -0.5f}, {-0.9f, 0.35f, 0.5f}, {0.9f, 0.35f, 0.5f}};
  for (const Vec3& p : legs) {
    shapes.push_back(Shape::box(Vec3(0.05f, 0.35f, 0.05f)));
    poses.push_back(xf(p));
  }
  auto table = compound(shapes, poses);
  const Shape ground = Shape::box(Vec3(10, 1, 10));
  // Legs 1 mm into the ground, table tilted a little so one leg is deepest.
  const Transform xt = xf(table->centroid - Vec3(0, 0.001f, 0), axisAngle(Vec3(1, 0, 1), 0.002f));
  Manifold m;
  ASSERT_EQ(collideBoth(ground, xf(Vec3(0, -1, 0)), Shape::compoundOf(table), xt, 0.02f, m), 4);
  bool under[4] = {};
  for (int i = 0; i < m.count; ++i) {
    expectVecNear(m.points[i].normal, Vec3::UnitY(), 1e-4f);
    for (int k = 0; k < 4; ++k)
      if (std::abs(m.points[i].position.x() - legs[k].x()) < 0.06f && std::abs(m.points[i].position.z() - legs[k].z()) < 0.06f)
        under[k] = true;
  }
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(under[k]) << "no point under leg " << k;
}

// Two floor slabs that overlap (as a drum's wall boxes do at their seams) under a small box standing
// in the overlap: each slab reports the box's corners, and the manifold keeps each corner once.
TEST(CompoundCollide, OverlappingPartsDoNotReportATouchTwice) {
  auto floor = compound({Shape::box(Vec3(1.0f, 0.1f, 1.0f)), Shape::box(Vec3(1.0f, 0.1f, 1.0f))},
                        {xf(Vec3(-0.9f, 0, 0)), xf(Vec3(0.9f, 0, 0))});
  Manifold m;
  const int n = collideBoth(Shape::compoundOf(floor), xf(Vec3::Zero()), Shape::box(Vec3(0.05f, 0.05f, 0.05f)),
                            xf(Vec3(0.0f, 0.149f, 0.0f)), 0.02f, m);
  ASSERT_EQ(n, 4);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      EXPECT_GT((m.points[i].position - m.points[j].position).norm(), 0.05f) << "points " << i << " and " << j;
}

// Parts whose bounds miss the other shape are skipped, and only the touching part reports points.
TEST(CompoundCollide, OnlyTouchingPartsReport) {
  auto bar = compound({Shape::sphere(0.5f), Shape::box(Vec3(1.5f, 0.1f, 0.1f)), Shape::sphere(0.5f)},
                      {xf(Vec3(-2, 0, 0)), xf(Vec3::Zero()), xf(Vec3(2, 0, 0))});
  Manifold m;
  // A small sphere just touching the right ball from the right.
  ASSERT_EQ(collideBoth(Shape::compoundOf(bar), xf(Vec3::Zero()), Shape::sphere(0.2f), xf(Vec3(2.69f, 0, 0)), 0.0f, m), 1);
  expectVecNear(m.points[0].normal, Vec3::UnitX(), 1e-5f);
  EXPECT_NEAR(m.points[0].depth, 0.01f, 1e-5f);
  // Between the balls, above the bar and out of reach: nothing.
  EXPECT_EQ(collide(Shape::compoundOf(bar), xf(Vec3::Zero()), Shape::sphere(0.2f), xf(Vec3(0, 0.6f, 0)), 0.05f, m), 0);
}


// A trough of three slabs (as a drum's wall boxes meet, 22.5 degrees apart) and a box lying flat on
// the middle one, 1 cm in, its ends 3 cm short of the side slabs, all within a wide (turning drum's)
// margin. The box keeps three points on the slab it lies on, so it is held flat; one place goes to the
// nearer side slab's speculative point. With a place for every slab it kept one point on its support
// and rocked from corner to corner, a step each, through a turning drum's wall.
TEST(CompoundCollide, ABoxLyingOnOnePartKeepsItsSupportBeforeFarParts) {
  const float a = 22.5f * kPi / 180.0f, h = 0.3f, t = 0.1f;
  std::vector<Shape> slabs(3, Shape::box(Vec3(h, t, 0.5f)));
  std::vector<Transform> poses{xf(Vec3::Zero())};
  for (float side : {1.0f, -1.0f})  // the top face's inner end on the middle slab's top edge
    poses.push_back(xf(Vec3(side * (h + h * std::cos(a) + t * std::sin(a)), t + h * std::sin(a) - t * std::cos(a), 0),
                       Quat(Eigen::AngleAxisf(side * a, Vec3::UnitZ()))));
  auto trough = compound(slabs, poses);
  const Shape box = Shape::box(Vec3(0.2f, 0.06f, 0.08f));
  // 1 cm into the middle slab, tipped a little towards +x so one end is deeper.
  const Transform xb = xf(Vec3(0.02f, t + 0.06f - 0.01f, 0), Quat(Eigen::AngleAxisf(0.005f, Vec3::UnitZ())));
  Manifold m;
  ASSERT_EQ(collideBoth(Shape::compoundOf(trough), xf(trough->centroid), box, xb, 0.25f, m), 4);
  int onMiddle = 0, onSide = 0;
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& p = m.points[i];
    if (p.normal.y() > 0.999f && p.depth > 0.0f) ++onMiddle;
    if (std::abs(p.normal.x()) > 0.3f) ++onSide;
  }
  EXPECT_EQ(onMiddle, 3) << "touching points on the slab the box lies on";
  EXPECT_EQ(onSide, 1) << "speculative points against a side slab";
}

}  // namespace
}  // namespace haif::test
