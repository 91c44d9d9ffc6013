// HiddenBoxFaces: exactly the faces pressed against a neighbour (or the ground) are hidden, and
// nothing that could be seen is: gaps, overhangs, tilted boxes and overlapping twins keep theirs.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/hidden_box_faces.h"

namespace haif::render {
namespace {

BoxPose box(float x, float y, float z, float hx = 0.5f, float hy = 0.5f, float hz = 0.5f) {
  BoxPose b;
  b.center = {x, y, z};
  b.half = {hx, hy, hz};
  return b;
}

// Rotation by `degrees` about the unit axis (ax, ay, az).
void turn(BoxPose& b, float degrees, float ax, float ay, float az) {
  const float h = 0.5f * degrees * 3.14159265f / 180.f;
  b.orientation[0] = ax * std::sin(h), b.orientation[1] = ay * std::sin(h), b.orientation[2] = az * std::sin(h);
  b.orientation[3] = std::cos(h);
}

const BoxPose kGround = box(0.f, -1.f, 0.f, 500.f, 1.f, 500.f);
const uint8_t kPosX = boxFaceBit(0, 1), kNegX = boxFaceBit(0, -1);
const uint8_t kPosY = boxFaceBit(1, 1), kNegY = boxFaceBit(1, -1);

std::vector<uint8_t> masksOf(const std::vector<BoxPose>& boxes) {
  HiddenBoxFaces finder;
  std::vector<uint8_t> masks;
  finder.find(boxes, masks);
  EXPECT_EQ(masks.size(), boxes.size());
  return masks;
}

TEST(HiddenBoxFaces, FaceBitsFollowTheBoxMeshOrder) {
  EXPECT_EQ(boxFaceBit(0, -1), 1u);
  EXPECT_EQ(boxFaceBit(0, 1), 2u);
  EXPECT_EQ(boxFaceBit(1, -1), 4u);
  EXPECT_EQ(boxFaceBit(2, 1), 32u);
}

TEST(HiddenBoxFaces, TwoSideBySideAndOneOnTopHideExactlyTheTouchingFaces) {
  // Left and right cubes on the ground touching along x; a third cube resting on the left one.
  const std::vector<BoxPose> boxes = {kGround, box(0.f, 0.5f, 0.f), box(1.f, 0.5f, 0.f), box(0.f, 1.5f, 0.f)};
  const std::vector<uint8_t> m = masksOf(boxes);
  EXPECT_EQ(m[0], 0u) << "the ground's top face is seen around the boxes";
  EXPECT_EQ(m[1], kPosX | kPosY | kNegY) << "left: faces against the right cube, the top cube and the ground";
  EXPECT_EQ(m[2], kNegX | kNegY) << "right: face against the left cube and the ground";
  EXPECT_EQ(m[3], kNegY) << "top: only the face resting on the left cube";
}

TEST(HiddenBoxFaces, SmallContactErrorsCountButVisibleGapsDoNot) {
  const float tol = HiddenBoxFaces::tolerance({0.5f, 0.5f, 0.5f});
  EXPECT_GT(tol, 0.f);
  // A hair of gap or of overlap between the stacked cubes: still hidden.
  for (float gap : {0.5f * tol, -0.5f * tol, -0.2f}) {
    const std::vector<uint8_t> m = masksOf({box(0.f, 0.5f, 0.f), box(0.f, 1.5f + gap, 0.f)});
    EXPECT_EQ(m[0], kPosY) << "gap " << gap;
    EXPECT_EQ(m[1], kNegY) << "gap " << gap;
  }
  // A gap one can see through keeps both faces.
  const std::vector<uint8_t> m = masksOf({box(0.f, 0.5f, 0.f), box(0.f, 1.5f + 3.f * tol, 0.f)});
  EXPECT_EQ(m[0], 0u);
  EXPECT_EQ(m[1], 0u);
}

TEST(HiddenBoxFaces, OverhangsKeepTheUncoveredFace) {
  // A smaller cube on a big one: its bottom is hidden, the big top face is partly visible.
  std::vector<uint8_t> m = masksOf({box(0.f, 1.f, 0.f, 1.f, 1.f, 1.f), box(0.3f, 2.25f, 0.f, 0.25f, 0.25f, 0.25f)});
  EXPECT_EQ(m[0], 0u);
  EXPECT_EQ(m[1], kNegY);
  // Equal cubes shifted sideways by a fifth: each face pokes out of the other.
  m = masksOf({box(0.f, 0.5f, 0.f), box(0.2f, 1.5f, 0.f)});
  EXPECT_EQ(m[0], 0u);
  EXPECT_EQ(m[1], 0u);
}

TEST(HiddenBoxFaces, TiltedBoxHidesNothing) {
  // A cube tilted about z leaning against the side of another with one edge: no face is shared.
  BoxPose tilted = box(1.16f, 0.8f, 0.f);
  turn(tilted, 25.f, 0.f, 0.f, 1.f);
  const std::vector<uint8_t> m = masksOf({kGround, box(0.f, 0.5f, 0.f), tilted});
  EXPECT_EQ(m[1], kNegY) << "the upright cube still rests on the ground";
  EXPECT_EQ(m[2], 0u);
  // A cube turned about y on top of another still hides its bottom (it lies inside the lower
  // cube's top face), but the lower top face pokes out and stays.
  BoxPose turned = box(0.f, 1.5f, 0.f, 0.3f, 0.5f, 0.3f);
  turn(turned, 45.f, 0.f, 1.f, 0.f);
  const std::vector<uint8_t> m2 = masksOf({box(0.f, 0.5f, 0.f), turned});
  EXPECT_EQ(m2[0], 0u);
  EXPECT_EQ(m2[1], kNegY);
}

TEST(HiddenBoxFaces, OverlappingTwinsDoNotHideEachOther) {
  // Two cubes in the same place: every face of one lies in the other, yet both must be drawn.
  std::vector<uint8_t> m = masksOf({box(0.f, 0.5f, 0.f), box(0.f, 0.5f, 0.f)});
  EXPECT_EQ(m[0], 0u);
  EXPECT_EQ(m[1], 0u);
  // Deeply overlapping side by side with coplanar tops: the tops stay.
  m = masksOf({box(0.f, 0.5f, 0.f), box(0.1f, 0.5f, 0.f)});
  EXPECT_EQ(m[0] & kPosY, 0u);
  EXPECT_EQ(m[1] & kPosY, 0u);
}

TEST(HiddenBoxFaces, ManyStacksFindEveryInnerFace) {
  // 30 stacks of 10 cubes 3 m apart on the ground: every face between two cubes and every bottom
  // is hidden, every side and the top of each stack is not; exercises the grid with many boxes.
  std::vector<BoxPose> boxes = {kGround};
  for (int s = 0; s < 30; ++s)
    for (int h = 0; h < 10; ++h) boxes.push_back(box(3.f * (s % 6) - 7.f, 0.5f + h, 3.f * (s / 6) - 6.f));
  const std::vector<uint8_t> m = masksOf(boxes);
  EXPECT_EQ(m[0], 0u);
  for (size_t i = 1; i < boxes.size(); ++i) {
    const int h = static_cast<int>((i - 1) % 10);
    EXPECT_EQ(m[i], h == 9 ? kNegY : (kNegY | kPosY)) << "box " << i;
  }
}

TEST(HiddenBoxFaces, NonFiniteBoxesAreIgnored) {
  std::vector<BoxPose> boxes = {box(0.f, 0.5f, 0.f), box(0.f, 1.5f, 0.f), box(NAN, 0.f, 0.f)};
  const std::vector<uint8_t> m = masksOf(boxes);
  EXPECT_EQ(m[0], kPosY);
  EXPECT_EQ(m[1], kNegY);
  EXPECT_EQ(m[2], 0u);
}

}  // namespace
}  // namespace haif::render
