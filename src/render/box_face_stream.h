// Box faces as one world-space vertex stream, built on the CPU each frame. llvmpipe pays a fixed
// cost per instance of an instanced draw (about as much as a box's pixels), so thousands of boxes
// drawn as instances cost more than the few faces of each that survive culling; one plain draw of
// those faces costs only their vertices and pixels. Quads keep the corner order and diagonal of
// makeBoxMesh, so the GPU rasterises the same triangles as before. Camera faces come in two lists:
// those turned towards the sun, and those turned away from it, which the sun cannot light, so
// their shader skips the shadow map lookup.
#pragma once

#include <cstdint>
#include <vector>

#include "render/hidden_box_faces.h"
#include "render/palette.h"
#include "render/render_math.h"

namespace haif::render {

/// One vertex of the camera stream (what shaders/box.vert reads).
struct BoxFaceVertex {
  float position[3];  ///< world
  float normal[3];    ///< world, unit, the face's outward normal
  float color[3];     ///< linear albedo
  float edge[4];      ///< metres to the face's four edges (-u, +u, -v, +v); linear across the face
  float edgeWidth;    ///< width of the dark edge line in metres (3 % of the box's smallest extent)
};

/// Reusable builder of the two streams; clear() keeps capacity, so steady frames do not allocate.
class BoxFaceStream {
 public:
  void clear();

  /// Appends the faces of `box` the camera at `eye` may see: not in `skip` (boxFaceBit mask) and
  /// turned towards the eye (a hair of slack: the GPU's face culling makes the exact call); each to
  /// sunwardVertices() or awayVertices() by the sign of its normal . toSun.
  void addCameraFaces(const BoxPose& box, LinearColor color, uint8_t skip, Vec3 eye, Vec3 toSun);
  /// Appends, positions only, the three faces of `box` turned towards the sun (those that cast its
  /// shadow) but for those in `skip`.
  void addShadowFaces(const BoxPose& box, uint8_t skip, Vec3 toSun);

  const std::vector<BoxFaceVertex>& sunwardVertices() const { return sunward_; }  ///< 4 per face
  const std::vector<BoxFaceVertex>& awayVertices() const { return away_; }        ///< 4 per face
  const std::vector<float>& shadowPositions() const { return shadow_; }  ///< xyz per vertex
  size_t sunwardFaces() const { return sunward_.size() / 4; }
  size_t awayFaces() const { return away_.size() / 4; }
  size_t shadowFaces() const { return shadow_.size() / 12; }

  /// Indices of `faces` quads of 4 consecutive vertices each (two triangles per quad, the diagonal
  /// from corner 0 to corner 2), appended to `out` after the quads it already holds.
  static void growQuadIndices(size_t faces, std::vector<uint32_t>& out);

 private:
  std::vector<BoxFaceVertex> sunward_, away_;
  std::vector<float> shadow_;
};

}  // namespace haif::render
