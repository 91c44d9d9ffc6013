#include "render/shader_program.h"

#include <fstream>
#include <sstream>
#include <vector>

namespace haif::render {
namespace {

bool readFile(const std::string& path, std::string* text, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = "cannot read shader file '" + path + "'";
    return false;
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  *text = ss.str();
  return true;
}

std::string joinPath(const std::string& dir, const std::string& file) {
  if (dir.empty()) return file;
  return dir.back() == '/' ? dir + file : dir + "/" + file;
}

// Puts `defines` after the #version line (GLSL wants #version first).
void insertDefines(std::string* source, const std::string& defines) {
  if (defines.empty()) return;
  size_t at = 0;
  if (source->compare(0, 8, "#version") == 0) {
    const size_t eol = source->find('\n');
    at = eol == std::string::npos ? source->size() : eol + 1;
    if (eol == std::string::npos) source->push_back('\n'), ++at;
  }
  source->insert(at, defines + "#line " + std::to_string(at ? 2 : 1) + "\n");  // logs keep the file's line numbers
}

GLuint compile(const GlFunctions& gl, GLenum type, const std::string& path, const std::string& defines,
               std::string* error) {
  std::string source;
  if (!readFile(path, &source, error)) return 0;
  insertDefines(&source, defines);
  const GLuint shader = gl.CreateShader(type);
  const char* src = source.c_str();
  gl.ShaderSource(shader, 1, &src, nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint len = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(static_cast<size_t>(len > 1 ? len : 1), '\0');
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    if (error) *error = "GLSL compile error in '" + path + "':\n" + log.data();
    gl.DeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

ShaderProgram::~ShaderProgram() {
  if (program_) gl_->DeleteProgram(program_);
}

bool ShaderProgram::load(const GlFunctions& gl, const std::string& dir, const std::string& vertFile,
                         const std::string& fragFile, std::string* error, const std::string& defines) {
  gl_ = &gl;
  const std::string vertPath = joinPath(dir, vertFile), fragPath = joinPath(dir, fragFile);
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, vertPath, defines, error);
  if (!vs) return false;
  const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, fragPath, defines, error);
  if (!fs) {
    gl.DeleteShader(vs);
    return false;
  }
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  gl.LinkProgram(program);
  // Shaders are owned by the program once linked; flag them for deletion either way.
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint len = 0;
    gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(static_cast<size_t>(len > 1 ? len : 1), '\0');
    gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    if (error) *error = "GLSL link error for '" + vertPath + "' + '" + fragPath + "':\n" + log.data();
    gl.DeleteProgram(program);
    return false;
  }
  if (program_) gl.DeleteProgram(program_);
  program_ = program;
  return true;
}

}  // namespace haif::render
