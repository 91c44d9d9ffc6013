#include "app/frame_builder.h"

#include "collision/compound.h"

#ifdef HAIF_HAVE_RENDER

namespace haif {

bool applyGlOption(const std::string& text, std::string& error) {
  render::GlBackend backend;
  if (!render::parseGlBackend(text, backend)) {
    error = "--gl: expected osmesa, egl or auto, got '" + text + "'";
    return false;
  }
  render::setPreferredGlBackend(backend);
  return true;
}

bool parseViewMode(const std::string& text, render::ViewMode& out) {
  if (text == "normal") out = render::ViewMode::Normal;
  else if (text == "island") out = render::ViewMode::Island;
  else if (text == "sleep") out = render::ViewMode::Sleep;
  else if (text == "heat") out = render::ViewMode::Heat;
  else return false;
  return true;
}

namespace {

// Hulls and meshes are drawn as registered meshes, one per geometry however many bodies share it.
const void* geometryKey(const Shape& s) {
  return s.type == ShapeType::ConvexHull ? static_cast<const void*>(s.hull.get())
         : s.type == ShapeType::TriangleMesh ? static_cast<const void*>(s.mesh.get())
                                             : nullptr;
}

}  // namespace

void FrameBuilder::setPose(const Vec3& p, const Quat& q, render::Instance& in) {
  in.position[0] = p.x(); in.position[1] = p.y(); in.position[2] = p.z();
  in.orientation[0] = q.x(); in.orientation[1] = q.y(); in.orientation[2] = q.z(); in.orientation[3] = q.w();
}

bool FrameBuilder::registerGeometry(const Shape& s, render::Renderer& renderer, std::string& error) {
  const void* key = geometryKey(s);
  if (!key || meshIds_.count(key)) return true;
  std::vector<float> pos;
  std::vector<uint32_t> idx;
  if (s.type == ShapeType::ConvexHull) {
    for (const Vec3& v : s.hull->vertices) pos.insert(pos.end(), {v.x(), v.y(), v.z()});
    for (const ConvexHull::Face& f : s.hull->faces)  // fan-triangulate each convex polygon
      for (uint32_t k = 1; k + 1 < f.count; ++k)
        idx.insert(idx.end(), {s.hull->faceVertices[f.first], s.hull->faceVertices[f.first + k],
                               s.hull->faceVertices[f.first + k + 1]});
  } else {
    for (const Vec3& v : s.mesh->vertices) pos.insert(pos.end(), {v.x(), v.y(), v.z()});
    idx = s.mesh->indices;
  }
  const uint32_t id = static_cast<uint32_t>(meshIds_.size() + renderMeshes_ + 1);
  std::string why;
  if (!renderer.registerMesh(id, pos, idx, &why)) {
    error = "cannot register render mesh: " + why;
    return false;
  }
  meshIds_.emplace(key, id);
  return true;
}

bool FrameBuilder::registerMeshes(const World& world, const SceneDesc& scene, render::Renderer& renderer,
                                  std::string& error) {
  renderMeshOfBody_.assign(world.bodyCount(), 0);
  drawnParts_.assign(world.bodyCount(), {});
  for (uint32_t i = 0; i < world.bodyCount(); ++i) {
    const Shape& s = world.shape(i);
    if (i < scene.bodies.size() && !scene.bodies[i].renderMesh.asset.empty()) {
      // The world body sits at the hull's centre of mass, not the scene body's origin: shift by it.
      const RenderMeshDesc& r = scene.bodies[i].renderMesh;
      const Vec3 shift = s.type == ShapeType::ConvexHull ? s.hull->centroid
                         : s.type == ShapeType::Compound ? s.compound->centroid
                                                         : Vec3::Zero();
      std::vector<float> pos;
      pos.reserve(3 * r.vertices.size());
      for (const Vec3& v : r.vertices) pos.insert(pos.end(), {v.x() - shift.x(), v.y() - shift.y(), v.z() - shift.z()});
      const uint32_t id = static_cast<uint32_t>(meshIds_.size() + renderMeshes_ + 1);
      std::string why;
      if (!renderer.registerMesh(id, pos, r.indices, &why)) {
        error = scene.bodies[i].where + ".render_mesh: cannot register '" + r.asset + "': " + why;
        return false;
      }
      ++renderMeshes_;
      renderMeshOfBody_[i] = id;
      continue;
    }
    bool registered = true;
    if (s.type == ShapeType::Compound) {
      for (uint32_t k = 0; k < uint32_t(s.compound->parts.size()); ++k) {
        if (i >= scene.bodies.size() || k >= scene.bodies[i].shape.parts.size() || scene.bodies[i].shape.parts[k].draw)
          drawnParts_[i].push_back(k);
        registered = registered && registerGeometry(s.compound->parts[k].shape, renderer, error);
      }
    } else {
      registered = registerGeometry(s, renderer, error);
    }
    if (!registered) {
      error = "body " + std::to_string(i) + ": " + error;
      return false;
    }
  }
  return true;
}

void FrameBuilder::placeShape(const Shape& s, const Transform& xf, render::Instance& in) const {
  switch (s.type) {
    case ShapeType::Sphere: in.kind = render::ShapeKind::Sphere; break;
    case ShapeType::Box: in.kind = render::ShapeKind::Box; break;
    case ShapeType::Capsule: in.kind = render::ShapeKind::Capsule; break;
    case ShapeType::ConvexHull: in.kind = render::ShapeKind::ConvexHull; break;
    case ShapeType::TriangleMesh: in.kind = render::ShapeKind::TriangleMesh; break;
    default: in.kind = render::ShapeKind::Plane; break;
  }
  Vec3 p = xf.p;
  Quat q = xf.q;
  if (s.type == ShapeType::Plane) {
    // Draw the plane through its closest point to the origin with local +y along the normal.
    p = xf.apply(s.planeNormal * s.planeOffset);
    q = xf.q * Quat::FromTwoVectors(Vec3::UnitY(), s.planeNormal);
    in.halfExtents[0] = in.halfExtents[2] = 200.0f;
  }
  setPose(p, q, in);
  if (s.type == ShapeType::Box)
    for (int k = 0; k < 3; ++k) in.halfExtents[k] = s.halfExtents[k];
  in.radius = s.radius;
  in.halfHeight = s.halfHeight;
  const void* key = geometryKey(s);
  const auto it = key ? meshIds_.find(key) : meshIds_.end();
  in.meshId = it == meshIds_.end() ? 0u : it->second;
}

void FrameBuilder::build(const World& world, const CameraDesc& camera, render::FrameInput& frame) const {
  frame.camera.automatic = !camera.given;
  if (camera.given) {
    for (int k = 0; k < 3; ++k) {
      frame.camera.eye[k] = camera.eye[k];
      frame.camera.target[k] = camera.target[k];
      frame.camera.up[k] = camera.up[k];
    }
    frame.camera.fovYDegrees = camera.fovYDeg;
  }
  const BodyStore& b = world.bodies();
  frame.instances.resize(world.bodyCount());
  for (uint32_t i = 0; i < world.bodyCount(); ++i) {
    render::Instance& in = frame.instances[i];
    in = render::Instance{};
    const Shape& s = world.shape(i);
    const Transform& xf = b.xf[i];
    const int32_t island = world.islandOf(i);
    in.bodyId = i;
    in.islandId = island < 0 ? 0u : uint32_t(island);
    in.sleeping = b.asleep[i] != 0;
    in.isStatic = b.kind[i] == BodyKind::Static;
    in.heat = std::min(1.0f, b.v[i].norm() / 5.0f);
    if (i < renderMeshOfBody_.size() && renderMeshOfBody_[i]) {
      in.kind = render::ShapeKind::TriangleMesh;
      in.meshId = renderMeshOfBody_[i];
      setPose(xf.p, xf.q, in);
      continue;
    }
    if (s.type != ShapeType::Compound) {
      placeShape(s, xf, in);
      continue;
    }
    // A compound is drawn part by part, each an instance of the same body (same colour, island, heat);
    // the body's own slot holds its first drawn part, or an empty box when it draws none.
    const render::Instance body = in;
    const auto& parts = s.compound->parts;
    // Without registerMeshes (no scene) every part is drawn.
    const std::vector<uint32_t>* listed = i < drawnParts_.size() ? &drawnParts_[i] : nullptr;
    const size_t drawn = listed ? listed->size() : parts.size();
    if (drawn == 0) {
      setPose(xf.p, xf.q, in);
      in.halfExtents[0] = in.halfExtents[1] = in.halfExtents[2] = 0.0f;
    }
    for (size_t k = 0; k < drawn; ++k) {
      const CompoundShape::Part& part = parts[listed ? (*listed)[k] : k];
      render::Instance& pi = k == 0 ? frame.instances[i] : frame.instances.emplace_back(body);
      placeShape(part.shape, Transform{xf.apply(part.local.p), xf.q * part.local.q}, pi);
    }
  }
  // Distance and rope joints have nothing of their own to see: draw each as a thin dark rod.
  for (uint32_t j = 0; j < world.jointCount(); ++j) {
    const Joint& jt = world.joint(j);
    if (jt.broken || jt.def.type != JointType::Distance) continue;
    auto at = [&](uint32_t body, const Vec3& local) { return body == kWorldBody ? local : b.xf[body].apply(local); };
    const Vec3 pa = at(jt.def.bodyA, jt.def.localAnchorA), pb = at(jt.def.bodyB, jt.def.localAnchorB);
    const float len = (pb - pa).norm();
    if (!(len > 1e-4f)) continue;
    render::Instance in;
    in.kind = render::ShapeKind::Capsule;
    const Vec3 c = 0.5f * (pa + pb);
    const Quat q = Quat::FromTwoVectors(Vec3::UnitY(), (pb - pa) / len);
    for (int k = 0; k < 3; ++k) in.position[k] = c[k];
    in.orientation[0] = q.x(); in.orientation[1] = q.y(); in.orientation[2] = q.z(); in.orientation[3] = q.w();
    in.radius = 0.012f;
    in.halfHeight = 0.5f * len;
    in.bodyId = world.bodyCount() + j;
    in.useColor = true;
    in.color[0] = in.color[1] = in.color[2] = 0.15f;
    frame.instances.push_back(in);
  }
  frame.contacts.clear();
  if (frame.showContacts) {
    for (const Contact& c : world.contacts())
      for (int k = 0; k < c.manifold.count; ++k) {
        const ContactPoint& cp = c.manifold.points[k];
        render::ContactMarker m;
        for (int d = 0; d < 3; ++d) {
          m.point[d] = cp.position[d];
          m.normal[d] = cp.normal[d];
        }
        frame.contacts.push_back(m);
      }
  }
}

}  // namespace haif

#endif
