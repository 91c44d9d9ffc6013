// Where shadows can fall on the ground, as a screen rectangle: outside it the ground is drawn with
// a shader variant that skips the shadow map lookup (the most expensive part of the ground's
// shading on llvmpipe, and most of the ground on screen is far from every caster).
#pragma once

#include "render/render_math.h"
#include "render/sky_extent.h"
#include "render/view_setup.h"

namespace haif::render {

/// Pixel rectangle [x0, x1) x [y0, y1), y counted from the bottom row as in GL.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

/// Screen rectangle outside which no shadow of anything inside `casters` can fall on `face`: the
/// casters' box pushed along the sun direction onto the face's plane, grown by worldMargin (filter
/// and normal offset of the lookup), projected, and grown by two pixels. The whole image when that
/// cannot be bounded (a point behind the camera, the sun grazing or below the plane).
PixelRect groundShadowRect(const ViewSetup& view, int width, int height, const SceneBounds& casters,
                           Vec3 sunDir, const GroundFace& face, float worldMargin);

}  // namespace haif::render
