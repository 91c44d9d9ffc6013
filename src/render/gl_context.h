// An OpenGL context the renderer draws into. The renderer only ever renders into its own
// framebuffer objects, so a backend just has to make a core-profile context current and hand out
// function pointers. OSMesa is the one backend today; an EGL-surfaceless one can be added beside it.
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
/// Returns nullptr and fills *error when OSMesa cannot give one.
std::unique_ptr<GlContext> createOsMesaContext(std::string* error);

}  // namespace haif::render
