// Finds boxes, and faces of boxes, that the camera cannot see because nearer boxes cover them.
// llvmpipe shades every rasterised fragment under MSAA, also those its depth test then rejects,
// so a face hidden behind other boxes costs as much as a visible one; dropping it before
// rasterisation saves that work without changing the picture.
//
// Conservative by construction: a small software rasteriser marks an MSAA sample (at the GPU's own
// sample positions) covered only when it lies inside the outline of a box, shrunk by a margin for
// rounding, and a face is hidden only when every sample of every pixel its projection could touch
// is covered by boxes whose front surfaces are all nearer than the face's nearest corner. Parts of
// an outline whose faces HiddenBoxFaces drops are covered by the neighbour those faces lie in (up
// to its contact tolerance). What covers a hidden face may itself be hidden, but then something
// nearer still covers it, so the picture keeps every visible sample.
#pragma once

#include <cstdint>
#include <vector>

#include "render/hidden_box_faces.h"
#include "render/render_math.h"

namespace haif::render {

/// The camera as the occlusion test needs it.
struct OcclusionView {
  Mat4 viewProj;     ///< world -> clip, as the GPU uses it
  Vec3 eye;          ///< camera position (world), to tell front faces from back faces
  float zNear = 0.1f;  ///< corners nearer than this (clip w) make a box neither occluder nor hidden
  int width = 1, height = 1;  ///< viewport in pixels
};

/// Reusable occlusion finder; keeps its buffers so repeated calls do not allocate.
class BoxOcclusion {
 public:
  /// MSAA sample offsets inside a pixel, (0, 0) = its lower left corner as GL reports them
  /// (GL_SAMPLE_POSITION); xy holds 2 floats per sample. With none set, one sample at the centre.
  void setSamples(const float* xy, int count);

  /// For the first `count` boxes (front to back gives the best result): `faces[i]` gets
  /// boxFaceBit(axis, side) for each drawn front face of box i that is hidden, and `whole[i]` = 1
  /// when all of them are (back faces are culled anyway). `undrawn[i]` are faces the renderer
  /// drops anyway (HiddenBoxFaces): they neither occlude nor need testing.
  void find(const OcclusionView& view, const std::vector<BoxPose>& boxes, size_t count,
            const std::vector<uint8_t>& undrawn, std::vector<uint8_t>& faces, std::vector<uint8_t>& whole);

 private:
  struct Projected {
    float x[8], y[8], w[8];  // window coordinates (pixels, y up) and clip w of the 8 corners
    uint8_t front;           // boxFaceBit of the faces turned towards the eye
    bool valid;              // every corner in front of the near plane (and finite)
  };
  struct Rect {
    int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1), clipped to the viewport
    bool empty() const { return x0 >= x1 || y0 >= y1; }
  };

  void project(const OcclusionView& view, const BoxPose& box, Projected& p) const;
  /// Marks the samples inside the box's outline as covered.
  void rasterSilhouette(const Projected& p);
  /// True when every pixel the face could touch is fully covered nearer than the face.
  bool faceHidden(const Projected& p, const int corner[4]) const;
  /// The front faces of p not in `undrawn` that faceHidden finds hidden.
  uint8_t hiddenFaces(const Projected& p, uint8_t undrawn) const;

  std::vector<float> sampleXY_ = {0.5f, 0.5f};
  uint8_t fullMask_ = 1;
  int width_ = 0, height_ = 0;
  std::vector<uint8_t> mask_;   // per pixel: bit s = sample s covered
  std::vector<float> depth_;    // per pixel: the covered samples are covered at clip w <= this
  std::vector<Projected> projected_;
};

}  // namespace haif::render
