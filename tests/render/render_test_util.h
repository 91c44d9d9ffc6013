// Helpers shared by the renderer tests: small scenes and pixel probes.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "render/frame_input.h"
#include "render/view_setup.h"

namespace haif::render::test {

/// The view of a fixed camera at `eye` looking at `target`, for a scene of one sphere of `radius`
/// centred at (0, 1, 0) (the bounds set the clip planes).
inline ViewSetup viewFrom(Vec3 eye, Vec3 target, int w = 320, int h = 240, float radius = 1.f) {
  Camera c;
  c.automatic = false;
  c.eye[0] = eye.x, c.eye[1] = eye.y, c.eye[2] = eye.z;
  c.target[0] = target.x, c.target[1] = target.y, c.target[2] = target.z;
  SceneBounds b;
  b.add({0.f, 1.f, 0.f}, radius);
  return computeView(c, b, w, h);
}

/// The reference ground: static box half extents (500, 1, 500) centred at y = -1.
inline Instance groundBox() {
  Instance g;
  g.kind = ShapeKind::Box;
  g.isStatic = true;
  g.halfExtents[0] = 500.f, g.halfExtents[1] = 1.f, g.halfExtents[2] = 500.f;
  g.position[1] = -1.f;
  return g;
}

/// A body with a fixed sRGB colour (Normal mode).
inline Instance coloredBody(ShapeKind kind, float x, float y, float z, float r, float g, float b) {
  Instance in;
  in.kind = kind;
  in.position[0] = x, in.position[1] = y, in.position[2] = z;
  in.useColor = true;
  in.color[0] = r, in.color[1] = g, in.color[2] = b;
  in.bodyId = 1;
  return in;
}

struct Pixel {
  int r, g, b, a;
};

inline Pixel at(const std::vector<uint8_t>& rgba, int w, int x, int y) {
  const uint8_t* p = rgba.data() + 4 * (static_cast<size_t>(y) * w + x);
  return {p[0], p[1], p[2], p[3]};
}

/// Strongly red: red clearly dominates green and blue.
inline bool isRed(Pixel p) { return p.r > 90 && p.r > p.g + 50 && p.r > p.b + 50; }
/// Strongly green.
inline bool isGreen(Pixel p) { return p.g > 90 && p.g > p.r + 50 && p.g > p.b + 50; }

/// The renderer's performance target: stacks_2000 (2000 unit boxes in stacks of 10, 3 m apart) on
/// the ground, with 240 steps of overlay history; the overlay itself off.
inline FrameInput stacks2000Frame() {
  FrameInput f;
  f.instances.push_back(groundBox());
  const int n = 2000, k = static_cast<int>(std::ceil(std::sqrt(std::ceil(n / 10.0))));
  for (int i = 0; i < n; ++i) {
    Instance b;
    b.bodyId = static_cast<uint32_t>(i);
    const int s = i / 10, h = i % 10;
    b.position[0] = 3.f * static_cast<float>(s % k);
    b.position[1] = 0.5f + 1.01f * static_cast<float>(h);
    b.position[2] = 3.f * static_cast<float>(s / k);
    f.instances.push_back(b);
  }
  for (int i = 0; i < 240; ++i) {
    f.overlay.iterations.push_back(10.f);
    f.overlay.collisionMs.push_back(2.f);
    f.overlay.solveMs.push_back(4.f);
  }
  f.overlay.enabled = false;
  return f;
}

/// Directory for test output files (created if needed).
std::string tempDir();

}  // namespace haif::render::test
