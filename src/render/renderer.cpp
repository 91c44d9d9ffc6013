#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "render/box_face_stream.h"
#include "render/box_occlusion.h"
#include "render/gl_context.h"
#include "render/gl_functions.h"
#include "render/hidden_box_faces.h"
#include "render/mesh_builder.h"
#include "render/overlay.h"
#include "render/palette.h"
#include "render/png_io.h"
#include "render/shader_program.h"
#include "render/shadow_footprint.h"
#include "render/sky_extent.h"
#include "render/text_renderer.h"
#include "render/view_setup.h"

namespace haif::render {
namespace {

// Per-instance record: position 3, quaternion 4, scale 3, capsule stretch 1, colour+emissive 4,
// hidden box faces 1 (as a float: a HiddenBoxFaces mask of a ground box; 0 for other shapes).
// Dynamic boxes are not instances: they go through BoxFaceStream.
constexpr int kInstanceFloats = 16;
constexpr GLsizei kInstanceStride = kInstanceFloats * sizeof(float);
constexpr float kPlaneHalfSize = 1000.f;
constexpr int kSkyRows = 24;
constexpr GLenum kPackInvertMesa = 0x8758;  // GL_PACK_INVERT_MESA (GL_MESA_pack_invert)  // must match kRows in shaders/sky.vert

// Ordering of draw groups: boxes (the face stream), other bodies (each group front to back), the
// ground after them, so early depth testing skips most hidden pixels; fragment work dominates on
// llvmpipe.
enum GroupKind : uint32_t { kBox, kSphere, kCapsule, kHull, kTriMesh, kGroundBox, kGroundPlane };
// kSurfaceGroundUnshadowed: the ground where no shadow can fall; kSurfaceBoxAway: box faces turned
// away from the sun (neither samples the shadow map).
enum Surface : int {
  kSurfaceBody = 0,
  kSurfaceGround = 1,
  kSurfaceBox = 2,
  kSurfaceGroundUnshadowed = 3,
  kSurfaceBoxAway = 4
};

struct GpuMesh {
  GLuint vao = 0, vbo = 0, ibo = 0;
  GLsizei indexCount = 0;
  float boundRadius = 1.f;
};

struct DrawGroup {
  const GpuMesh* mesh;
  size_t first, count;
  int surface;
  bool cull;          // closed shapes only; open triangle meshes and planes are two-sided
  bool castsShadow;
};

struct SortItem {
  uint32_t kind, meshId;
  float depth;  // squared distance from the eye, for front-to-back order inside a group
  uint32_t index;
};

// Sun from the back left of the default camera so shadows fall towards the viewer's right.
const Vec3 kSunDir = normalize({-0.45f, 0.82f, -0.30f});

}  // namespace

struct Renderer::Impl {
  RendererOptions opt;
  int samples = 1;
  std::unique_ptr<GlContext> ctx;
  GlFunctions gl;
  ShaderProgram sceneProgram[5], shadowProgram, boxShadowProgram, skyProgram;  // scene: one variant per Surface
  GpuMesh box, sphere, capsule, plane;  // box: ground boxes (dynamic boxes go through boxStream)
  std::unordered_map<uint32_t, GpuMesh> meshes;
  GLuint instanceVbo = 0;
  size_t instanceCapacity = 0;  // bytes
  GLuint msaaFbo = 0, msaaColor = 0, msaaDepth = 0, resolveFbo = 0, resolveColor = 0;
  GLuint shadowFbo = 0, shadowTex = 0, emptyVao = 0;
  // The box face streams: camera faces (BoxFaceVertex) and shadow faces (xyz), one shared quad index buffer.
  BoxFaceStream boxStream;
  std::vector<uint32_t> quadIndices;
  GLuint boxVao = 0, boxVbo = 0, boxShadowVao = 0, boxShadowVbo = 0, quadIbo = 0;
  size_t boxVboCapacity = 0, boxShadowVboCapacity = 0, quadIboFaces = 0;  // bytes, bytes, quads
  bool shadowMapEmpty = false;  // the map holds only the far depth (cleared while nothing casts)
  // Reused every frame so steady-state rendering does not allocate.
  std::vector<float> staging;
  std::vector<SortItem> order;
  std::vector<FramingSphere> framing;
  std::vector<DrawGroup> groups;
  std::vector<GroundFace> groundFaces;  // for skyStartNdc
  HiddenBoxFaces hiddenFaces;
  std::vector<BoxPose> boxPoses;      // boxes of this frame in draw order, for hiddenFaces
  std::vector<uint8_t> hiddenMasks;   // per entry of boxPoses
  BoxOcclusion occlusion;
  std::vector<uint8_t> occludedFaces, occludedBoxes;  // per dynamic box of boxPoses (BoxOcclusion::find)
  size_t dynamicBoxes = 0;  // the first entries of order and boxPoses
  std::vector<uint8_t> readback;  // bottom-up rows, unless packInvert
  bool packInvert = false;        // GL_MESA_pack_invert: glReadPixels returns the top row first
  std::unique_ptr<TextRenderer> text;  // created on the first frame with the overlay enabled
  RenderPhaseTimes phases;
  std::chrono::steady_clock::time_point phaseStart;

