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

std::unique_ptr<GlContext> createGlContext(GlBackend backend, std::string* error) {
  if (backend == GlBackend::OsMesa) return createOsMesaContext(error);
  if (backend == GlBackend::Egl) return createEglContext(error);
  std::string osmesaError;
  if (auto ctx = createOsMesaContext(&osmesaError)) return ctx;
  std::string eglError;
  if (auto ctx = createEglContext(&eglError)) return ctx;
  if (error) *error = "no OpenGL context: " + osmesaError + "; " + eglError;
  return nullptr;
}

GlBackend preferredGlBackend() { return preferred.load(); }
void setPreferredGlBackend(GlBackend backend) { preferred.store(backend); }

}  // namespace haif::render
