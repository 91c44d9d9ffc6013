// Where the sky can show: the rows of the image below the far edge of the ground are covered by
// it, so the sky pass (a full-screen strip at the far plane) only needs to start above them.
// On llvmpipe with MSAA a covered pixel still costs its per-sample depth tests.
#pragma once

#include <vector>

#include "render/render_math.h"
#include "render/view_setup.h"

namespace haif::render {

/// A rectangle the ground is drawn with (the top face of a ground box, or a plane).
struct GroundFace {
  Vec3 center;                  ///< centre of the rectangle
  Vec3 normal{0.f, 1.f, 0.f};   ///< unit normal on the visible side
  Vec3 axisU{1.f, 0.f, 0.f};    ///< unit in-plane axis
  Vec3 axisV{0.f, 0.f, 1.f};    ///< unit in-plane axis, perpendicular to axisU
  float halfU = 1.f, halfV = 1.f;  ///< half sizes along axisU and axisV
};

/// Lowest NDC y in [-1, 1] from which the sky must be drawn: every pixel centre below it sees one
/// of the faces from the front, between the near and far planes. -1 when no face covers the
/// bottom corners of the image; 1 when the faces cover it all. Allows a few pixels of margin.
float skyStartNdc(const ViewSetup& view, int imageHeight, const std::vector<GroundFace>& faces);

}  // namespace haif::render
