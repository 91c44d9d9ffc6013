// An OpenGL context the renderer draws into. The renderer only ever renders into its own
// framebuffer objects, so a backend just has to make a core-profile context current and hand out
// function pointers. Two back ends: OSMesa (osmesa_context.cpp) and EGL surfaceless
// (egl_context.cpp); `--gl osmesa|egl|auto` picks one.
#pragma once

#include <memory>
#include <string>

namespace haif::render {

/// Generic function pointer returned by a backend's proc-address lookup.
using GlProc = void (*)();

class GlContext {
 public:
  virtual ~GlContext() = default;

  /// Makes the context current on the calling thread; false (and *error set) on failure.
  virtual bool makeCurrent(std::string* error) = 0;
  /// Address of a GL entry point by name (e.g. "glCreateShader"), or nullptr when unknown.
  virtual GlProc getProcAddress(const char* name) const = 0;
  /// Short backend name for messages, e.g. "OSMesa".
  virtual const char* backendName() const = 0;
};

/// Creates an OSMesa (llvmpipe) core-profile context of at least GL 3.3 and makes it current.
/// Returns nullptr and fills *error when OSMesa cannot give one. Defined only in builds that have
/// OSMesa: call createGlContext.
std::unique_ptr<GlContext> createOsMesaContext(std::string* error);
/// The same through EGL's surfaceless platform (no window system, no config); likewise only in
/// builds that have EGL.
std::unique_ptr<GlContext> createEglContext(std::string* error);

enum class GlBackend { Auto, OsMesa, Egl };
/// Whether this build has the back end (its package was found at configure time). Auto: always.
bool glBackendBuilt(GlBackend backend);
/// "auto", "osmesa" or "egl"; false for anything else.
bool parseGlBackend(const std::string& text, GlBackend& out);
/// Auto: OSMesa when it gives a context, else EGL (Mesa 25.1 and later ship no OSMesa).
std::unique_ptr<GlContext> createGlContext(GlBackend backend, std::string* error);
/// The back end a RendererOptions starts with: Auto unless a command's --gl set another.
GlBackend preferredGlBackend();
void setPreferredGlBackend(GlBackend backend);

}  // namespace haif::render
