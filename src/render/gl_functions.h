// The GL entry points the renderer uses, loaded through GlContext::getProcAddress so that nothing
// links against a particular libGL. Types and enums come from Khronos' glcorearb.h.
#pragma once

#include <GL/glcorearb.h>

#include <string>

namespace haif::render {

class GlContext;

// X(type, member, "glName"): one line per function, so adding one is a one-line change.
#define HAIF_GL_FUNCTIONS(X)                                                        \
  X(PFNGLGETERRORPROC, GetError, "glGetError")                                      \
  X(PFNGLGETSTRINGPROC, GetString, "glGetString")                                   \
  X(PFNGLGETSTRINGIPROC, GetStringi, "glGetStringi")                                \
  X(PFNGLGETINTEGERVPROC, GetIntegerv, "glGetIntegerv")                             \
  X(PFNGLGETMULTISAMPLEFVPROC, GetMultisamplefv, "glGetMultisamplefv")              \
  X(PFNGLENABLEPROC, Enable, "glEnable")                                            \
  X(PFNGLDISABLEPROC, Disable, "glDisable")                                         \
  X(PFNGLVIEWPORTPROC, Viewport, "glViewport")                                      \
  X(PFNGLSCISSORPROC, Scissor, "glScissor")                                         \
  X(PFNGLCLEARPROC, Clear, "glClear")                                               \
  X(PFNGLCLEARCOLORPROC, ClearColor, "glClearColor")                                \
  X(PFNGLCLEARDEPTHPROC, ClearDepth, "glClearDepth")                                \
  X(PFNGLDEPTHFUNCPROC, DepthFunc, "glDepthFunc")                                   \
  X(PFNGLDEPTHMASKPROC, DepthMask, "glDepthMask")                                   \
  X(PFNGLCOLORMASKPROC, ColorMask, "glColorMask")                                   \
  X(PFNGLCULLFACEPROC, CullFace, "glCullFace")                                      \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset, "glPolygonOffset")                       \
  X(PFNGLBLENDFUNCPROC, BlendFunc, "glBlendFunc")                                   \
  X(PFNGLREADPIXELSPROC, ReadPixels, "glReadPixels")                                \
  X(PFNGLPIXELSTOREIPROC, PixelStorei, "glPixelStorei")                             \
  X(PFNGLFINISHPROC, Finish, "glFinish")                                            \
  X(PFNGLFLUSHPROC, Flush, "glFlush")                                              \
  X(PFNGLGENBUFFERSPROC, GenBuffers, "glGenBuffers")                                \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers, "glDeleteBuffers")                       \
  X(PFNGLBINDBUFFERPROC, BindBuffer, "glBindBuffer")                                \
  X(PFNGLBUFFERDATAPROC, BufferData, "glBufferData")                                \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData, "glBufferSubData")                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays, "glGenVertexArrays")                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays, "glDeleteVertexArrays")        \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray, "glBindVertexArray")                 \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray,                      \
    "glEnableVertexAttribArray")                                                    \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer, "glVertexAttribPointer")     \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor, "glVertexAttribDivisor")     \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced, "glDrawElementsInstanced") \
  X(PFNGLDRAWARRAYSPROC, DrawArrays, "glDrawArrays")                                \
  X(PFNGLDRAWELEMENTSPROC, DrawElements, "glDrawElements")                          \
  X(PFNGLCREATESHADERPROC, CreateShader, "glCreateShader")                          \
  X(PFNGLSHADERSOURCEPROC, ShaderSource, "glShaderSource")                          \
  X(PFNGLCOMPILESHADERPROC, CompileShader, "glCompileShader")                       \
  X(PFNGLGETSHADERIVPROC, GetShaderiv, "glGetShaderiv")                             \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog, "glGetShaderInfoLog")              \
  X(PFNGLDELETESHADERPROC, DeleteShader, "glDeleteShader")                          \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram, "glCreateProgram")                       \
  X(PFNGLATTACHSHADERPROC, AttachShader, "glAttachShader")                          \
  X(PFNGLLINKPROGRAMPROC, LinkProgram, "glLinkProgram")                             \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv, "glGetProgramiv")                          \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog, "glGetProgramInfoLog")           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram, "glDeleteProgram")                       \
  X(PFNGLUSEPROGRAMPROC, UseProgram, "glUseProgram")                                \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation, "glGetUniformLocation")        \
  X(PFNGLUNIFORM1IPROC, Uniform1i, "glUniform1i")                                   \
  X(PFNGLUNIFORM1FPROC, Uniform1f, "glUniform1f")                                   \
  X(PFNGLUNIFORM2FPROC, Uniform2f, "glUniform2f")                                   \
  X(PFNGLUNIFORM3FPROC, Uniform3f, "glUniform3f")                                   \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv, "glUniformMatrix4fv")              \
  X(PFNGLGENTEXTURESPROC, GenTextures, "glGenTextures")                             \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures, "glDeleteTextures")                    \
  X(PFNGLBINDTEXTUREPROC, BindTexture, "glBindTexture")                             \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture, "glActiveTexture")                       \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D, "glTexImage2D")                                \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri, "glTexParameteri")                       \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv, "glTexParameterfv")                    \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers, "glGenFramebuffers")                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers, "glDeleteFramebuffers")        \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer, "glBindFramebuffer")                 \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D, "glFramebufferTexture2D")  \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer,                      \
    "glFramebufferRenderbuffer")                                                    \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus,                        \
    "glCheckFramebufferStatus")                                                     \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers, "glGenRenderbuffers")              \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers, "glDeleteRenderbuffers")     \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer, "glBindRenderbuffer")              \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage, "glRenderbufferStorage")     \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample,        \
    "glRenderbufferStorageMultisample")                                             \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer, "glBlitFramebuffer")                 \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer, "glDrawBuffer")                                \
  X(PFNGLREADBUFFERPROC, ReadBuffer, "glReadBuffer")

/// Table of GL function pointers; members are the GL names without the "gl" prefix.
struct GlFunctions {
#define HAIF_GL_MEMBER(type, member, name) type member = nullptr;
  HAIF_GL_FUNCTIONS(HAIF_GL_MEMBER)
#undef HAIF_GL_MEMBER

  /// Fills every pointer from the context; false (and *error naming the missing function) if any is absent.
  bool load(const GlContext& context, std::string* error);
};

}  // namespace haif::render
