#include "runtime/gl/gl_functions.hpp"

#include <algorithm>

#include <EGL/egl.h>
#include <fmt/core.h>

namespace crtforge::gl {

Result<GlFunctions> GlFunctions::load() {
    GlFunctions gl;
    std::vector<std::string> missing;
#define CRTFORGE_GL_LOAD(type, member, name)                                   \
    gl.member = reinterpret_cast<type>(eglGetProcAddress(name));               \
    if (gl.member == nullptr) missing.emplace_back(name);
    CRTFORGE_GL_FUNCTIONS(CRTFORGE_GL_LOAD)
#undef CRTFORGE_GL_LOAD
    if (!missing.empty()) {
        return make_error(fmt::format("the GL driver does not provide {} (and {} more entry points)", missing.front(),
                                      missing.size() - 1));
    }
    return gl;
}

bool GlContextFacts::has_extension(const std::string& name) const {
    return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
}

namespace {

std::string gl_string(const GLubyte* text) { return text ? reinterpret_cast<const char*>(text) : ""; }

}  // namespace

GlContextFacts query_context_facts(const GlFunctions& gl) {
    GlContextFacts facts;
    facts.renderer = gl_string(gl.GetString(GL_RENDERER));
    facts.version = gl_string(gl.GetString(GL_VERSION));
    GLint count = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) facts.extensions.push_back(gl_string(gl.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i))));
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &facts.max_texture_size);
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &facts.max_renderbuffer_size);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, facts.max_viewport);
    gl.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &facts.max_uniform_block_size);
    gl.GetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &facts.max_texture_units);
    return facts;
}

std::string gl_error_name(GLenum error) {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
        default: return fmt::format("GL error 0x{:04X}", error);
    }
}

std::vector<GLenum> take_gl_errors(const GlFunctions& gl) {
    std::vector<GLenum> errors;
    // Bounded: a lost context may report GL_CONTEXT_LOST forever.
    for (int i = 0; i < 32; ++i) {
        const GLenum error = gl.GetError();
        if (error == GL_NO_ERROR) break;
        errors.push_back(error);
    }
    return errors;
}

}  // namespace crtforge::gl
