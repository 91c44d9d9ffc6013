// A GLSL program built from a vertex and a fragment shader file read at run time. Every failure
// (missing file, compile or link error) comes back as a message naming the file and the GLSL log.
#pragma once

#include <string>

#include "render/gl_functions.h"

namespace haif::render {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  /// Reads dir/vertFile and dir/fragFile, compiles and links them. `defines` (e.g. "#define X 1\n")
  /// goes right after each file's #version line, so one file can yield specialised variants.
  /// On failure returns false, leaves no GL objects behind and sets *error.
  bool load(const GlFunctions& gl, const std::string& dir, const std::string& vertFile,
            const std::string& fragFile, std::string* error, const std::string& defines = "");

  /// Binds the program.
  void use() const { gl_->UseProgram(program_); }
  /// Location of a uniform (-1 when the compiler removed or never had it; GL ignores -1).
  GLint uniform(const char* name) const { return gl_->GetUniformLocation(program_, name); }

 private:
  const GlFunctions* gl_ = nullptr;
  GLuint program_ = 0;
};

}  // namespace haif::render