  // With timePhases: finishes the GL work queued so far and books the time since the last mark.
  void mark(double* phase) {
    if (!opt.timePhases) return;
    gl.Finish();
    const auto now = std::chrono::steady_clock::now();
    if (phase) *phase = std::chrono::duration<double, std::milli>(now - phaseStart).count();
    phaseStart = now;
  }

  ~Impl() {
    if (!ctx) return;
    std::string ignored;
    ctx->makeCurrent(&ignored);
    for (GpuMesh* m : {&box, &sphere, &capsule, &plane}) destroyMesh(*m);
    for (auto& kv : meshes) destroyMesh(kv.second);
    if (gl.DeleteBuffers) {
      gl.DeleteBuffers(1, &instanceVbo);
      gl.DeleteFramebuffers(1, &msaaFbo);
      gl.DeleteFramebuffers(1, &resolveFbo);
      gl.DeleteFramebuffers(1, &shadowFbo);
      gl.DeleteRenderbuffers(1, &msaaColor);
      gl.DeleteRenderbuffers(1, &msaaDepth);
      gl.DeleteRenderbuffers(1, &resolveColor);
      gl.DeleteTextures(1, &shadowTex);
      gl.DeleteVertexArrays(1, &emptyVao);
      gl.DeleteVertexArrays(1, &boxVao);
      gl.DeleteVertexArrays(1, &boxShadowVao);
      gl.DeleteBuffers(1, &boxVbo);
      gl.DeleteBuffers(1, &boxShadowVbo);
      gl.DeleteBuffers(1, &quadIbo);
    }
  }

  void destroyMesh(GpuMesh& m) {
    if (!gl.DeleteBuffers || !m.vao) return;
    gl.DeleteVertexArrays(1, &m.vao);
    gl.DeleteBuffers(1, &m.vbo);
    gl.DeleteBuffers(1, &m.ibo);
    m = GpuMesh{};
  }

