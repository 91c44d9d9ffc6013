#include "render/box_face_stream.h"

#include <algorithm>

namespace haif::render {
namespace {

// Corners of a face in its (u, v) plane, u = axis + 1, v = axis + 2 (mod 3), in makeBoxMesh's
// order: counter-clockwise seen from outside on a +side face. A -side face lists them in reverse
// (0, 3, 2, 1), which keeps both its triangles and its diagonal.
constexpr float kCorner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
constexpr int kReversed[4] = {0, 3, 2, 1};

// The box's axes in world space, each scaled by its half extent.
void worldAxes(const BoxPose& box, Vec3 axes[3]) {
  axes[0] = rotate(box.orientation, {box.half.x, 0.f, 0.f});
  axes[1] = rotate(box.orientation, {0.f, box.half.y, 0.f});
  axes[2] = rotate(box.orientation, {0.f, 0.f, box.half.z});
}

float component(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

}  // namespace

void BoxFaceStream::clear() {
  sunward_.clear();
  away_.clear();
  shadow_.clear();
}

void BoxFaceStream::addCameraFaces(const BoxPose& box, LinearColor color, uint8_t skip, Vec3 eye, Vec3 toSun) {
  Vec3 axes[3];
  worldAxes(box, axes);
  const float edgeWidth = 0.03f * std::min({box.half.x, box.half.y, box.half.z});
  for (int axis = 0; axis < 3; ++axis) {
    const float halfN = component(box.half, axis);
    const Vec3 n = normalize(axes[axis]);
    for (int side = -1; side <= 1; side += 2) {
      if (skip & boxFaceBit(axis, side)) continue;
      const Vec3 centre = box.center + axes[axis] * static_cast<float>(side);
      // n . (eye - p) is the same for every point p of the face; a face seen exactly edge-on may
      // still cover a sample, so the slack keeps it and leaves the decision to the GPU.
      const Vec3 outward = n * static_cast<float>(side), toEye = eye - centre;
      if (dot(outward, toEye) < -1e-3f * (length(toEye) + halfN)) continue;
      std::vector<BoxFaceVertex>& out = dot(outward, toSun) > 0.f ? sunward_ : away_;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const float hu = component(box.half, u), hv = component(box.half, v);
      for (int k = 0; k < 4; ++k) {
        const float* c = kCorner[side > 0 ? k : kReversed[k]];
        const Vec3 p = centre + axes[u] * c[0] + axes[v] * c[1];
        out.push_back({{p.x, p.y, p.z},
                           {outward.x, outward.y, outward.z},
                           {color.r, color.g, color.b},
                           {hu * (1.f + c[0]), hu * (1.f - c[0]), hv * (1.f + c[1]), hv * (1.f - c[1])},
                           edgeWidth});
      }
    }
  }
}

void BoxFaceStream::addShadowFaces(const BoxPose& box, uint8_t skip, Vec3 toSun) {
  Vec3 axes[3];
  worldAxes(box, axes);
  // Per axis, the side facing the sun (as shaders/shadow.vert mirrored the corner mesh).
  int sideOf[3];
  for (int axis = 0; axis < 3; ++axis) sideOf[axis] = dot(axes[axis], toSun) < 0.f ? -1 : 1;
  for (int axis = 0; axis < 3; ++axis) {
    if (skip & boxFaceBit(axis, sideOf[axis])) continue;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const Vec3 centre = box.center + axes[axis] * static_cast<float>(sideOf[axis]);
    for (const auto& c : kCorner) {
      const Vec3 p = centre + axes[u] * (c[0] * static_cast<float>(sideOf[u])) +
                     axes[v] * (c[1] * static_cast<float>(sideOf[v]));
      shadow_.insert(shadow_.end(), {p.x, p.y, p.z});
    }
  }
}

void BoxFaceStream::growQuadIndices(size_t faces, std::vector<uint32_t>& out) {
  for (size_t f = out.size() / 6; f < faces; ++f) {
    const uint32_t b = static_cast<uint32_t>(4 * f);
    out.insert(out.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
}

}  // namespace haif::render
