#include "render/gl_functions.h"

#include "render/gl_context.h"

namespace haif::render {

bool GlFunctions::load(const GlContext& context, std::string* error) {
  // A missing entry point is reported by name instead of crashing at the first call.
#define HAIF_GL_LOAD(type, member, name)                                          \
  member = reinterpret_cast<type>(context.getProcAddress(name));                  \
  if (!member) {                                                                  \
    if (error) *error = std::string(context.backendName()) + ": missing GL function " + name; \
    return false;                                                                 \
  }
  HAIF_GL_FUNCTIONS(HAIF_GL_LOAD)
#undef HAIF_GL_LOAD
  return true;
}

}  // namespace haif::render
