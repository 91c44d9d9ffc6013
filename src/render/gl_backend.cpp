// Choosing the GL back end: --gl osmesa|egl|auto.
#include "render/gl_context.h"

#include <atomic>

namespace haif::render {

namespace {
std::atomic<GlBackend> preferred{GlBackend::Auto};
}  // namespace

bool glBackendBuilt(GlBackend backend) {
  switch (backend) {
#ifdef HAIF_HAVE_OSMESA
    case GlBackend::OsMesa: return true;
#else
    case GlBackend::OsMesa: return false;
#endif
#ifdef HAIF_HAVE_EGL
    case GlBackend::Egl: return true;
#else
    case GlBackend::Egl: return false;
#endif
    default: return true;
  }
}

bool parseGlBackend(const std::string& text, GlBackend& out) {
  if (text == "auto") out = GlBackend::Auto;
  else if (text == "osmesa") out = GlBackend::OsMesa;
  else if (text == "egl") out = GlBackend::Egl;
  else return false;
  return true;
}

namespace {

// The one back end asked for, or the reason this build cannot give it.
std::unique_ptr<GlContext> createBackend(GlBackend backend, std::string* error) {
#ifdef HAIF_HAVE_OSMESA
  if (backend == GlBackend::OsMesa) return createOsMesaContext(error);
#endif
#ifdef HAIF_HAVE_EGL
  if (backend == GlBackend::Egl) return createEglContext(error);
#endif
  if (error)
    *error = backend == GlBackend::OsMesa
                 ? "OSMesa: this build has no OSMesa back end (libosmesa6-dev was not found at configure time)"
                 : "EGL: this build has no EGL back end (libegl-dev was not found at configure time)";
  return nullptr;
}

}  // namespace

std::unique_ptr<GlContext> createGlContext(GlBackend backend, std::string* error) {
  if (backend != GlBackend::Auto) return createBackend(backend, error);
  std::string osmesaError;
  if (auto ctx = createBackend(GlBackend::OsMesa, &osmesaError)) return ctx;
  std::string eglError;
  if (auto ctx = createBackend(GlBackend::Egl, &eglError)) return ctx;
  if (error) *error = "no OpenGL context: " + osmesaError + "; " + eglError;
  return nullptr;
}

GlBackend preferredGlBackend() { return preferred.load(); }
void setPreferredGlBackend(GlBackend backend) { preferred.store(backend); }

}  // namespace haif::render
