// Finds box faces that can never be seen because they lie inside another box: the top of a box
// with another resting on it, the sides between boxes pressed together, the bottom on the ground.
// Dropping them before rasterisation saves fragment work (llvmpipe shades every rasterised
// fragment under MSAA, hidden or not) without changing the picture: a face inside a closed opaque
// box is covered by that box from every direction, also from the sun, so shadows stay the same.
#pragma once

#include <cstdint>
#include <vector>

#include "render/render_math.h"

namespace haif::render {

/// One box: centre, orientation (unit quaternion x, y, z, w, box -> world) and half extents.
struct BoxPose {
  Vec3 center;
  float orientation[4] = {0.f, 0.f, 0.f, 1.f};
  Vec3 half;
};

/// Bit of face (axis 0..2, side -1/+1) in a hidden-face mask; matches the face order of makeBoxMesh.
constexpr uint8_t boxFaceBit(int axis, int side) { return static_cast<uint8_t>(1u << (2 * axis + (side > 0 ? 1 : 0))); }

/// Computes hidden-face masks; keeps its scratch buffers so repeated calls do not allocate.
class HiddenBoxFaces {
 public:
  /// masks[i] gets boxFaceBit(axis, side) for every face of boxes[i] whose four corners all lie in
  /// one other box grown by tolerance(boxes[i].half), where that box's centre is on the outer side
  /// of the face (so two boxes in the same place do not hide each other). A face inside a convex
  /// box is covered by it; the tolerance lets resting contacts with a hair of gap count.
  /// Conservative: a face poking out of its neighbour by more, or covered only by several boxes
  /// together, stays visible.
  void find(const std::vector<BoxPose>& boxes, std::vector<uint8_t>& masks);

  /// Gap (metres) still treated as touching for a box of these half extents: 1 % of the smallest.
  static float tolerance(Vec3 half);

 private:
  std::vector<float> radius_;            // bounding sphere radius per box
  std::vector<Vec3> axes_;               // three unit axes per box (world)
  std::vector<uint32_t> big_;            // boxes too large for the grid, tested against every box
  std::vector<uint32_t> cellStart_;      // counting-sort offsets per hash bucket (+1 sentinel)
  std::vector<uint32_t> cellBoxes_;      // box indices grouped by bucket
  std::vector<uint32_t> bucketOf_;       // bucket per box (UINT32_MAX for big boxes)
  std::vector<float> scratch_;           // radii for the median
};

}  // namespace haif::render
