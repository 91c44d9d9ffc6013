// The renderer's GL objects: shader programs, meshes, framebuffers and the shadow map, made once
// by init(); the buffers that grow and are refilled every frame; and their release.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>

namespace haif::render {
namespace {

std::string hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%x", v);
  return buf;
}

}  // namespace

Renderer::Impl::~Impl() {
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

void Renderer::Impl::destroyMesh(GpuMesh& m) {
  if (!gl.DeleteBuffers || !m.vao) return;
  gl.DeleteVertexArrays(1, &m.vao);
  gl.DeleteBuffers(1, &m.vbo);
  gl.DeleteBuffers(1, &m.ibo);
  m = GpuMesh{};
}

void Renderer::Impl::upload(const MeshData& data, GpuMesh& m) {
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
void Renderer::Impl::createBoxStreamBuffers() {
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
void Renderer::Impl::uploadGrowing(GLuint vbo, size_t* capacity, const void* data, size_t bytes) {
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
  if (bytes > *capacity) {
    *capacity = std::max(bytes, *capacity * 2);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(*capacity), nullptr, GL_DYNAMIC_DRAW);
  }
  if (bytes && data) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
}

// The quad index buffer must cover `faces` quads; grows (rarely) before any draw of the frame.
void Renderer::Impl::reserveQuadIndices(size_t faces) {
  if (faces <= quadIboFaces) return;
  quadIboFaces = std::max(faces, quadIboFaces * 2);
  BoxFaceStream::growQuadIndices(quadIboFaces, quadIndices);
  gl.BindVertexArray(0);
  gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, quadIbo);
  gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(quadIndices.size() * sizeof(uint32_t)),
                quadIndices.data(), GL_STATIC_DRAW);
}

void Renderer::Impl::uploadShadowStream() {
  const auto& sh = boxStream.shadowPositions();
  uploadGrowing(boxShadowVbo, &boxShadowVboCapacity, sh.data(), sh.size() * sizeof(float));
}

void Renderer::Impl::uploadCameraStream() {
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

void Renderer::Impl::uploadInstances() {
  const size_t bytes = staging.size() * sizeof(float);
  gl.BindBuffer(GL_ARRAY_BUFFER, instanceVbo);
  if (bytes > instanceCapacity) {
    // Grow geometrically so a slowly growing scene does not reallocate every frame.
    instanceCapacity = std::max(bytes, instanceCapacity * 2);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instanceCapacity), nullptr, GL_DYNAMIC_DRAW);
  }
  if (bytes) gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), staging.data());
}

bool Renderer::Impl::init(std::string* error) {
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
void Renderer::Impl::clearShadowMap() {
  const int side = std::max(opt.shadowMapSize, 1);
  gl.Viewport(0, 0, side, side);
  gl.DepthMask(GL_TRUE);
  gl.ClearDepth(1.0);
  gl.Clear(GL_DEPTH_BUFFER_BIT);
  shadowMapEmpty = true;
}

bool Renderer::Impl::checkFramebuffer(const char* what, std::string* error) {
  const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return true;
  if (error) *error = std::string("renderer: ") + what + " framebuffer incomplete (status 0x" + hex(status) + ")";
  return false;
}

bool Renderer::Impl::checkGl(const char* what, std::string* error) {
  const GLenum e = gl.GetError();
  if (e == GL_NO_ERROR) return true;
  if (error) *error = std::string("renderer: GL error 0x") + hex(e) + " during " + what;
  return false;
}

}  // namespace haif::render
