// Convex hull construction (topology, mass properties, errors) and hull collisions.
#include "collision/convex_hull.h"
#include "collision/polytope.h"
#include "collision/support.h"
#include "collision_test_util.h"

#include <limits>
#include <random>
#include <set>

namespace haif {
namespace {

using test::axisAngle;
using test::collideBoth;
using test::expectAll;
using test::expectVecNear;
using test::expectSameContacts;
using test::findPoint;
using test::randomTurn;
using test::xf;

std::vector<Vec3> cubeCorners(const Vec3& h, const Vec3& centre = Vec3::Zero()) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back(centre + Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
  return p;
}

std::shared_ptr<ConvexHull> mustBuild(const std::vector<Vec3>& pts) {
  std::string err;
  auto h = buildConvexHull(pts, &err);
  EXPECT_TRUE(h) << err;
  return h;
}

// The hull of `points` random points in the unit cube about the origin (no two edges parallel, as a rule).
std::shared_ptr<ConvexHull> cloudHull(std::mt19937& rng, int points) {
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::vector<Vec3> pts;
  for (int i = 0; i < points; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return mustBuild(pts);
}

TEST(ConvexHullBuild, CubeTopologyAndMass) {
  // Cube of half extent 1 with extra interior and face-centre points that must not survive.
  auto pts = cubeCorners(Vec3(1, 1, 1), Vec3(3, -1, 2));
  pts.push_back(Vec3(3, -1, 2));
  pts.push_back(Vec3(3.2f, -0.5f, 2.1f));
  pts.push_back(Vec3(4, -1, 2));  // centre of the +x face
  auto h = mustBuild(pts);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->vertices.size(), 8u);
  EXPECT_EQ(h->faces.size(), 6u);
  EXPECT_EQ(h->edges.size(), 12u);
  EXPECT_EQ(h->faceVertices.size(), 24u);
  EXPECT_NEAR(h->volume, 8.0f, 1e-4f);
  expectVecNear(h->centroid, Vec3(3, -1, 2), 1e-5f);
  // Closed form: I = m/12 (b^2 + c^2) = 8/12 * 8 for side 2, density 1.
  const float I = 8.0f / 12.0f * 8.0f;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(h->inertiaPerDensity(r, c), r == c ? I : 0.0f, 1e-3f);
  // Vertices recentred, faces outward with offset 1 and CCW from outside.
  for (const Vec3& v : h->vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0f, 1e-5f);
  for (const auto& f : h->faces) {
    EXPECT_NEAR(f.offset, 1.0f, 1e-5f);
    EXPECT_NEAR(f.normal.cwiseAbs().maxCoeff(), 1.0f, 1e-5f);
    ASSERT_EQ(f.count, 4u);
    const Vec3 a = h->vertices[h->faceVertices[f.first]], b = h->vertices[h->faceVertices[f.first + 1]],
               c = h->vertices[h->faceVertices[f.first + 2]];
    EXPECT_GT((b - a).cross(c - b).dot(f.normal), 0.0f);
  }
  const MassProperties mp = computeMassProperties(Shape::convexHull(h), 2.0f);
  EXPECT_NEAR(mp.mass, 16.0f, 1e-3f);
}

TEST(ConvexHullBuild, BoxInertiaMatchesShapeFormula) {
  auto h = mustBuild(cubeCorners(Vec3(0.5f, 1.0f, 2.0f)));
  ASSERT_TRUE(h);
  const MassProperties hm = computeMassProperties(Shape::convexHull(h), 3.0f);
  const MassProperties bm = computeMassProperties(Shape::box(Vec3(0.5f, 1.0f, 2.0f)), 3.0f);
  EXPECT_NEAR(hm.mass, bm.mass, 1e-3f);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(hm.inertia(r, c), bm.inertia(r, c), 1e-2f);
}

TEST(ConvexHullBuild, TetrahedronCentroidAndVolume) {
  auto h = mustBuild({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->volume, 8.0f / 6.0f, 1e-5f);
  expectVecNear(h->centroid, Vec3(0.5f, 0.5f, 0.5f), 1e-5f);
  EXPECT_EQ(h->faces.size(), 4u);
  EXPECT_EQ(h->edges.size(), 6u);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : h->vertices) sum += v;
  expectVecNear(sum / 4.0f, Vec3::Zero(), 1e-5f);  // recentred
}

TEST(ConvexHullBuild, RandomSphereCloudIsConvexAndContainsAllPoints) {
  std::mt19937 rng(7);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<Vec3> pts;
  for (int i = 0; i < 300; ++i) pts.push_back(Vec3(g(rng), g(rng), g(rng)).normalized() * 2.0f);
  for (int i = 0; i < 100; ++i) pts.push_back(Vec3(g(rng), g(rng), g(rng)).normalized() * 1.0f);
  auto h = mustBuild(pts);
  ASSERT_TRUE(h);
  const float sphereVol = 4.0f / 3.0f * kPi * 8.0f;
  EXPECT_LT(h->volume, sphereVol);
  EXPECT_GT(h->volume, 0.9f * sphereVol);
  EXPECT_LT(h->centroid.norm(), 0.1f);
  // Euler: V - E + F = 2.
  EXPECT_EQ(int(h->vertices.size()) - int(h->edges.size()) + int(h->faces.size()), 2);
  for (const Vec3& p : pts)
    for (const auto& f : h->faces) EXPECT_LE(f.normal.dot(p - h->centroid) - f.offset, 1e-4f);
}

TEST(ConvexHullBuild, BadInputGivesClearErrors) {
  std::string err;
  EXPECT_EQ(buildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, &err), nullptr);
  EXPECT_NE(err.find("at least 4"), std::string::npos) << err;
  err.clear();
  EXPECT_EQ(buildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 5, 0)}, &err), nullptr);
  EXPECT_NE(err.find("coplanar"), std::string::npos) << err;
  err.clear();
  EXPECT_EQ(buildConvexHull({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)}, &err), nullptr);
  EXPECT_NE(err.find("collinear"), std::string::npos) << err;
  err.clear();
  EXPECT_EQ(buildConvexHull(std::vector<Vec3>(5, Vec3(1, 2, 3)), &err), nullptr);
  EXPECT_NE(err.find("coincide"), std::string::npos) << err;
  err.clear();
  auto pts = cubeCorners(Vec3(1, 1, 1));
  pts[5].y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(buildConvexHull(pts, &err), nullptr);
  EXPECT_NE(err.find("point 5"), std::string::npos) << err;
  EXPECT_EQ(buildConvexHull(pts, nullptr), nullptr);  // no error string requested: still no crash
}

