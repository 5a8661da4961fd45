// The GL entry points the engine calls, loaded with eglGetProcAddress into a plain table (no
// GLEW/glad). Every entry is core in both OpenGL 4.5 and OpenGL ES 3.0, so one table serves both
// APIs; the enum values used are the same in <GL/glcorearb.h> and <GLES3/gl3.h>.
#pragma once

#include <string>
#include <vector>

#include <GL/glcorearb.h>

#include "crtforge/diagnostic.hpp"

namespace crtforge::gl {

// X(type, member, "glName") for every entry point in the table.
#define CRTFORGE_GL_FUNCTIONS(X)                                                   \
    X(PFNGLGETSTRINGPROC, GetString, "glGetString")                                \
    X(PFNGLGETSTRINGIPROC, GetStringi, "glGetStringi")                             \
    X(PFNGLGETINTEGERVPROC, GetIntegerv, "glGetIntegerv")                          \
    X(PFNGLGETERRORPROC, GetError, "glGetError")                                   \
    X(PFNGLENABLEPROC, Enable, "glEnable")                                         \
    X(PFNGLDISABLEPROC, Disable, "glDisable")                                      \
    X(PFNGLPIXELSTOREIPROC, PixelStorei, "glPixelStorei")                          \
    X(PFNGLVIEWPORTPROC, Viewport, "glViewport")                                   \
    X(PFNGLDRAWARRAYSPROC, DrawArrays, "glDrawArrays")                             \
    X(PFNGLREADPIXELSPROC, ReadPixels, "glReadPixels")                             \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv, "glClearBufferfv")                    \
    X(PFNGLCREATESHADERPROC, CreateShader, "glCreateShader")                       \
    X(PFNGLSHADERSOURCEPROC, ShaderSource, "glShaderSource")                       \
    X(PFNGLCOMPILESHADERPROC, CompileShader, "glCompileShader")                    \
    X(PFNGLGETSHADERIVPROC, GetShaderiv, "glGetShaderiv")                          \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog, "glGetShaderInfoLog")           \
    X(PFNGLDELETESHADERPROC, DeleteShader, "glDeleteShader")                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram, "glCreateProgram")                    \
    X(PFNGLATTACHSHADERPROC, AttachShader, "glAttachShader")                       \
    X(PFNGLLINKPROGRAMPROC, LinkProgram, "glLinkProgram")                          \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv, "glGetProgramiv")                       \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog, "glGetProgramInfoLog")        \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram, "glDeleteProgram")                    \
    X(PFNGLUSEPROGRAMPROC, UseProgram, "glUseProgram")                             \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex, "glGetUniformBlockIndex") \
    X(PFNGLGETACTIVEUNIFORMBLOCKIVPROC, GetActiveUniformBlockiv, "glGetActiveUniformBlockiv") \
    X(PFNGLGETACTIVEUNIFORMBLOCKNAMEPROC, GetActiveUniformBlockName, "glGetActiveUniformBlockName") \
    X(PFNGLGETACTIVEUNIFORMSIVPROC, GetActiveUniformsiv, "glGetActiveUniformsiv")  \
    X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding, "glUniformBlockBinding")  \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation, "glGetUniformLocation")     \
    X(PFNGLUNIFORM1IPROC, Uniform1i, "glUniform1i")                                \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv, "glUniform1fv")                             \
    X(PFNGLUNIFORM2FVPROC, Uniform2fv, "glUniform2fv")                             \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv, "glUniform3fv")                             \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv, "glUniform4fv")                             \
    X(PFNGLUNIFORM1IVPROC, Uniform1iv, "glUniform1iv")                             \
    X(PFNGLUNIFORM2IVPROC, Uniform2iv, "glUniform2iv")                             \
    X(PFNGLUNIFORM3IVPROC, Uniform3iv, "glUniform3iv")                             \
    X(PFNGLUNIFORM4IVPROC, Uniform4iv, "glUniform4iv")                             \
    X(PFNGLUNIFORM1UIVPROC, Uniform1uiv, "glUniform1uiv")                          \
    X(PFNGLGETACTIVEUNIFORMPROC, GetActiveUniform, "glGetActiveUniform")           \
    X(PFNGLGENBUFFERSPROC, GenBuffers, "glGenBuffers")                             \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers, "glDeleteBuffers")                    \
    X(PFNGLBINDBUFFERPROC, BindBuffer, "glBindBuffer")                             \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase, "glBindBufferBase")                 \
    X(PFNGLBUFFERDATAPROC, BufferData, "glBufferData")                             \
    X(PFNGLGENTEXTURESPROC, GenTextures, "glGenTextures")                          \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures, "glDeleteTextures")                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture, "glBindTexture")                          \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture, "glActiveTexture")                    \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D, "glTexStorage2D")                       \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap, "glGenerateMipmap")                 \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D, "glTexSubImage2D")                    \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri, "glTexParameteri")                    \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers, "glGenFramebuffers")              \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers, "glDeleteFramebuffers")     \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer, "glBindFramebuffer")              \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D, "glFramebufferTexture2D") \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus, "glCheckFramebufferStatus") \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers, "glDrawBuffers")                          \
    X(PFNGLREADBUFFERPROC, ReadBuffer, "glReadBuffer")                             \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays, "glGenVertexArrays")              \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays, "glDeleteVertexArrays")     \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray, "glBindVertexArray")

struct GlFunctions {
#define CRTFORGE_GL_MEMBER(type, member, name) type member = nullptr;
    CRTFORGE_GL_FUNCTIONS(CRTFORGE_GL_MEMBER)
#undef CRTFORGE_GL_MEMBER

    // Fills the table through eglGetProcAddress. Needs the engine's context current (some drivers
    // only resolve entry points for the current API); a missing entry point is an error naming it.
    static Result<GlFunctions> load();
};

// What the current context reports about itself.
struct GlContextFacts {
    std::string renderer, version;       // GL_RENDERER, GL_VERSION
    std::vector<std::string> extensions; // GL_EXTENSIONS, one by one (glGetStringi)
    int max_texture_size = 0;            // GL_MAX_TEXTURE_SIZE
    int max_renderbuffer_size = 0;       // GL_MAX_RENDERBUFFER_SIZE
    int max_viewport[2] = {0, 0};        // GL_MAX_VIEWPORT_DIMS
    int max_uniform_block_size = 0;      // GL_MAX_UNIFORM_BLOCK_SIZE
    int max_texture_units = 0;           // GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS

    bool has_extension(const std::string& name) const;
};

GlContextFacts query_context_facts(const GlFunctions& gl);

// "GL_INVALID_OPERATION" and friends; unknown codes as hex.
std::string gl_error_name(GLenum error);

// Returns (and clears) every pending glGetError code; empty when the context is clean.
std::vector<GLenum> take_gl_errors(const GlFunctions& gl);

}  // namespace crtforge::gl
