#include "render/view_setup.h"

#include <algorithm>
#include <cmath>

namespace haif::render {

void SceneBounds::add(Vec3 c, float r) {
  const Vec3 lo{c.x - r, c.y - r, c.z - r}, hi{c.x + r, c.y + r, c.z + r};
  if (!valid) {
    min = lo, max = hi, valid = true;
    return;
  }
  min = {std::min(min.x, lo.x), std::min(min.y, lo.y), std::min(min.z, lo.z)};
  max = {std::max(max.x, hi.x), std::max(max.y, hi.y), std::max(max.z, hi.z)};
}

ViewSetup computeView(const Camera& camera, const SceneBounds& boundsIn, int width, int height,
                      const std::vector<FramingSphere>* spheres) {
  SceneBounds bounds = boundsIn;
  if (!bounds.valid) bounds.min = {-3.f, 0.f, -3.f}, bounds.max = {3.f, 3.f, 3.f};

  ViewSetup v;
  v.aspect = static_cast<float>(width) / static_cast<float>(std::max(1, height));
  const float fov = std::clamp(camera.fovYDegrees, 5.f, 150.f) * 3.14159265f / 180.f;
  v.tanHalfFovY = std::tan(fov * 0.5f);
  const float tanHalfFovX = v.tanHalfFovY * v.aspect;

  Vec3 corners[8];
  for (int i = 0; i < 8; ++i)
    corners[i] = {(i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                  (i & 4) ? bounds.max.z : bounds.min.z};

  Vec3 target, up{0.f, 1.f, 0.f};
  if (camera.automatic) {
    // 3/4 view: 35 degrees around y from the +z axis side, 28 degrees above the horizon.
    const float az = 0.61f, el = 0.49f;
    const Vec3 toEye{std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
    target = bounds.center();
    v.forward = toEye * -1.f;
    v.right = normalize(cross(v.forward, up));
    v.up = cross(v.right, v.forward);
    // Smallest distance along toEye that keeps everything inside both half angles. Spheres fit
    // tighter than the box corners (the empty top corners of a wide scene waste the frame).
    float dist = 0.f;
    auto fit = [&](Vec3 c, float r) {
      const Vec3 d = c - target;
      const float towardEye = dot(d, toEye);
      // A sphere clears a frustum plane when its centre is r / cos(half angle) inside it.
      dist = std::max(dist, towardEye + (std::fabs(dot(d, v.right)) + r * std::sqrt(1.f + tanHalfFovX * tanHalfFovX)) / tanHalfFovX);
      dist = std::max(dist, towardEye + (std::fabs(dot(d, v.up)) + r * std::sqrt(1.f + v.tanHalfFovY * v.tanHalfFovY)) / v.tanHalfFovY);
    };
    if (spheres && !spheres->empty() && boundsIn.valid)
      for (const FramingSphere& s : *spheres) fit(s.center, s.radius);
    else
      for (const Vec3& c : corners) fit(c, 0.f);
    dist = std::max(dist * 1.04f, 0.5f);
    v.eye = target + toEye * dist;
  } else {
    v.eye = {camera.eye[0], camera.eye[1], camera.eye[2]};
    target = {camera.target[0], camera.target[1], camera.target[2]};
    if (length(target - v.eye) < 1e-6f) target = v.eye + Vec3{0.f, 0.f, -1.f};
    const Vec3 wantUp = normalize({camera.up[0], camera.up[1], camera.up[2]});
    v.forward = normalize(target - v.eye);
    v.right = cross(v.forward, wantUp);
    if (length(v.right) < 1e-6f) v.right = cross(v.forward, Vec3{1.f, 0.f, 0.f});
    v.right = normalize(v.right);
    v.up = cross(v.right, v.forward);
    up = wantUp;
  }

  // Depth range from the bounds, but far enough that the ground reaches the fogged horizon.
  float nearest = 1e30f, farthest = 0.f;
  for (const Vec3& c : corners) {
    const float depth = dot(c - v.eye, v.forward);
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  const float size = std::max(bounds.radius(), 1.f);
  v.zNear = std::clamp(nearest * 0.5f, 0.02f, 50.f);
  v.zFar = std::max(farthest, 0.f) + 40.f * size + 200.f;
  v.view = lookAt(v.eye, v.eye + v.forward, v.up);
  v.proj = perspective(fov, v.aspect, v.zNear, v.zFar);
  v.viewProj = v.proj * v.view;
  return v;
}

}  // namespace haif::render