// A hull built from a box's corners collides exactly like the box.
TEST(HullCollision, CubeHullBehavesLikeBox) {
  auto h = mustBuild(cubeCorners(Vec3::Constant(0.5f)));
  ASSERT_TRUE(h);
  const Shape hull = Shape::convexHull(h);
  const Shape box = Shape::box(Vec3::Constant(0.5f));
  struct Case { Transform ta, tb; };
  const Case cases[] = {
      {xf(Vec3::Zero()), xf(Vec3(0.2f, 0.95f, -0.1f))},
      {xf(Vec3::Zero()), xf(Vec3(0.0f, 0.98f, 0.0f), axisAngle(Vec3::UnitY(), 0.6f))},
      {xf(Vec3(1, 2, 3), axisAngle(Vec3(1, 1, 0), 0.4f)), xf(Vec3(1, 2, 3) + axisAngle(Vec3(1, 1, 0), 0.4f) * Vec3(0.9f, 0.3f, 0), axisAngle(Vec3(1, 1, 0), 0.4f))},
      {xf(Vec3::Zero(), axisAngle(Vec3::UnitZ(), kPi / 4)), xf(Vec3(0, std::sqrt(2.0f) - 0.1f, 0), axisAngle(Vec3::UnitX(), kPi / 4))},
  };
  for (const Case& c : cases) {
    Manifold mb, mh, mhb;
    const int nb = collide(box, c.ta, box, c.tb, 0.01f, mb);
    ASSERT_EQ(collideBoth(hull, c.ta, hull, c.tb, 0.01f, mh), nb);
    ASSERT_EQ(collideBoth(box, c.ta, hull, c.tb, 0.01f, mhb), nb);
    for (int i = 0; i < nb; ++i) {
      const int k = findPoint(mh, mb.points[i].position, 1e-4f);
      const int k2 = findPoint(mhb, mb.points[i].position, 1e-4f);
      ASSERT_GE(k, 0);
      ASSERT_GE(k2, 0);
      EXPECT_NEAR(mh.points[k].depth, mb.points[i].depth, 1e-4f);
      expectVecNear(mh.points[k].normal, mb.points[i].normal, 1e-4f);
      EXPECT_NEAR(mhb.points[k2].depth, mb.points[i].depth, 1e-4f);
    }
  }
}

