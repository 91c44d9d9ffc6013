// Turns a Camera (explicit or automatic) plus the scene bounds into matrices for one frame.
#pragma once

#include <vector>

#include "render/frame_input.h"
#include "render/render_math.h"

namespace haif::render {

/// Axis-aligned bounds of the things worth looking at (the ground is never included).
struct SceneBounds {
  Vec3 min{-1.f, -1.f, -1.f};  ///< lower corner
  Vec3 max{1.f, 1.f, 1.f};     ///< upper corner
  bool valid = false;          ///< false: nothing was added (a default box around the origin is used)

  void add(Vec3 center, float radius);
  Vec3 center() const { return (min + max) * 0.5f; }
  float radius() const { return length(max - min) * 0.5f; }
};

/// Everything the passes need to know about the view.
struct ViewSetup {
  Mat4 view, proj, viewProj;     ///< camera matrices
  Vec3 eye, forward, right, up;  ///< camera frame (world)
  float tanHalfFovY = 0.4f;      ///< tan(fovY / 2)
  float aspect = 1.f;            ///< width / height
  float zNear = 0.1f, zFar = 1000.f;
};

/// A bounding sphere of one framed object.
struct FramingSphere {
  Vec3 center;
  float radius = 0.f;
};

/// Automatic camera: a 3/4 view from above aimed at the bounds' centre, as close as possible while
/// every sphere (or, without spheres, every corner of the bounds) stays inside the frustum.
ViewSetup computeView(const Camera& camera, const SceneBounds& bounds, int width, int height,
                      const std::vector<FramingSphere>* spheres = nullptr);

}  // namespace haif::render
