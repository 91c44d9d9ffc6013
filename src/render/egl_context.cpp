// EGL backend of GlContext: a surfaceless context (EGL_MESA_platform_surfaceless, no window
// system, no config: EGL_KHR_no_config_context) on Mesa's llvmpipe or whatever driver EGL finds.
// Mesa removed OSMesa in 25.1; this is the back end that outlives it. Only this file includes EGL.
// Built only where EGL is found (CMakeLists.txt); gl_backend.cpp knows whether it was.
#include "render/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace haif::render {

namespace {

std::string eglErrorText(const char* what) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", unsigned(eglGetError()));
  return std::string("EGL: ") + what + " failed (error " + hex + ")";
}

class EglContext final : public GlContext {
 public:
  ~EglContext() override {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }

  bool init(std::string* error) {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return fail(error, "EGL: eglGetPlatformDisplayEXT is missing (no EGL_EXT_platform_base)");
    display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY) return fail(error, "EGL: no surfaceless display (EGL_MESA_platform_surfaceless)");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) {
      display_ = EGL_NO_DISPLAY;
      return fail(error, eglErrorText("eglInitialize"));
    }
    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    for (const char* needed : {"EGL_KHR_surfaceless_context", "EGL_KHR_no_config_context"})
      if (!extensions || !std::strstr(extensions, needed))
        return fail(error, std::string("EGL: the display lacks ") + needed);
    if (!eglBindAPI(EGL_OPENGL_API)) return fail(error, eglErrorText("eglBindAPI(EGL_OPENGL_API)"));
    // 4.5 core first (what Mesa 22 gives), then the 3.3 minimum, as the OSMesa back end.
    const EGLint versions[][2] = {{4, 5}, {3, 3}};
    for (const auto& v : versions) {
      const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, v[0], EGL_CONTEXT_MINOR_VERSION, v[1],
                                EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
      context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
      if (context_ != EGL_NO_CONTEXT) break;
    }
    if (context_ == EGL_NO_CONTEXT) return fail(error, "EGL: could not create a core-profile OpenGL 3.3+ context");
    return makeCurrent(error);
  }

  bool makeCurrent(std::string* error) override {
    // No surface: the renderer draws only into its own framebuffer objects.
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return fail(error, eglErrorText("eglMakeCurrent"));
    return true;
  }

  GlProc getProcAddress(const char* name) const override { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); }

  const char* backendName() const override { return "EGL"; }

 private:
  static bool fail(std::string* error, const std::string& message) {
    if (error) *error = message;
    return false;
  }
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(std::string* error) {
  auto ctx = std::make_unique<EglContext>();
  if (!ctx->init(error)) return nullptr;
  return ctx;
}

}  // namespace haif::render
