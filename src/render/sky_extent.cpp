#include "render/sky_extent.h"

#include <algorithm>
#include <cmath>

namespace haif::render {
namespace {

// True when the view ray through NDC (x, y) meets the face from its front, inside the depth range.
// Slightly shrunk face and depth range, so float error cannot claim an uncovered pixel.
bool covers(const ViewSetup& v, const GroundFace& g, float x, float y) {
  const Vec3 dir = v.forward + v.right * (x * v.tanHalfFovY * v.aspect) + v.up * (y * v.tanHalfFovY);
  const float facing = dot(dir, g.normal);
  const float height = dot(v.eye - g.center, g.normal);
  if (!(height > 0.f) || !(facing < 0.f)) return false;
  const float t = height / -facing;  // depth along forward: dir's forward component is 1
  if (!(t > v.zNear * 1.01f && t < v.zFar * 0.99f)) return false;
  const Vec3 local = v.eye + dir * t - g.center;
  return std::fabs(dot(local, g.axisU)) < 0.999f * g.halfU && std::fabs(dot(local, g.axisV)) < 0.999f * g.halfV;
}

}  // namespace

float skyStartNdc(const ViewSetup& view, int imageHeight, const std::vector<GroundFace>& faces) {
  float start = -1.f;
  for (const GroundFace& g : faces) {
    // What a face covers on screen is convex (a planar convex region cut by the depth range and
    // projected), so a band [-1, y] of the image is covered when its four corners are.
    auto bandCovered = [&](float y) { return covers(view, g, -1.f, y) && covers(view, g, 1.f, y); };
    if (!bandCovered(-1.f)) continue;
    float lo = -1.f, hi = 1.f;
    if (bandCovered(hi)) return 1.f;
    for (int i = 0; i < 24; ++i) {
      const float mid = 0.5f * (lo + hi);
      (bandCovered(mid) ? lo : hi) = mid;
    }
    start = std::max(start, lo);
  }
  // Two pixels of margin for rasterisation and sample positions.
  return start <= -1.f ? -1.f : std::max(-1.f, start - 4.f / static_cast<float>(std::max(imageHeight, 1)));
}

}  // namespace haif::render
