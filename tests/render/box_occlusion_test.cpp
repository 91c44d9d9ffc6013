// BoxOcclusion: boxes and faces behind a wall of boxes are found hidden, and nothing the camera
// could see through a gap, over the top or beside the wall is.
#include <gtest/gtest.h>

#include <vector>

#include "render/box_occlusion.h"
#include "render/hidden_box_faces.h"
#include "render/view_setup.h"

namespace haif::render {
namespace {

constexpr int kWidth = 320, kHeight = 240;

BoxPose box(float x, float y, float z, float hx = 0.5f, float hy = 0.5f, float hz = 0.5f) {
  BoxPose b;
  b.center = {x, y, z};
  b.half = {hx, hy, hz};
  return b;
}

struct Result {
  std::vector<uint8_t> faces, whole;
};

// Runs BoxOcclusion on `boxes` (nearest first, as the renderer orders them) seen from `eye`, with
// the faces HiddenBoxFaces drops and the 4x MSAA sample pattern of llvmpipe.
Result occlusion(const std::vector<BoxPose>& boxes, Vec3 eye, Vec3 target) {
  Camera c;
  c.automatic = false;
  c.eye[0] = eye.x, c.eye[1] = eye.y, c.eye[2] = eye.z;
  c.target[0] = target.x, c.target[1] = target.y, c.target[2] = target.z;
  SceneBounds bounds;
  for (const BoxPose& b : boxes) bounds.add(b.center, length(b.half));
  const ViewSetup view = computeView(c, bounds, kWidth, kHeight);
  OcclusionView ov;
  ov.viewProj = view.viewProj, ov.eye = view.eye, ov.zNear = view.zNear;
  ov.width = kWidth, ov.height = kHeight;
  HiddenBoxFaces hidden;
  std::vector<uint8_t> undrawn;
  hidden.find(boxes, undrawn);
  BoxOcclusion finder;
  const float samples[8] = {0.375f, 0.125f, 0.875f, 0.375f, 0.125f, 0.625f, 0.625f, 0.875f};
  finder.setSamples(samples, 4);
  Result r;
  finder.find(ov, boxes, boxes.size(), undrawn, r.faces, r.whole);
  EXPECT_EQ(r.faces.size(), boxes.size());
  EXPECT_EQ(r.whole.size(), boxes.size());
  return r;
}

// A wall of touching unit cubes, 5 wide and 3 high, in the plane z = 0 (minus `gapX`, `gapY`).
std::vector<BoxPose> wall(int gapX = -1, int gapY = -1) {
  std::vector<BoxPose> boxes;
  for (int y = 0; y < 3; ++y)
    for (int x = -2; x <= 2; ++x)
      if (x != gapX || y != gapY) boxes.push_back(box(static_cast<float>(x), 0.5f + static_cast<float>(y), 0.f));
  return boxes;
}

TEST(BoxOcclusion, BoxBehindAWallIsHiddenAndItsNeighboursAreNot) {
  std::vector<BoxPose> boxes = wall();
  const size_t behind = boxes.size();
  boxes.push_back(box(0.f, 1.5f, -3.f));
  const size_t beside = boxes.size();
  boxes.push_back(box(5.f, 1.5f, -3.f));
  const size_t above = boxes.size();
  boxes.push_back(box(0.f, 4.5f, -3.f));
  const Result r = occlusion(boxes, {0.f, 1.5f, 12.f}, {0.f, 1.5f, 0.f});
  EXPECT_EQ(r.whole[behind], 1) << "the wall covers it";
  EXPECT_EQ(r.whole[beside], 0) << "beside the wall";
  EXPECT_EQ(r.whole[above], 0) << "over the top of the wall";
  for (size_t i = 0; i < behind; ++i) {
    EXPECT_EQ(r.whole[i], 0) << "wall box " << i;
    EXPECT_EQ(r.faces[i] & boxFaceBit(2, 1), 0) << "the wall's faces towards the camera, box " << i;
  }
}

TEST(BoxOcclusion, BoxSeenThroughAGapOrFromTheSideStaysVisible) {
  std::vector<BoxPose> boxes = wall(0, 1);  // the middle of the wall is missing
  const size_t behind = boxes.size();
  boxes.push_back(box(0.f, 1.5f, -3.f));
  Result r = occlusion(boxes, {0.f, 1.5f, 12.f}, {0.f, 1.5f, 0.f});
  EXPECT_EQ(r.whole[behind], 0);
  EXPECT_EQ(r.faces[behind] & boxFaceBit(2, 1), 0) << "its front face shows through the gap";
  // The whole wall again, but seen from far to the side: the box behind comes out beside it.
  boxes = wall();
  boxes.push_back(box(0.f, 1.5f, -3.f));
  r = occlusion(boxes, {14.f, 1.5f, 6.f}, {0.f, 1.5f, 0.f});
  EXPECT_EQ(r.whole.back(), 0);
}

TEST(BoxOcclusion, AFaceBehindTheWallIsHiddenWhileTheTopShowsOverIt) {
  // A low box 1.1 behind a wall two cubes high, seen from above: its face towards the wall is
  // covered, the far part of its top is seen over the wall.
  std::vector<BoxPose> boxes;
  boxes.push_back(box(0.f, 1.f, 0.f, 2.f, 1.f, 0.5f));
  boxes.push_back(box(0.f, 0.4f, -2.1f, 0.5f, 0.4f, 0.5f));
  const Result r = occlusion(boxes, {0.f, 8.f, 6.f}, {0.f, 0.5f, -0.5f});
  EXPECT_EQ(r.whole[1], 0);
  EXPECT_NE(r.faces[1] & boxFaceBit(2, 1), 0) << "face towards the wall";
  EXPECT_EQ(r.faces[1] & boxFaceBit(1, 1), 0) << "top";
  EXPECT_EQ(r.faces[0], 0) << "the wall is in front of everything";
}

TEST(BoxOcclusion, BoxesCrossingTheNearPlaneNeitherHideNorAreHidden) {
  // A huge box around the camera would cover everything if it counted as an occluder.
  std::vector<BoxPose> boxes = {box(0.f, 1.f, 10.f, 3.f, 3.f, 3.f), box(0.f, 1.f, 0.f)};
  const Result r = occlusion(boxes, {0.f, 1.f, 10.f}, {0.f, 1.f, 0.f});
  EXPECT_EQ(r.whole[0], 0);
  EXPECT_EQ(r.whole[1], 0);
  EXPECT_EQ(r.faces[1], 0);
}

}  // namespace
}  // namespace haif::render
