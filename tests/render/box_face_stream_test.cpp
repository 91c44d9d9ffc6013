// BoxFaceStream: the camera stream holds exactly the faces turned to the eye (minus the skipped
// ones), split by the sun, with corners on the box, wound counter-clockwise from outside and edge
// distances that reach zero on the edges; the shadow stream holds the three faces turned to the sun.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/box_face_stream.h"

namespace haif::render {
namespace {

BoxPose box(Vec3 c, Vec3 half) {
  BoxPose b;
  b.center = c;
  b.half = half;
  return b;
}

// Rotation by `degrees` about the unit axis (ax, ay, az).
void turn(BoxPose& b, float degrees, float ax, float ay, float az) {
  const float h = 0.5f * degrees * 3.14159265f / 180.f;
  b.orientation[0] = ax * std::sin(h), b.orientation[1] = ay * std::sin(h), b.orientation[2] = az * std::sin(h);
  b.orientation[3] = std::cos(h);
}

Vec3 at(const float* v) { return {v[0], v[1], v[2]}; }

// Position of p in the box's own frame (metres).
Vec3 local(const BoxPose& b, Vec3 p) {
  const float inv[4] = {-b.orientation[0], -b.orientation[1], -b.orientation[2], b.orientation[3]};
  return rotate(inv, p - b.center);
}

// Checks one quad of the camera stream against its box: corners on the face its normal names,
// counter-clockwise seen from outside, edge distances matching the corner's place on the face.
void expectFaceOnBox(const BoxFaceVertex* q, const BoxPose& b) {
  const Vec3 n = at(q[0].normal);
  EXPECT_NEAR(length(n), 1.f, 1e-5f);
  const Vec3 winding = cross(at(q[1].position) - at(q[0].position), at(q[2].position) - at(q[0].position));
  EXPECT_GT(dot(winding, n), 0.f) << "counter-clockwise seen from outside";
  const Vec3 half = b.half;
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = local(b, at(q[k].position));
    EXPECT_NEAR(std::fabs(p.x), half.x, 1e-4f);
    EXPECT_NEAR(std::fabs(p.y), half.y, 1e-4f);
    EXPECT_NEAR(std::fabs(p.z), half.z, 1e-4f);
    // Every corner lies on two edges of its face and is a full side away from the other two.
    int zero = 0, full = 0;
    for (float e : q[k].edge) {
      zero += std::fabs(e) < 1e-5f;
      full += std::fabs(e - 2.f * half.x) < 1e-4f || std::fabs(e - 2.f * half.y) < 1e-4f ||
              std::fabs(e - 2.f * half.z) < 1e-4f;
    }
    EXPECT_EQ(zero, 2);
    EXPECT_EQ(full, 2);
    EXPECT_FLOAT_EQ(q[k].edgeWidth, 0.03f * std::fmin(half.x, std::fmin(half.y, half.z)));
    for (int j = 0; j < 3; ++j) EXPECT_EQ(q[k].normal[j], q[0].normal[j]) << "one normal per face";
  }
}

TEST(BoxFaceStream, CameraFacesAreThoseTurnedToTheEyeSplitBySun) {
  BoxFaceStream s;
  const BoxPose b = box({1.f, 0.5f, -2.f}, {0.5f, 0.5f, 0.5f});
  const Vec3 eye{4.f, 3.f, 2.f};  // sees +x, +y, +z
  const Vec3 sun = normalize({-0.2f, 1.f, -0.1f});  // lights +y only of those
  s.addCameraFaces(b, {0.2f, 0.4f, 0.6f}, 0, eye, sun);
  ASSERT_EQ(s.sunwardFaces(), 1u);
  ASSERT_EQ(s.awayFaces(), 2u);
  EXPECT_NEAR(s.sunwardVertices()[0].normal[1], 1.f, 1e-6f);
  EXPECT_EQ(s.sunwardVertices()[0].color[2], 0.6f);
  for (size_t f = 0; f < 2; ++f) {
    const BoxFaceVertex* q = &s.awayVertices()[4 * f];
    EXPECT_GT(dot(at(q[0].normal), eye - at(q[0].position)), 0.f) << "turned to the eye";
    EXPECT_LE(dot(at(q[0].normal), sun), 0.f) << "turned from the sun";
    expectFaceOnBox(q, b);
  }
  expectFaceOnBox(s.sunwardVertices().data(), b);

  // Skipped faces (hidden inside a neighbour or behind other boxes) are left out.
  s.clear();
  s.addCameraFaces(b, {1.f, 1.f, 1.f}, boxFaceBit(1, 1) | boxFaceBit(0, 1), eye, sun);
  EXPECT_EQ(s.sunwardFaces(), 0u);
  ASSERT_EQ(s.awayFaces(), 1u);
  EXPECT_NEAR(s.awayVertices()[0].normal[2], 1.f, 1e-6f);
}

TEST(BoxFaceStream, TurnedFlatBoxKeepsItsCornersAndWinding) {
  BoxFaceStream s;
  BoxPose b = box({0.f, 2.f, 0.f}, {1.5f, 0.25f, 0.75f});
  turn(b, 37.f, 0.f, 0.6f, 0.8f);
  const Vec3 eye{-3.f, 6.f, 5.f};
  s.addCameraFaces(b, {1.f, 0.f, 0.f}, 0, eye, normalize({-0.45f, 0.82f, -0.3f}));
  const size_t faces = s.sunwardFaces() + s.awayFaces();
  EXPECT_GE(faces, 1u);
  EXPECT_LE(faces, 3u) << "a convex box shows at most three faces";
  for (const auto* list : {&s.sunwardVertices(), &s.awayVertices()})
    for (size_t f = 0; f < list->size() / 4; ++f) {
      const BoxFaceVertex* q = &(*list)[4 * f];
      expectFaceOnBox(q, b);
      EXPECT_GT(dot(at(q[0].normal), eye - at(q[0].position)), 0.f);
    }
  // Seen from the opposite side, the other faces come (none twice, none missing).
  BoxFaceStream back;
  back.addCameraFaces(b, {1.f, 0.f, 0.f}, 0, b.center * 2.f - eye, normalize({-0.45f, 0.82f, -0.3f}));
  EXPECT_EQ(faces + back.sunwardFaces() + back.awayFaces(), 6u);
}

TEST(BoxFaceStream, ShadowFacesAreTheThreeTurnedToTheSun) {
  BoxFaceStream s;
  BoxPose b = box({0.f, 1.f, 0.f}, {0.5f, 1.f, 0.25f});
  turn(b, 20.f, 1.f, 0.f, 0.f);
  const Vec3 sun = normalize({-0.45f, 0.82f, -0.3f});
  s.addShadowFaces(b, 0, sun);
  ASSERT_EQ(s.shadowFaces(), 3u);
  ASSERT_EQ(s.shadowPositions().size(), 36u);
  for (size_t f = 0; f < 3; ++f) {
    Vec3 c{0.f, 0.f, 0.f};
    for (int k = 0; k < 4; ++k) {
      const float* p = &s.shadowPositions()[12 * f + 3 * k];
      c = c + local(b, {p[0], p[1], p[2]}) * 0.25f;
    }
    // The face centre (box frame) sits on one axis at the half extent; that side faces the sun.
    const Vec3 toSunLocal = local(b, b.center + sun);
    const float cs[3] = {c.x, c.y, c.z}, hs[3] = {b.half.x, b.half.y, b.half.z};
    const float ts[3] = {toSunLocal.x, toSunLocal.y, toSunLocal.z};
    int onAxis = 0;
    for (int a = 0; a < 3; ++a)
      if (std::fabs(std::fabs(cs[a]) - hs[a]) < 1e-4f) {
        ++onAxis;
        EXPECT_GT(cs[a] * ts[a], 0.f) << "face " << f << " axis " << a << " is turned to the sun";
      }
    EXPECT_EQ(onAxis, 1);
  }
  s.clear();
  s.addShadowFaces(b, boxFaceBit(1, 1), sun);  // the top faces the sun and is skipped
  EXPECT_EQ(s.shadowFaces(), 2u);
  s.addShadowFaces(b, boxFaceBit(1, -1), sun);  // the bottom does not face it: nothing to skip
  EXPECT_EQ(s.shadowFaces(), 5u);
}

TEST(BoxFaceStream, QuadIndicesGrowWithoutRepeating) {
  std::vector<uint32_t> idx;
  BoxFaceStream::growQuadIndices(2, idx);
  EXPECT_EQ(idx, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}));
  BoxFaceStream::growQuadIndices(3, idx);
  ASSERT_EQ(idx.size(), 18u);
  EXPECT_EQ(idx[12], 8u);
  EXPECT_EQ(idx[17], 11u);
  BoxFaceStream::growQuadIndices(1, idx);  // never shrinks
  EXPECT_EQ(idx.size(), 18u);
}

}  // namespace
}  // namespace haif::render
