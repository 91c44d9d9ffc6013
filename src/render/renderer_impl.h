// Renderer::Impl, internal to the renderer: its state, and its members by the file that defines them.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "render/box_face_stream.h"
#include "render/box_occlusion.h"
#include "render/gl_context.h"
#include "render/gl_functions.h"
#include "render/hidden_box_faces.h"
#include "render/mesh_builder.h"
#include "render/palette.h"
#include "render/render_math.h"
#include "render/renderer.h"
#include "render/shader_program.h"
#include "render/shadow_footprint.h"
#include "render/sky_extent.h"
#include "render/text_renderer.h"
#include "render/view_setup.h"

namespace haif::render {

struct Renderer::Impl {
  // Per-instance record: position 3, quaternion 4, scale 3, capsule stretch 1, colour+emissive 4,
  // hidden box faces 1 (as a float: a HiddenBoxFaces mask of a ground box; 0 for other shapes).
  // Dynamic boxes are not instances: they go through BoxFaceStream.
  static constexpr int kInstanceFloats = 16;
  static constexpr GLsizei kInstanceStride = kInstanceFloats * sizeof(float);

  // Sun from the back left of the default camera so shadows fall towards the viewer's right.
  static inline const Vec3 kSunDir = normalize({-0.45f, 0.82f, -0.30f});

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

  // What the scene pass needs of the shadow pass.
  struct ShadowView {
    bool drawn = false;   // the map holds this frame's casters (else only the far depth)
    Mat4 lightViewProj;   // the sun's view of the casters
    float texelWorld = 0.f;  // the larger side of a shadow map texel in the world (m)
  };

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

  // renderer.cpp: the frame, phase by phase, and its read back.
  bool render(const FrameInput& f, std::vector<uint8_t>& out, std::string* error);
  void mark(double* phase);

  // renderer_resources.cpp: GL objects and the buffers refilled every frame.
  ~Impl();
  bool init(std::string* error);
  void destroyMesh(GpuMesh& m);
  void upload(const MeshData& data, GpuMesh& m);
  void createBoxStreamBuffers();
  void uploadGrowing(GLuint vbo, size_t* capacity, const void* data, size_t bytes);
  void reserveQuadIndices(size_t faces);
  void uploadShadowStream();
  void uploadCameraStream();
  void uploadInstances();
  void clearShadowMap();
  bool checkFramebuffer(const char* what, std::string* error);
  bool checkGl(const char* what, std::string* error);

  // renderer_instances.cpp: what a frame draws.
  bool classify(const FrameInput& f, SceneBounds* bounds, float* meanRadius, std::string* error);
  bool isGround(const Instance& in) const;
  void buildInstances(const FrameInput& f, const ViewSetup& view);
  void buildContactMarkers(const FrameInput& f, float meanRadius);
  void buildCameraFaces(const FrameInput& f, const ViewSetup& view);
  void findHiddenBoxFaces(const FrameInput& f);
  void findOccludedBoxes(const ViewSetup& view, size_t count);
  void addGroundFace(const Instance& in, bool isBox);
  void pushInstance(Vec3 p, const float* q, Vec3 scale, float stretch, LinearColor c, float emissive,
                    unsigned hidden = 0);
  size_t instanceCount() const;
  void addGroup(const GpuMesh* mesh, size_t first, int surface, bool cull, bool casts);

  // renderer_passes.cpp: the GL passes.
  ShadowView drawShadowMap(const SceneBounds& bounds, size_t casterGroups);
  void drawScene(const ViewSetup& view, const SceneBounds& bounds, const ShadowView& shadow);
  void drawSky(const ViewSetup& view);
  Mat4 lightMatrix(const SceneBounds& casters, float* texelWorld) const;
  void drawGroup(const DrawGroup& g);
  void drawGroundGroup(const DrawGroup& g, const PixelRect& shade);
  void drawQuads(GLuint vao, size_t first, size_t faces);
};

}  // namespace haif::render
