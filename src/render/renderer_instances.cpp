// What a frame draws: each instance classified and sorted into draw groups, its instance record,
// the box face streams' faces, the ground's faces and the contact markers.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/palette.h"

namespace haif::render {
namespace {

constexpr float kPlaneHalfSize = 1000.f;

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// Unit quaternion from q; identity for a zero or non-finite one.
void normalizedQuat(const float* q, float* qn) {
  for (int k = 0; k < 4; ++k) qn[k] = q[k];
  const float len = std::sqrt(qn[0] * qn[0] + qn[1] * qn[1] + qn[2] * qn[2] + qn[3] * qn[3]);
  if (!(len > 1e-12f) || !std::isfinite(len))
    qn[0] = qn[1] = qn[2] = 0.f, qn[3] = 1.f;
  else
    for (int k = 0; k < 4; ++k) qn[k] /= len;
}

}  // namespace

bool Renderer::Impl::isGround(const Instance& in) const {
  if (in.kind == ShapeKind::Plane) return true;
  return in.kind == ShapeKind::Box && in.isStatic &&
         std::max(in.halfExtents[0], in.halfExtents[2]) >= opt.groundMinHalfExtent;
}

void Renderer::Impl::pushInstance(Vec3 p, const float* q, Vec3 scale, float stretch, LinearColor c,
                                  float emissive, unsigned hidden) {
  float qn[4];
  normalizedQuat(q, qn);
  staging.insert(staging.end(), {p.x, p.y, p.z, qn[0], qn[1], qn[2], qn[3], scale.x, scale.y, scale.z,
                                 stretch, c.r, c.g, c.b, emissive, static_cast<float>(hidden)});
}

// Hidden-face masks for the boxes of the sorted order (ground boxes included: they cover the
// bottoms of the boxes resting on them), in the order buildInstances pushes them.
void Renderer::Impl::findHiddenBoxFaces(const FrameInput& f) {
  boxPoses.clear();
  for (const SortItem& s : order) {
    if (s.kind != kBox && s.kind != kGroundBox) continue;
    const Instance& in = f.instances[s.index];
    BoxPose b;
    b.center = {in.position[0], in.position[1], in.position[2]};
    normalizedQuat(in.orientation, b.orientation);
    b.half = {in.halfExtents[0], in.halfExtents[1], in.halfExtents[2]};
    boxPoses.push_back(b);
  }
  if (opt.cullHiddenBoxFaces)
    hiddenFaces.find(boxPoses, hiddenMasks);
  else
    hiddenMasks.assign(boxPoses.size(), 0);
}

// BoxOcclusion over the first `count` entries of boxPoses (the dynamic boxes, front to back).
void Renderer::Impl::findOccludedBoxes(const ViewSetup& view, size_t count) {
  if (!opt.cullOccludedBoxes) {
    occludedFaces.assign(count, 0);
    occludedBoxes.assign(count, 0);
    return;
  }
  OcclusionView ov;
  ov.viewProj = view.viewProj;
  ov.eye = view.eye;
  ov.zNear = view.zNear;
  ov.width = opt.width, ov.height = opt.height;
  occlusion.find(ov, boxPoses, count, hiddenMasks, occludedFaces, occludedBoxes);
}

size_t Renderer::Impl::instanceCount() const { return staging.size() / kInstanceFloats; }

// A group of the instances pushed since `first`.
void Renderer::Impl::addGroup(const GpuMesh* mesh, size_t first, int surface, bool cull, bool casts) {
  const size_t count = instanceCount() - first;
  if (count) groups.push_back({mesh, first, count, surface, cull, casts});
}

// Bounds of everything but the ground (for framing and the shadow frustum) and the draw kind of
// each instance. Returns false for unregistered meshes.
bool Renderer::Impl::classify(const FrameInput& f, SceneBounds* bounds, float* meanRadius, std::string* error) {
  order.clear();
  framing.clear();
  float radiusSum = 0.f;
  int radiusCount = 0;
  for (uint32_t i = 0; i < f.instances.size(); ++i) {
    const Instance& in = f.instances[i];
    if (!finite3(in.position)) continue;  // a NaN body must not poison framing or the GPU
    uint32_t kind = kBox;
    float r = 0.f;
    switch (in.kind) {
      case ShapeKind::Box:
        kind = isGround(in) ? kGroundBox : kBox;
        r = std::sqrt(in.halfExtents[0] * in.halfExtents[0] + in.halfExtents[1] * in.halfExtents[1] +
                      in.halfExtents[2] * in.halfExtents[2]);
        break;
      case ShapeKind::Sphere: kind = kSphere, r = in.radius; break;
      case ShapeKind::Capsule: kind = kCapsule, r = in.radius + in.halfHeight; break;
      case ShapeKind::ConvexHull:
      case ShapeKind::TriangleMesh: {
        auto it = meshes.find(in.meshId);
        if (it == meshes.end()) {
          if (error) *error = "renderer: instance " + std::to_string(i) + " (body " + std::to_string(in.bodyId) +
                              ") uses mesh id " + std::to_string(in.meshId) + " that was never registered";
          return false;
        }
        kind = in.kind == ShapeKind::ConvexHull ? kHull : kTriMesh;
        r = it->second.boundRadius;
        break;
      }
      case ShapeKind::Plane: kind = kGroundPlane; break;
    }
    if (kind != kGroundBox && kind != kGroundPlane && std::isfinite(r)) {
      bounds->add({in.position[0], in.position[1], in.position[2]}, r);
      framing.push_back({{in.position[0], in.position[1], in.position[2]}, r});
      radiusSum += r, ++radiusCount;
    }
    order.push_back({kind, (kind == kHull || kind == kTriMesh) ? in.meshId : 0u, 0.f, i});
  }
  *meanRadius = radiusCount ? radiusSum / radiusCount : 0.5f;
  return true;
}

// The camera stream: the faces of the dynamic boxes the camera may see, front to back.
void Renderer::Impl::buildCameraFaces(const FrameInput& f, const ViewSetup& view) {
  findOccludedBoxes(view, dynamicBoxes);
  for (size_t k = 0; k < dynamicBoxes; ++k)
    if (!occludedBoxes[k])
      boxStream.addCameraFaces(boxPoses[k], instanceColor(f.instances[order[k].index], f.mode),
                               hiddenMasks[k] | occludedFaces[k], view.eye, kSunDir);
}

// Sorts instances into draw groups (front to back inside each) and fills the staging buffer.
void Renderer::Impl::buildInstances(const FrameInput& f, const ViewSetup& view) {
  const Vec3 eye = view.eye;
  staging.clear();
  groups.clear();
  for (SortItem& it : order) {
    const float* p = f.instances[it.index].position;
    const Vec3 d{p[0] - eye.x, p[1] - eye.y, p[2] - eye.z};
    it.depth = dot(d, d);
  }
  std::sort(order.begin(), order.end(), [](const SortItem& a, const SortItem& b) {
    return a.kind != b.kind ? a.kind < b.kind : a.meshId != b.meshId ? a.meshId < b.meshId : a.depth < b.depth;
  });

  findHiddenBoxFaces(f);
  groundFaces.clear();
  // The dynamic boxes come first (kBox sorts first), front to back. The shadow stream gets the
  // faces of every box turned to the sun; the camera stream is built later (buildCameraFaces).
  dynamicBoxes = 0;
  while (dynamicBoxes < order.size() && order[dynamicBoxes].kind == kBox) ++dynamicBoxes;
  boxStream.clear();
  for (size_t k = 0; k < dynamicBoxes; ++k) boxStream.addShadowFaces(boxPoses[k], hiddenMasks[k], kSunDir);
  size_t groupStart = instanceCount(), boxIndex = dynamicBoxes;
  for (size_t k = dynamicBoxes; k < order.size(); ++k) {
    const SortItem& s = order[k];
    const Instance& in = f.instances[s.index];
    const Vec3 p{in.position[0], in.position[1], in.position[2]};
    const LinearColor c = instanceColor(in, f.mode);
    if (s.kind == kGroundBox || s.kind == kGroundPlane) addGroundFace(in, s.kind == kGroundBox);
    switch (s.kind) {
      case kGroundBox:
        pushInstance(p, in.orientation, {in.halfExtents[0], in.halfExtents[1], in.halfExtents[2]}, 0.f, c, 0.f,
                     hiddenMasks[boxIndex++]);
        break;
      case kGroundPlane: pushInstance(p, in.orientation, {kPlaneHalfSize, 1.f, kPlaneHalfSize}, 0.f, c, 0.f); break;
      case kSphere: pushInstance(p, in.orientation, {in.radius, in.radius, in.radius}, 0.f, c, 0.f); break;
      case kCapsule: pushInstance(p, in.orientation, {in.radius, in.radius, in.radius}, in.halfHeight, c, 0.f); break;
      default: pushInstance(p, in.orientation, {1.f, 1.f, 1.f}, 0.f, c, 0.f); break;
    }
    const bool last = k + 1 == order.size() || order[k + 1].kind != s.kind || order[k + 1].meshId != s.meshId;
    if (!last) continue;
    switch (s.kind) {
      case kGroundBox: addGroup(&box, groupStart, kSurfaceGround, true, false); break;
      case kGroundPlane: addGroup(&plane, groupStart, kSurfaceGround, false, false); break;
      case kSphere: addGroup(&sphere, groupStart, kSurfaceBody, true, true); break;
      case kCapsule: addGroup(&capsule, groupStart, kSurfaceBody, true, true); break;
      case kHull: addGroup(&meshes[s.meshId], groupStart, kSurfaceBody, true, true); break;
      case kTriMesh: addGroup(&meshes[s.meshId], groupStart, kSurfaceBody, false, true); break;
      default: break;
    }
    groupStart = instanceCount();
  }
}

// The face the ground is seen by: a ground box's local +y face, or the plane.
void Renderer::Impl::addGroundFace(const Instance& in, bool isBox) {
  float q[4];
  normalizedQuat(in.orientation, q);
  GroundFace g;
  g.normal = rotate(q, {0.f, 1.f, 0.f});
  g.axisU = rotate(q, {1.f, 0.f, 0.f});
  g.axisV = rotate(q, {0.f, 0.f, 1.f});
  g.center = Vec3{in.position[0], in.position[1], in.position[2]} + g.normal * (isBox ? in.halfExtents[1] : 0.f);
  g.halfU = isBox ? in.halfExtents[0] : kPlaneHalfSize;
  g.halfV = isBox ? in.halfExtents[2] : kPlaneHalfSize;
  groundFaces.push_back(g);
}

void Renderer::Impl::buildContactMarkers(const FrameInput& f, float meanRadius) {
  if (!f.showContacts || f.contacts.empty()) return;
  const float s = f.contactScale > 0.f ? f.contactScale : std::max(0.01f, 0.12f * meanRadius);
  const float identity[4] = {0.f, 0.f, 0.f, 1.f};
  const LinearColor dot{1.f, 0.08f, 0.05f}, arrow{1.f, 0.8f, 0.05f};
  size_t first = instanceCount();
  for (const ContactMarker& m : f.contacts)
    if (finite3(m.point)) pushInstance({m.point[0], m.point[1], m.point[2]}, identity, {s, s, s}, 0.f, dot, 0.7f);
  addGroup(&sphere, first, kSurfaceBody, true, false);
  first = instanceCount();
  for (const ContactMarker& m : f.contacts) {
    if (!finite3(m.point) || !finite3(m.normal)) continue;
    const Vec3 n = normalize({m.normal[0], m.normal[1], m.normal[2]});
    // Shortest rotation taking local +y onto n; the antiparallel case turns about x.
    float q[4] = {n.z, 0.f, -n.x, 1.f + n.y};
    if (q[3] < 1e-5f) q[0] = 1.f, q[1] = q[2] = q[3] = 0.f;
    const float len = 4.f * s;
    const Vec3 c = Vec3{m.point[0], m.point[1], m.point[2]} + n * (len * 0.5f + s);
    pushInstance(c, q, {s * 0.3f, s * 0.3f, s * 0.3f}, len * 0.5f, arrow, 0.6f);
  }
  addGroup(&capsule, first, kSurfaceBody, true, false);
}

}  // namespace haif::render
