// OSMesa backend of GlContext. Only this file includes the OSMesa header, so the rest of the
// renderer is free of it (egl_context.cpp is the other back end). Built only where OSMesa is found
// (CMakeLists.txt); gl_backend.cpp knows whether it was.
#include "render/gl_context.h"

#include <GL/osmesa.h>

#include <vector>

namespace haif::render {
namespace {

class OsMesaContext final : public GlContext {
 public:
  ~OsMesaContext() override {
    if (context_) OSMesaDestroyContext(context_);
  }

  bool init(std::string* error) {
    // Ask for 4.5 core first (what Mesa 22 gives), then fall back to the 3.3 minimum.
    const int versions[][2] = {{4, 5}, {3, 3}};
    for (const auto& v : versions) {
      const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                             OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                             OSMESA_CONTEXT_MAJOR_VERSION, v[0],
                             OSMESA_CONTEXT_MINOR_VERSION, v[1], 0};
      context_ = OSMesaCreateContextAttribs(attribs, nullptr);
      if (context_) break;
    }
    if (!context_) {
      if (error) *error = "OSMesa: could not create a core-profile OpenGL 3.3+ context";
      return false;
    }
    return makeCurrent(error);
  }

  bool makeCurrent(std::string* error) override {
    // All drawing goes to FBOs; the window-system buffer only has to exist, so keep it tiny.
    if (!OSMesaMakeCurrent(context_, backing_.data(), GL_UNSIGNED_BYTE, kBackingSize, kBackingSize)) {
      if (error) *error = "OSMesa: OSMesaMakeCurrent failed";
      return false;
    }
    return true;
  }

  GlProc getProcAddress(const char* name) const override {
    return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
  }

  const char* backendName() const override { return "OSMesa"; }

 private:
  static constexpr int kBackingSize = 16;
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> backing_ = std::vector<unsigned char>(kBackingSize * kBackingSize * 4);
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext(std::string* error) {
  auto ctx = std::make_unique<OsMesaContext>();
  if (!ctx->init(error)) return nullptr;
  return ctx;
}

}  // namespace haif::render
