#include "render/shadow_footprint.h"

#include <algorithm>
#include <cmath>

namespace haif::render {

PixelRect groundShadowRect(const ViewSetup& view, int width, int height, const SceneBounds& casters,
                           Vec3 sunDir, const GroundFace& face, float worldMargin) {
  const PixelRect whole{0, 0, width, height};
  const float sunUp = dot(sunDir, face.normal);
  if (!(sunUp > 0.05f)) return whole;
  // Projection along the sun is affine, so the shadow of the box lies in the hull of its corners'
  // shadows; growing each in the plane by the margin (both in-plane axes) keeps that true.
  float lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f};
  for (int corner = 0; corner < 32; ++corner) {
    const int c = corner & 7;
    Vec3 p{(c & 1) ? casters.max.x : casters.min.x, (c & 2) ? casters.max.y : casters.min.y,
           (c & 4) ? casters.max.z : casters.min.z};
    p = p - sunDir * (dot(p - face.center, face.normal) / sunUp);
    p = p + face.axisU * ((corner & 8) ? worldMargin : -worldMargin) +
        face.axisV * ((corner & 16) ? worldMargin : -worldMargin);
    const float* m = view.viewProj.m;
    const float cw = m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15];
    if (!(cw > view.zNear * 0.5f)) return whole;  // behind or at the camera: no finite bound
    const float ndc[2] = {(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12]) / cw,
                          (m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13]) / cw};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], ndc[k]), hi[k] = std::max(hi[k], ndc[k]);
  }
  auto toPixel = [](float ndc, int size, float grow) {
    const float px = (std::clamp(ndc, -2.f, 2.f) * 0.5f + 0.5f) * static_cast<float>(size) + grow;
    return std::clamp(static_cast<int>(std::floor(px)), 0, size);
  };
  PixelRect r;
  r.x0 = toPixel(lo[0], width, -2.f);
  r.y0 = toPixel(lo[1], height, -2.f);
  r.x1 = toPixel(hi[0], width, 3.f);
  r.y1 = toPixel(hi[1], height, 3.f);
  return r;
}

}  // namespace haif::render