  void upload(const MeshData& data, GpuMesh& m) {
    destroyMesh(m);
    gl.GenVertexArrays(1, &m.vao);
    gl.GenBuffers(1, &m.vbo);
    gl.GenBuffers(1, &m.ibo);
    gl.BindVertexArray(m.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.vertices.size() * sizeof(float)),
                  data.vertices.data(), GL_STATIC_DRAW);
    const GLsizei stride = MeshData::kFloatsPerVertex * sizeof(float);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(3 * sizeof(float)));
    gl.EnableVertexAttribArray(2);
    gl.VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(6 * sizeof(float)));
    // Instance attributes: enabled and stepped once per instance; their pointers are set per draw.
    for (GLuint a = 3; a <= 8; ++a) {
      gl.EnableVertexAttribArray(a);
      gl.VertexAttribDivisor(a, 1);
    }
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.indices.size() * sizeof(uint32_t)),
                  data.indices.data(), GL_STATIC_DRAW);
    gl.BindVertexArray(0);
    m.indexCount = static_cast<GLsizei>(data.indices.size());
    m.boundRadius = data.boundRadius;
  }

  // Vertex arrays of the two box face streams; their buffers are sized by uploadBoxStreams.
  void createBoxStreamBuffers() {
    static_assert(sizeof(BoxFaceVertex) == 14 * sizeof(float), "BoxFaceVertex must be tightly packed");
    gl.GenBuffers(1, &quadIbo);
    gl.GenVertexArrays(1, &boxVao);
    gl.GenBuffers(1, &boxVbo);
    gl.BindVertexArray(boxVao);
    gl.BindBuffer(GL_ARRAY_BUFFER, boxVbo);
    const GLsizei stride = sizeof(BoxFaceVertex);
    const GLint sizes[5] = {3, 3, 3, 4, 1};
    const size_t offsets[5] = {offsetof(BoxFaceVertex, position), offsetof(BoxFaceVertex, normal),
                               offsetof(BoxFaceVertex, color), offsetof(BoxFaceVertex, edge),
                               offsetof(BoxFaceVertex, edgeWidth)};
    for (GLuint a = 0; a < 5; ++a) {
      gl.EnableVertexAttribArray(a);
      gl.VertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsets[a]));
    }
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, quadIbo);
    gl.GenVertexArrays(1, &boxShadowVao);
    gl.GenBuffers(1, &boxShadowVbo);
    gl.BindVertexArray(boxShadowVao);
    gl.BindBuffer(GL_ARRAY_BUFFER, boxShadowVbo);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, quadIbo);
    gl.BindVertexArray(0);
  }

  // Makes vbo hold at least `bytes`, growing it geometrically (a slowly growing scene must not
  // reallocate every frame), and copies them from data unless it is null. Leaves vbo bound.
  void uploadGrowing(GLuint vbo, size_t* capacity, const void* data, size_t bytes) {
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    if (bytes > *capacity) {
      *capacity = std::max(bytes, *capacity * 2);
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(*capacity), nullptr, GL_DYNAMIC_DRAW);
    }
    if (bytes && data) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
  }

  // The quad index buffer must cover `faces` quads; grows (rarely) before any draw of the frame.
  void reserveQuadIndices(size_t faces) {
    if (faces <= quadIboFaces) return;
    quadIboFaces = std::max(faces, quadIboFaces * 2);
    BoxFaceStream::growQuadIndices(quadIboFaces, quadIndices);
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, quadIbo);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(quadIndices.size() * sizeof(uint32_t)),
                  quadIndices.data(), GL_STATIC_DRAW);
  }

  void uploadShadowStream() {
    const auto& sh = boxStream.shadowPositions();
    uploadGrowing(boxShadowVbo, &boxShadowVboCapacity, sh.data(), sh.size() * sizeof(float));
  }

  void uploadCameraStream() {
    // One buffer: the faces turned to the sun, then those turned away.
    const auto& sunward = boxStream.sunwardVertices();
    const auto& away = boxStream.awayVertices();
    const size_t sunwardBytes = sunward.size() * sizeof(BoxFaceVertex);
    uploadGrowing(boxVbo, &boxVboCapacity, nullptr, sunwardBytes + away.size() * sizeof(BoxFaceVertex));
    if (!sunward.empty()) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(sunwardBytes), sunward.data());
    if (!away.empty())
      gl.BufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(sunwardBytes),
                       static_cast<GLsizeiptr>(away.size() * sizeof(BoxFaceVertex)), away.data());
  }

  // One non-instanced draw of quads [first, first + faces) of vao.
  void drawQuads(GLuint vao, size_t first, size_t faces) {
    if (!faces) return;
    gl.BindVertexArray(vao);
    gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(6 * faces), GL_UNSIGNED_INT,
                    reinterpret_cast<void*>(6 * first * sizeof(uint32_t)));
  }

  bool init(std::string* error) {
    if (opt.width <= 0 || opt.height <= 0 || opt.width > 16384 || opt.height > 16384) {
      if (error) *error = "renderer: invalid image size " + std::to_string(opt.width) + "x" + std::to_string(opt.height);
      return false;
    }
    ctx = createGlContext(opt.gl, error);
    if (!ctx || !gl.load(*ctx, error)) return false;
    for (int surface : {kSurfaceBody, kSurfaceGround, kSurfaceBox, kSurfaceGroundUnshadowed, kSurfaceBoxAway}) {
      const std::string defines = surface == kSurfaceGroundUnshadowed ? "#define SURFACE 1\n#define RECEIVES_SHADOW 0\n"
                                  : surface == kSurfaceBoxAway ? "#define SURFACE 2\n#define RECEIVES_SHADOW 0\n"
                                                               : "#define SURFACE " + std::to_string(surface) + "\n";
      const char* vert = surface == kSurfaceBox || surface == kSurfaceBoxAway ? "box.vert" : "scene.vert";
      if (!sceneProgram[surface].load(gl, opt.shaderDir, vert, "scene.frag", error, defines)) return false;
    }
    if (!shadowProgram.load(gl, opt.shaderDir, "shadow.vert", "shadow.frag", error) ||
        !boxShadowProgram.load(gl, opt.shaderDir, "box_shadow.vert", "shadow.frag", error) ||
        !skyProgram.load(gl, opt.shaderDir, "sky.vert", "sky.frag", error))
      return false;

    upload(makeBoxMesh(), box);
    upload(makeSphereMesh(24, 14), sphere);
    upload(makeCapsuleMesh(24, 7), capsule);
    upload(makePlaneMesh(), plane);
    gl.GenBuffers(1, &instanceVbo);
    gl.GenVertexArrays(1, &emptyVao);
    createBoxStreamBuffers();

    GLint maxSamples = 1;
    gl.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    samples = std::clamp(opt.msaaSamples, 1, std::max(1, static_cast<int>(maxSamples)));

    gl.GenFramebuffers(1, &msaaFbo);
    gl.GenRenderbuffers(1, &msaaColor);
    gl.GenRenderbuffers(1, &msaaDepth);
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaaFbo);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaaColor);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA8, opt.width, opt.height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColor);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaaDepth);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_DEPTH_COMPONENT24,
                                      opt.width, opt.height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaaDepth);
    if (!checkFramebuffer("scene", error)) return false;
    if (samples > 1) {
      // Where the GPU puts its samples, so the occlusion test covers exactly those points.
      std::vector<float> xy(2 * static_cast<size_t>(samples));
      for (int s = 0; s < samples; ++s) gl.GetMultisamplefv(GL_SAMPLE_POSITION, static_cast<GLuint>(s), &xy[2 * s]);
      occlusion.setSamples(xy.data(), samples);
    }

    if (samples > 1) {
      gl.GenFramebuffers(1, &resolveFbo);
      gl.GenRenderbuffers(1, &resolveColor);
      gl.BindFramebuffer(GL_FRAMEBUFFER, resolveFbo);
      gl.BindRenderbuffer(GL_RENDERBUFFER, resolveColor);
      gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, opt.width, opt.height);
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveColor);
      if (!checkFramebuffer("resolve", error)) return false;
    }

    {
      // Always present (1 texel without shadows): scene.frag samples it unconditionally, and a
      // map holding 1.0 everywhere lights every point.
      opt.shadowMapSize = std::clamp(opt.shadowMapSize, 0, 8192);
      const int side = std::max(opt.shadowMapSize, 1);
      gl.GenTextures(1, &shadowTex);
      gl.BindTexture(GL_TEXTURE_2D, shadowTex);
      gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, side, side, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT,
                    nullptr);
      // Linear filtering + compare mode: each tap is already a 2x2 bilinear PCF.
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
      const float border[4] = {1.f, 1.f, 1.f, 1.f};
      gl.TexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
      gl.GenFramebuffers(1, &shadowFbo);
      gl.BindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
      gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTex, 0);
      gl.DrawBuffer(GL_NONE);
      gl.ReadBuffer(GL_NONE);
      if (!checkFramebuffer("shadow", error)) return false;
      clearShadowMap();
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    GLint extensions = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    for (GLint i = 0; i < extensions; ++i) {
      const GLubyte* name = gl.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
      if (name && std::strcmp(reinterpret_cast<const char*>(name), "GL_MESA_pack_invert") == 0) packInvert = true;
    }
    if (!packInvert) readback.resize(static_cast<size_t>(opt.width) * opt.height * 4);
    return checkGl("initialisation", error);
  }

  // Fills the shadow map with the far depth (nothing casts); needs shadowFbo bound.
  void clearShadowMap() {
    const int side = std::max(opt.shadowMapSize, 1);
    gl.Viewport(0, 0, side, side);
    gl.DepthMask(GL_TRUE);
    gl.ClearDepth(1.0);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    shadowMapEmpty = true;
  }

  bool checkFramebuffer(const char* what, std::string* error) {
    const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE) return true;
    if (error) *error = std::string("renderer: ") + what + " framebuffer incomplete (status 0x" + hex(status) + ")";
    return false;
  }

  bool checkGl(const char* what, std::string* error) {
    const GLenum e = gl.GetError();
    if (e == GL_NO_ERROR) return true;
    if (error) *error = std::string("renderer: GL error 0x") + hex(e) + " during " + what;
    return false;
  }

  static std::string hex(unsigned v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%x", v);
    return buf;
  }

  bool isGround(const Instance& in) const {
    if (in.kind == ShapeKind::Plane) return true;
    return in.kind == ShapeKind::Box && in.isStatic &&
           std::max(in.halfExtents[0], in.halfExtents[2]) >= opt.groundMinHalfExtent;
  }

  static bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

  // Unit quaternion from q; identity for a zero or non-finite one.
  static void normalizedQuat(const float* q, float* qn) {
    for (int k = 0; k < 4; ++k) qn[k] = q[k];
    const float len = std::sqrt(qn[0] * qn[0] + qn[1] * qn[1] + qn[2] * qn[2] + qn[3] * qn[3]);
    if (!(len > 1e-12f) || !std::isfinite(len))
      qn[0] = qn[1] = qn[2] = 0.f, qn[3] = 1.f;
    else
      for (int k = 0; k < 4; ++k) qn[k] /= len;
  }

  void pushInstance(Vec3 p, const float* q, Vec3 scale, float stretch, LinearColor c, float emissive,
                    unsigned hidden = 0) {
    float qn[4];
    normalizedQuat(q, qn);
    staging.insert(staging.end(), {p.x, p.y, p.z, qn[0], qn[1], qn[2], qn[3], scale.x, scale.y, scale.z,
                                   stretch, c.r, c.g, c.b, emissive, static_cast<float>(hidden)});
  }

  // Hidden-face masks for the boxes of the sorted order (ground boxes included: they cover the
  // bottoms of the boxes resting on them), in the order buildInstances pushes them.
  void findHiddenBoxFaces(const FrameInput& f) {
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
  void findOccludedBoxes(const ViewSetup& view, size_t count) {
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

  size_t instanceCount() const { return staging.size() / kInstanceFloats; }

  // A group of the instances pushed since `first`.
  void addGroup(const GpuMesh* mesh, size_t first, int surface, bool cull, bool casts) {
    const size_t count = instanceCount() - first;
    if (count) groups.push_back({mesh, first, count, surface, cull, casts});
  }

  // Bounds of everything but the ground (for framing and the shadow frustum) and the draw kind of
  // each instance. Returns false for unregistered meshes.
  bool classify(const FrameInput& f, SceneBounds* bounds, float* meanRadius, std::string* error) {
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
  void buildCameraFaces(const FrameInput& f, const ViewSetup& view) {
    findOccludedBoxes(view, dynamicBoxes);
    for (size_t k = 0; k < dynamicBoxes; ++k)
      if (!occludedBoxes[k])
        boxStream.addCameraFaces(boxPoses[k], instanceColor(f.instances[order[k].index], f.mode),
                                 hiddenMasks[k] | occludedFaces[k], view.eye, kSunDir);
  }

  // Sorts instances into draw groups (front to back inside each) and fills the staging buffer.
  void buildInstances(const FrameInput& f, const ViewSetup& view) {
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
  void addGroundFace(const Instance& in, bool isBox) {
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

  void buildContactMarkers(const FrameInput& f, float meanRadius) {
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

  void uploadInstances() {
    const size_t bytes = staging.size() * sizeof(float);
    gl.BindBuffer(GL_ARRAY_BUFFER, instanceVbo);
    if (bytes > instanceCapacity) {
      // Grow geometrically so a slowly growing scene does not reallocate every frame.
      instanceCapacity = std::max(bytes, instanceCapacity * 2);
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instanceCapacity), nullptr, GL_DYNAMIC_DRAW);
    }
    if (bytes) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), staging.data());
  }

  void drawGroup(const DrawGroup& g) {
    gl.BindVertexArray(g.mesh->vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, instanceVbo);
    const size_t base = g.first * kInstanceStride;
    auto at = [&](size_t floats) { return reinterpret_cast<void*>(base + floats * sizeof(float)); };
    gl.VertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, kInstanceStride, at(0));
    gl.VertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, kInstanceStride, at(3));
    gl.VertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, kInstanceStride, at(7));
    gl.VertexAttribPointer(6, 1, GL_FLOAT, GL_FALSE, kInstanceStride, at(10));
    gl.VertexAttribPointer(7, 4, GL_FLOAT, GL_FALSE, kInstanceStride, at(11));
    gl.VertexAttribPointer(8, 1, GL_FLOAT, GL_FALSE, kInstanceStride, at(15));
    if (g.cull)
      gl.Enable(GL_CULL_FACE);
    else
      gl.Disable(GL_CULL_FACE);
    gl.DrawElementsInstanced(GL_TRIANGLES, g.mesh->indexCount, GL_UNSIGNED_INT, nullptr,
                             static_cast<GLsizei>(g.count));
  }

  // A ground group: the shadowed variant inside `shade`, the unshadowed one in up to four bands
  // around it (scissored, so each pixel is drawn by exactly one of them).
  void drawGroundGroup(const DrawGroup& g, const PixelRect& shade) {
    const int w = opt.width, h = opt.height;
    if (shade.empty()) {
      sceneProgram[kSurfaceGroundUnshadowed].use();
      drawGroup(g);
      return;
    }
    gl.Enable(GL_SCISSOR_TEST);
    sceneProgram[kSurfaceGround].use();
    gl.Scissor(shade.x0, shade.y0, shade.x1 - shade.x0, shade.y1 - shade.y0);
    drawGroup(g);
    sceneProgram[kSurfaceGroundUnshadowed].use();
    const PixelRect bands[4] = {{0, 0, w, shade.y0},
                                {0, shade.y1, w, h},
                                {0, shade.y0, shade.x0, shade.y1},
                                {shade.x1, shade.y0, w, shade.y1}};
    for (const PixelRect& b : bands) {
      if (b.empty()) continue;
      gl.Scissor(b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
      drawGroup(g);
    }
    gl.Disable(GL_SCISSOR_TEST);
  }

  // Orthographic sun view fitted to the casters' box as seen from the sun (tighter than their
  // bounding sphere, so a smaller map gives the same texel size). Extents are quantised and the
  // centre snapped to whole texels so shadows do not shimmer when the framing moves a little.
  Mat4 lightMatrix(const SceneBounds& casters, float* texelWorld) const {
    const Vec3 f = kSunDir * -1.f;
    const Vec3 s = normalize(cross(f, {0.f, 1.f, 0.f}));
    const Vec3 u = cross(s, f);
    float lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f};
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p{(corner & 1) ? casters.max.x : casters.min.x, (corner & 2) ? casters.max.y : casters.min.y,
                   (corner & 4) ? casters.max.z : casters.min.z};
      const float ps[2] = {dot(p, s), dot(p, u)};
      for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], ps[k]), hi[k] = std::max(hi[k], ps[k]);
    }
    const auto quantise = [](float half) {  // texel size changes in steps of 2^(1/4)
      return std::pow(2.f, std::ceil(std::log2(std::max(half, 0.5f)) * 4.f) / 4.f);
    };
    const float hw = quantise(0.5f * (hi[0] - lo[0])), hh = quantise(0.5f * (hi[1] - lo[1]));
    const float texelS = 2.f * hw / static_cast<float>(opt.shadowMapSize);
    const float texelU = 2.f * hh / static_cast<float>(opt.shadowMapSize);
    const float sx = std::round(0.5f * (lo[0] + hi[0]) / texelS) * texelS;
    const float sy = std::round(0.5f * (lo[1] + hi[1]) / texelU) * texelU;
    const Vec3 c = casters.center();
    const Vec3 center = s * sx + u * sy + f * dot(c, f);
    // Depth: the casters' sphere in front, and room behind it for the ground they shade.
    const float r = std::max(casters.radius(), 0.5f);
    *texelWorld = std::max(texelS, texelU);
    return ortho(-hw, hw, -hh, hh, r, 9.f * r) * lookAt(center - f * (3.f * r), center, u);
  }

  bool render(const FrameInput& f, std::vector<uint8_t>& out, std::string* error) {
    if (!ctx->makeCurrent(error)) return false;
    phases = RenderPhaseTimes{};
    mark(nullptr);
    SceneBounds bounds;
    float meanRadius = 0.5f;
    if (!classify(f, &bounds, &meanRadius, error)) return false;
    const ViewSetup view = computeView(f.camera, bounds, opt.width, opt.height, &framing);
    buildInstances(f, view);
    const size_t groupsBeforeMarkers = groups.size();
    buildContactMarkers(f, meanRadius);
    uploadInstances();
    uploadShadowStream();
    // Up to 6 camera faces per box (faces seen edge-on are kept), so one size fits both streams.
    reserveQuadIndices(std::max(boxStream.shadowFaces(), 6 * dynamicBoxes));
    mark(&phases.prepare);

    const Vec3 focus = bounds.valid ? bounds.center() : Vec3{0.f, 0.f, 0.f};
    const float sceneR = bounds.valid ? std::max(bounds.radius(), 1.f) : 5.f;
    const float eyeDist = length(view.eye - focus);

    // ---- shadow pass ----
    float texelWorld = 0.f;
    Mat4 lightVP;
    bool shadows = boxStream.shadowFaces() > 0;
    for (size_t i = 0; i < groupsBeforeMarkers; ++i) shadows |= groups[i].castsShadow;
    shadows = shadows && opt.shadowMapSize > 0;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    gl.CullFace(GL_BACK);
    if (shadows) {
      lightVP = lightMatrix(bounds, &texelWorld);
      gl.BindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
      gl.Viewport(0, 0, opt.shadowMapSize, opt.shadowMapSize);
      gl.Clear(GL_DEPTH_BUFFER_BIT);
      gl.Enable(GL_POLYGON_OFFSET_FILL);
      gl.PolygonOffset(1.5f, 3.f);
      // Boxes: only the three faces turned to the sun (the ones culling would keep); their
      // winding is not checked, so no face culling.
      boxShadowProgram.use();
      gl.UniformMatrix4fv(boxShadowProgram.uniform("uLightViewProj"), 1, GL_FALSE, lightVP.m);
      gl.Disable(GL_CULL_FACE);
      drawQuads(boxShadowVao, 0, boxStream.shadowFaces());
      shadowProgram.use();
      gl.UniformMatrix4fv(shadowProgram.uniform("uLightViewProj"), 1, GL_FALSE, lightVP.m);
      for (size_t i = 0; i < groupsBeforeMarkers; ++i)
        if (groups[i].castsShadow) drawGroup(groups[i]);
      gl.Disable(GL_POLYGON_OFFSET_FILL);
      shadowMapEmpty = false;
    } else if (!shadowMapEmpty) {
      gl.BindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
      clearShadowMap();
    }
    mark(&phases.shadow);

    // ---- what the camera sees of the boxes, while the rasteriser threads draw the shadow map ----
    gl.Flush();
    buildCameraFaces(f, view);
    uploadCameraStream();
    double cameraFacesMs = 0.0;
    mark(&cameraFacesMs);
    phases.prepare += cameraFacesMs;

    // ---- main pass ----
    const LinearColor horizon{srgbToLinear(0.80f), srgbToLinear(0.85f), srgbToLinear(0.90f)};
    const LinearColor zenith{srgbToLinear(0.38f), srgbToLinear(0.56f), srgbToLinear(0.80f)};
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaaFbo);
    gl.Viewport(0, 0, opt.width, opt.height);
    // No colour clear: the sky pass below fills every pixel that geometry left empty, and an
    // MSAA clear is expensive on llvmpipe.
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    for (const ShaderProgram& sp : sceneProgram) {
      sp.use();
      gl.UniformMatrix4fv(sp.uniform("uViewProj"), 1, GL_FALSE, view.viewProj.m);
      gl.UniformMatrix4fv(sp.uniform("uLightViewProj"), 1, GL_FALSE, lightVP.m);
      gl.Uniform1f(sp.uniform("uShadowNormalOffset"), 1.5f * texelWorld);
      gl.Uniform1i(sp.uniform("uShadowMap"), 0);
      gl.Uniform3f(sp.uniform("uSunDir"), kSunDir.x, kSunDir.y, kSunDir.z);
      gl.Uniform3f(sp.uniform("uSunColor"), 1.25f, 1.18f, 1.05f);
      gl.Uniform3f(sp.uniform("uSkyAmbient"), 0.30f, 0.36f, 0.46f);
      gl.Uniform3f(sp.uniform("uGroundAmbient"), 0.16f, 0.14f, 0.12f);
      gl.Uniform3f(sp.uniform("uEye"), view.eye.x, view.eye.y, view.eye.z);
      gl.Uniform3f(sp.uniform("uFogColor"), horizon.r, horizon.g, horizon.b);
      gl.Uniform1f(sp.uniform("uFogDistance"), (eyeDist + 2.f * sceneR) * 2.5f);
      gl.Uniform3f(sp.uniform("uGroundColor"), srgbToLinear(0.70f), srgbToLinear(0.70f), srgbToLinear(0.68f));
      gl.Uniform1f(sp.uniform("uGridSpacing"), 1.f);
      gl.Uniform1f(sp.uniform("uGridFade"), eyeDist + 3.f * sceneR);
    }
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, shadowTex);
    // The ground gets the shadow lookup only inside the rectangle where shadows can fall.
    PixelRect shade{0, 0, opt.width, opt.height};
    if (shadows) {
      PixelRect u{opt.width, opt.height, 0, 0};
      for (const GroundFace& face : groundFaces) {
        const PixelRect r = groundShadowRect(view, opt.width, opt.height, bounds, kSunDir, face, 6.f * texelWorld);
        u = {std::min(u.x0, r.x0), std::min(u.y0, r.y0), std::max(u.x1, r.x1), std::max(u.y1, r.y1)};
      }
      shade = u;
    } else {
      shade = PixelRect{};
    }
    gl.Enable(GL_CULL_FACE);
    sceneProgram[kSurfaceBox].use();
    drawQuads(boxVao, 0, boxStream.sunwardFaces());
    sceneProgram[kSurfaceBoxAway].use();
    drawQuads(boxVao, boxStream.sunwardFaces(), boxStream.awayFaces());
    int bound = kSurfaceBoxAway;
    for (const DrawGroup& g : groups) {
      if (g.surface == kSurfaceGround) {
        drawGroundGroup(g, shade);
        bound = -1;
        continue;
      }
      if (g.surface != bound) sceneProgram[g.surface].use(), bound = g.surface;
      drawGroup(g);
    }
    mark(&phases.scene);

    // ---- sky where nothing was drawn ----
    gl.Disable(GL_CULL_FACE);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    skyProgram.use();
    gl.Uniform3f(skyProgram.uniform("uForward"), view.forward.x, view.forward.y, view.forward.z);
    gl.Uniform3f(skyProgram.uniform("uRight"), view.right.x, view.right.y, view.right.z);
    gl.Uniform3f(skyProgram.uniform("uUp"), view.up.x, view.up.y, view.up.z);
    gl.Uniform2f(skyProgram.uniform("uTanHalfFov"), view.tanHalfFovY * view.aspect, view.tanHalfFovY);
    gl.Uniform3f(skyProgram.uniform("uHorizon"), horizon.r, horizon.g, horizon.b);
    gl.Uniform3f(skyProgram.uniform("uZenith"), zenith.r, zenith.g, zenith.b);
    const float skyBottom = skyStartNdc(view, opt.height, groundFaces);
    gl.Uniform1f(skyProgram.uniform("uBottom"), skyBottom);
    gl.BindVertexArray(emptyVao);
    if (skyBottom < 1.f) gl.DrawArrays(GL_TRIANGLE_STRIP, 0, 2 * (kSkyRows + 1));
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    gl.BindVertexArray(0);
    mark(&phases.sky);

    // ---- resolve + read back ----
    GLuint readFbo = msaaFbo;
    if (samples > 1) {
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaaFbo);
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo);
      gl.BlitFramebuffer(0, 0, opt.width, opt.height, 0, 0, opt.width, opt.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      readFbo = resolveFbo;
    }
    mark(&phases.resolve);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, readFbo);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    // GL row 0 is the bottom of the image; callers get the top row first.
    const size_t rowBytes = static_cast<size_t>(opt.width) * 4;
    out.resize(rowBytes * opt.height);
    if (packInvert) gl.PixelStorei(kPackInvertMesa, GL_TRUE);
    gl.ReadPixels(0, 0, opt.width, opt.height, GL_RGBA, GL_UNSIGNED_BYTE, packInvert ? out.data() : readback.data());
    if (packInvert) gl.PixelStorei(kPackInvertMesa, GL_FALSE);
    if (!checkGl("rendering", error)) return false;
    mark(&phases.readback);
    if (!packInvert)
      for (int y = 0; y < opt.height; ++y)
        std::memcpy(out.data() + rowBytes * y, readback.data() + rowBytes * (opt.height - 1 - y), rowBytes);
    mark(&phases.flip);

    if (f.overlay.enabled) {
      if (!text) {
        text = TextRenderer::create(opt.fontPath, error);
        if (!text) return false;
      }
      Canvas canvas(out.data(), opt.width, opt.height);
      drawOverlay(canvas, *text, f.overlay, f.mode);
    }
    mark(&phases.overlay);
    return true;
  }
};

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