TEST(HullCollision, IdsStableAndSeparation) {
  auto h = mustBuild(cubeCorners(Vec3::Constant(0.5f)));
  ASSERT_TRUE(h);
  const Shape hull = Shape::convexHull(h);
  Manifold m1, m2;
  ASSERT_EQ(collide(hull, xf(Vec3::Zero()), hull, xf(Vec3(0.1f, 0.99f, 0.05f)), 0.0f, m1), 4);
  ASSERT_EQ(collide(hull, xf(Vec3(0, 1e-4f, 0)), hull, xf(Vec3(0.1002f, 0.9902f, 0.0501f), axisAngle(Vec3(1, 2, 3), 1e-3f)), 0.0f, m2), 4);
  std::set<uint32_t> a, b;
  for (int i = 0; i < 4; ++i) { a.insert(m1.points[i].id); b.insert(m2.points[i].id); }
  EXPECT_EQ(a.size(), 4u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(collide(hull, xf(Vec3::Zero()), hull, xf(Vec3(0.1f, 1.2f, 0)), 0.1f, m1), 0);
  ASSERT_EQ(collide(hull, xf(Vec3::Zero()), hull, xf(Vec3(0.1f, 1.05f, 0)), 0.1f, m1), 4);
  expectAll(m1, Vec3::UnitY(), -0.05f, 1e-5f);
}

TEST(HullCollision, SphereAgainstHull) {
  auto h = mustBuild({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2)});
  ASSERT_TRUE(h);
  const Shape hull = Shape::convexHull(h);
  // Hull body placed so its input frame coincides with the world: origin at the centroid.
  const Transform th = xf(h->centroid);
  Manifold m;
  // Above the slanted face x + y + z = 2.
  const Vec3 n = Vec3(1, 1, 1).normalized();
  const Vec3 onFace(2.0f / 3, 2.0f / 3, 2.0f / 3);
  ASSERT_EQ(collideBoth(Shape::sphere(0.5f), xf(onFace + 0.4f * n), hull, th, 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  expectVecNear(m.points[0].normal, -n, 1e-5f);  // sphere (a) towards hull (b)
  expectVecNear(m.points[0].position, onFace - 0.05f * n, 1e-5f);  // surfaces at onFace and onFace - 0.1n
  // Near the vertex (2,0,0), beyond it along +x.
  ASSERT_EQ(collide(hull, th, Shape::sphere(0.5f), xf(Vec3(2.45f, 0, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitX(), 1e-5f);
  // Centre inside the hull, nearest face z = 0: pushed along -z, depth = 0.1 + r.
  ASSERT_EQ(collide(hull, th, Shape::sphere(0.3f), xf(Vec3(0.4f, 0.5f, 0.1f)), 0.0f, m), 1);
  expectVecNear(m.points[0].normal, -Vec3::UnitZ(), 1e-5f);
  EXPECT_NEAR(m.points[0].depth, 0.4f, 1e-5f);
  // Separated beyond margin.
  EXPECT_EQ(collide(hull, th, Shape::sphere(0.5f), xf(Vec3(-0.7f, 0.5f, 0.5f)), 0.1f, m), 0);
}

TEST(HullCollision, CapsuleLyingOnHull) {
  auto h = mustBuild(cubeCorners(Vec3(2, 0.5f, 2)));
  ASSERT_TRUE(h);
  const Shape hull = Shape::convexHull(h);
  const Shape cap = Shape::capsule(0.25f, 0.75f);
  Manifold m;
  ASSERT_EQ(collideBoth(hull, xf(Vec3::Zero()), cap, xf(Vec3(0.5f, 0.73f, 1.0f), axisAngle(Vec3::UnitZ(), kPi / 2)), 0.0f, m), 2);
  expectAll(m, Vec3::UnitY(), 0.02f, 1e-5f);
  EXPECT_GE(findPoint(m, Vec3(1.25f, 0.49f, 1.0f), 1e-5f), 0);
}

TEST(HullCollision, OctahedronPointDownOnBox) {
  // Octahedron vertex pointing into a box face: one point at the tip.
  auto h = mustBuild({Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->volume, 4.0f / 3.0f, 1e-5f);
  EXPECT_EQ(h->faces.size(), 8u);
  Manifold m;
  ASSERT_EQ(collideBoth(Shape::box(Vec3(2, 0.5f, 2)), xf(Vec3::Zero()), Shape::convexHull(h), xf(Vec3(0.3f, 1.45f, 0)), 0.0f, m), 1);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  expectVecNear(m.points[0].normal, Vec3::UnitY(), 1e-5f);
  expectVecNear(m.points[0].position, Vec3(0.3f, 0.475f, 0), 1e-5f);
}

// Regression (stress scene pile_10000: a 9 m "penetration" of 0.3 m bodies): an 11-vertex hull from the
// pile just above the 1000 m ground box. Its face most anti-parallel to the ground normal does not hold
// its lowest vertex, so every vertex of that incident face lay beyond the margin, clipping kept nothing
// and the edge-pair fallback reported an axis tilted 0.6 degrees from vertical, on which the 1000 m box
// projects 5.6 m long: depth 5.5 m. The known answer is the lowest vertex's height, a vertex-face gap.
TEST(HullCollision, HullVertexJustAboveHugeBoxIsAGapNotAPenetration) {
  const std::vector<Vec3> pts = {
      {-0.159283653f, 0.105807841f, -0.0791489333f}, {-0.0134383524f, -0.00647925958f, 0.212480605f},
      {-0.0134383524f, 0.2130972f, -0.0104417438f},  {-0.0134383524f, -0.00647925958f, -0.156291172f},
      {-0.0134383524f, -0.211989671f, -0.0104417438f}, {0.147544757f, 0.0680003092f, -0.104481153f},
      {-0.0892515853f, -0.140549675f, 0.105268709f}, {0.130980939f, -0.113300614f, -0.0442552082f},
      {0.163279995f, -0.00647925958f, -0.0104417438f}, {0.13526693f, 0.0398818962f, 0.01854771f},
      {-0.148845315f, -0.00647925958f, -0.0104417438f}};
  auto h = mustBuild(pts);
  ASSERT_TRUE(h);
  const Shape ground = Shape::box(Vec3(500.0f, 1.0f, 500.0f));
  const Transform xg = xf(Vec3(0.0f, -1.0f, 0.0f));
  const Transform xh = xf(Vec3(-2.96993995f, 0.181302547f, -5.09772635f),
                          Quat(-0.549479544f, -0.563578963f, -0.381894618f, -0.48436299f));
  float lowest = 1e30f;
  for (const Vec3& v : h->vertices) lowest = std::min(lowest, xh.apply(v).y());
  ASSERT_GT(lowest, 0.03f);  // the hull hovers 3.7 cm above the ground: a gap
  // 4 cm: only the lowest vertex is in reach (the pile's case); 10 cm: the incident face is too, but it
  // sits 4.6 mm higher, so the contact was reported that much too far away.
  for (float margin : {0.04f, 0.1f}) {
    Manifold m;
    ASSERT_GE(collideBoth(ground, xg, Shape::convexHull(h), xh, margin, m), 1) << "margin " << margin;
    float deepest = -1e30f;
    for (int i = 0; i < m.count; ++i) {
      expectVecNear(m.points[i].normal, Vec3::UnitY(), 1e-4f);
      EXPECT_LE(m.points[i].depth, -lowest + 1e-4f) << "point " << i << ", margin " << margin;
      deepest = std::max(deepest, m.points[i].depth);
    }
    EXPECT_NEAR(deepest, -lowest, 1e-4f) << "margin " << margin;
  }
}

// The separating-axis tests read a hull's vertices by coordinate, made once when the hull is built.
// They must hold every vertex, padded with vertex 0, and give the same contacts as lanes made per pair.
TEST(HullCollision, VertexLanesMadeOnceGiveTheContactsOfLanesMadePerPair) {
  std::mt19937 rng(68);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  int touching = 0;
  for (int h = 0; h < 6; ++h) {
    auto a = cloudHull(rng, 6 + 3 * h), b = cloudHull(rng, 9 + 2 * h);
    ASSERT_TRUE(a && b);
    const int lanes = ConvexHull::vertexLaneCount(a->vertices.size());
    ASSERT_EQ(a->vertexLanes.size(), 3u * size_t(lanes));
    EXPECT_EQ(lanes % ConvexHull::kVertexLaneWidth, 0);
    for (int i = 0; i < lanes; ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(a->vertexLanes[size_t(k * lanes + i)], a->vertices[i < int(a->vertices.size()) ? i : 0][k]);
    const detail::PolyView made = detail::hullView(*a), other = detail::hullView(*b);
    ASSERT_NE(made.vertexLanes, nullptr);
    detail::PolyView perPair = made;
    perPair.vertexLanes = nullptr;
    for (int k = 0; k < 200; ++k) {
      Transform xa, xb;
      xa.q = randomTurn(rng);
      xb.q = randomTurn(rng);
      xb.p = Vec3(u(rng), u(rng), u(rng)) * 1.5f;
      Manifold m1, m2;
      touching += detail::collidePolyPoly(made, xa, other, xb, 0.02f, m1) > 0;
      detail::collidePolyPoly(perPair, xa, other, xb, 0.02f, m2);
      expectSameContacts(m2, m1);
    }
  }
  EXPECT_GT(touching, 300);  // most poses touch: the clipping, not only the early outs, is compared
}

// An edge contact takes, among the edges parallel to the one its axis came from, the one that supports
// the shape. A hull with no two edges parallel skips that search: the same contacts as searching.
TEST(HullCollision, HullsWithoutParallelEdgesSkipTheSupportingEdgeSearch) {
  EXPECT_TRUE(mustBuild(cubeCorners(Vec3(0.3f, 0.2f, 0.1f)))->parallelEdges);
  std::mt19937 rng(70);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  int skipping = 0, edgeContacts = 0;
  for (int h = 0; h < 6; ++h) {
    auto a = cloudHull(rng, 8 + 3 * h), b = cloudHull(rng, 10 + 2 * h);
    ASSERT_TRUE(a && b);
    skipping += !a->parallelEdges;
    const detail::PolyView own = detail::hullView(*a), other = detail::hullView(*b);
    detail::PolyView searching = own;
    searching.parallelEdges = true;
    for (int k = 0; k < 300; ++k) {
      Transform xa, xb;
      xa.q = randomTurn(rng);
      xb.q = randomTurn(rng);
      xb.p = Vec3(u(rng), u(rng), u(rng)) * 1.6f;
      Manifold m1, m2;
      const int n1 = detail::collidePolyPoly(own, xa, other, xb, 0.02f, m1);
      detail::collidePolyPoly(searching, xa, other, xb, 0.02f, m2);
      expectSameContacts(m2, m1);
      edgeContacts += n1 == 1 && (m1.points[0].id & 0x40000000u) != 0;
    }
  }
  EXPECT_GE(skipping, 4);        // random clouds have no parallel edges
  EXPECT_GT(edgeContacts, 100);  // and the edge contacts are among the poses compared
  // Boxes built as hulls have parallel edges: the search runs, and their edge contacts are box-box's.
  const Vec3 ha(0.3f, 0.2f, 0.1f), hb(0.25f, 0.15f, 0.2f);
  const Shape hullA = Shape::convexHull(mustBuild(cubeCorners(ha))), hullB = Shape::convexHull(mustBuild(cubeCorners(hb)));
  const Shape boxA = Shape::box(ha), boxB = Shape::box(hb);
  int boxEdges = 0;
  for (int k = 0; k < 600; ++k) {
    const Transform xa = xf(Vec3::Zero(), randomTurn(rng)), xb = xf(Vec3(u(rng), u(rng), u(rng)) * 1.0f, randomTurn(rng));
    Manifold asHulls, asBoxes;
    if (collide(hullA, xa, hullB, xb, 0.02f, asHulls) != 1 || (asHulls.points[0].id & 0x40000000u) == 0) continue;
    ASSERT_GT(collide(boxA, xa, boxB, xb, 0.02f, asBoxes), 0);
    ++boxEdges;
    EXPECT_NEAR(asHulls.points[0].depth, asBoxes.nearest(), 1e-4f);
  }
  EXPECT_GT(boxEdges, 20);
}

// A pair kept apart by an axis notes it in its manifold (Manifold::apartAxis): a face, or for two
// polyhedra an edge pair. The next collision tests that axis first. A noted axis must keep the pair
// apart beyond the margin (checked here from the shapes' supports, not by the routine); a face noted
// gives the contacts of a manifold without a note; an edge pair noted at another pose either changes
// nothing or holds the pair apart beyond the margin along its axis.
TEST(HullCollision, ApartAxisNotedKeepsThePairApart) {
  std::mt19937 rng(69);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::normal_distribution<float> g(0.0f, 1.0f);  // pile directions
  auto ha = cloudHull(rng, 14), hb = cloudHull(rng, 20);
  ASSERT_TRUE(ha && hb);
  // Hull-hull, box-hull and hull-box (collide swaps it), capsule-hull, sphere-hull, capsule-box.
  const Shape hullA = Shape::convexHull(ha), hullB = Shape::convexHull(hb), box = Shape::box(Vec3(0.3f, 0.2f, 0.4f));
  const Shape capsule = Shape::capsule(0.15f, 0.3f), sphere = Shape::sphere(0.25f);
  const std::pair<const Shape*, const Shape*> pairs[] = {{&hullA, &hullB}, {&box, &hullB}, {&hullA, &box},
                                                         {&capsule, &hullB}, {&sphere, &hullA}, {&capsule, &box}};
  // The polyhedra a note numbers faces and edges of, in the pair routine's order (collide puts the
  // box first; a core's routine numbers the polyhedron's faces only).
  const detail::BoxPoly boxPoly(box.halfExtents);
  auto poly = [&](const Shape* s) { return s == &box ? boxPoly.view() : detail::hullView(*s->hull); };
  auto routineOrder = [&](const Shape* sa, const Shape* sb) -> std::pair<const Shape*, const Shape*> {
    if (sa == &capsule || sa == &sphere) return {sb, nullptr};
    return sb == &box ? std::make_pair(sb, sa) : std::make_pair(sa, sb);
  };
  const float margin = 0.02f;
  // How far apart the two shapes are along the noted axis, from their supports in world space.
  auto apartAlongNote = [&](const Shape* sa, const Transform& xa, const Shape* sb, const Transform& xb, uint32_t note) {
    const auto [first, second] = routineOrder(sa, sb);
    const Transform& xFirst = first == sa ? xa : xb;
    auto apartAlong = [&](const Vec3& n) {  // b beyond a along n, or a beyond b
      return std::max(-supportAlong(*sb, xb, -n) - supportAlong(*sa, xa, n),
                      -supportAlong(*sa, xa, -n) - supportAlong(*sb, xb, n));
    };
    const detail::PolyView p1 = poly(first);
    if ((note & 0xC0000000u) == 0x40000000u) {  // an edge of the first, an edge of the second
      const detail::PolyView p2 = poly(second);
      const Transform& xSecond = second == sa ? xa : xb;
      const auto e1 = p1.edges[(note >> 15) & 0x7FFFu], e2 = p2.edges[note & 0x7FFFu];
      const Vec3 d1 = xFirst.q * (p1.verts[e1.second] - p1.verts[e1.first]);
      const Vec3 d2 = xSecond.q * (p2.verts[e2.second] - p2.verts[e2.first]);
      return apartAlong(d1.cross(d2).normalized());
    }
    const bool inFirst = note < uint32_t(p1.numFaces);
    const Shape* owner = inFirst ? first : second;
    const ConvexHull::Face& F = inFirst ? p1.faces[note] : poly(second).faces[note - uint32_t(p1.numFaces)];
    return apartAlong((owner == sa ? xa : xb).q * F.normal);
  };
  int noted = 0, edgeNotes = 0, apart = 0, touching = 0;
  for (const auto& [sa, sb] : pairs) {
    std::vector<uint32_t> seenEdgeNotes;
    for (int k = 0; k < 400; ++k) {
      Transform xa, xb;
      xa.q = randomTurn(rng);
      xb.q = randomTurn(rng);
      xa.p = Vec3(u(rng), u(rng), u(rng));
      xb.p = xa.p + Vec3(u(rng), u(rng), u(rng)) * 2.5f;
      if (k % 2 == 0) {  // as a pile's pairs: out along a random direction to where they touch, then 0-3 cm on
        const Vec3 d = Vec3(g(rng), g(rng), g(rng)).normalized();
        float lo = 0.0f, hi = 4.0f;
        Manifold probe;
        for (int it = 0; it < 30; ++it) {
          const float mid = 0.5f * (lo + hi);
          xb.p = xa.p + mid * d;
          (collide(*sa, xa, *sb, xb, 0.0f, probe) > 0 ? lo : hi) = mid;
        }
        xb.p = xa.p + (hi + 0.03f * (u(rng) + 0.5f)) * d;
      }
      Manifold fresh;
      const int n = collide(*sa, xa, *sb, xb, margin, fresh);
      touching += n > 0;
      apart += n == 0;
      if (fresh.apartAxis != kNoApartAxis) {
        ++noted;
        EXPECT_EQ(n, 0);
        EXPECT_GT(apartAlongNote(sa, xa, sb, xb, fresh.apartAxis), margin - 1e-5f);
        if (fresh.apartAxis & 0x40000000u) {
          ++edgeNotes;
          seenEdgeNotes.push_back(fresh.apartAxis);
        }
      }
      // Faces (and notes naming nothing): the contacts of a fresh manifold.
      for (const uint32_t note : {fresh.apartAxis, uint32_t(k % 40), uint32_t(k % 7), kNoApartAxis, 0x7FFFFFFFu}) {
        Manifold m;
        m.apartAxis = note;
        collide(*sa, xa, *sb, xb, margin, m);
        SCOPED_TRACE(testing::Message() << "note " << note);
        expectSameContacts(m, fresh);
        if (m.apartAxis != kNoApartAxis) {
          EXPECT_GT(apartAlongNote(sa, xa, sb, xb, m.apartAxis), margin - 1e-5f);
        }
      }
      // An edge pair noted at another pose: the same contacts, or none because its axis holds the
      // pair apart beyond the margin here too.
      if (!seenEdgeNotes.empty()) {
        Manifold m;
        m.apartAxis = seenEdgeNotes[size_t(k) % seenEdgeNotes.size()];
        const int got = collide(*sa, xa, *sb, xb, margin, m);
        if (got != n) {
          EXPECT_EQ(got, 0);
          EXPECT_GT(apartAlongNote(sa, xa, sb, xb, m.apartAxis), margin - 1e-5f);
        } else {
          expectSameContacts(m, fresh);
        }
      }
    }
  }
  EXPECT_GT(noted, 600);     // most apart poses are kept apart by a noted axis
  EXPECT_GT(edgeNotes, 50);  // of them some by an edge pair
  EXPECT_GT(touching, 300);  // and the clipping and closest-feature paths are compared too
  EXPECT_GT(apart, noted);   // some apart poses are told apart by the closest features
}

}  // namespace
}  // namespace haif