std::unique_ptr<Renderer> Renderer::create(const RendererOptions& options, std::string* error) {
  auto impl = std::make_unique<Impl>();
  impl->opt = options;
  if (!impl->init(error)) return nullptr;
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

bool Renderer::registerMesh(uint32_t meshId, const std::vector<float>& positions,
                            const std::vector<uint32_t>& indices, std::string* error) {
  const MeshData data = makeFlatMesh(positions, indices);
  if (data.indices.empty()) {
    if (error) *error = "renderer: mesh " + std::to_string(meshId) + " has no valid triangle";
    return false;
  }
  if (!impl_->ctx->makeCurrent(error)) return false;
  impl_->upload(data, impl_->meshes[meshId]);
  return impl_->checkGl("mesh upload", error);
}

bool Renderer::hasMesh(uint32_t meshId) const { return impl_->meshes.count(meshId) != 0; }

bool Renderer::render(const FrameInput& frame, std::vector<uint8_t>& rgba, std::string* error) {
  return impl_->render(frame, rgba, error);
}

bool Renderer::renderToPng(const FrameInput& frame, const std::string& path, std::string* error) {
  std::vector<uint8_t> rgba;
  return render(frame, rgba, error) && writePng(path, impl_->opt.width, impl_->opt.height, rgba.data(), error);
}

int Renderer::width() const { return impl_->opt.width; }
int Renderer::height() const { return impl_->opt.height; }
int Renderer::msaaSamples() const { return impl_->samples; }
const RenderPhaseTimes& Renderer::lastPhaseTimes() const { return impl_->phases; }

}  // namespace haif::render
