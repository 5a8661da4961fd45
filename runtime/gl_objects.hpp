// Move-only owners for the GL objects of one job, so every object is deleted on every path out of
// render() — early error returns included. They must be destroyed while the engine's context is
// current (the engine keeps its current-context scope alive longer than any job object).
#pragma once

#include <utility>

#include "gl_functions.hpp"

namespace crtforge::gl {

enum class ObjectKind { Shader, Program, Buffer, Texture, Framebuffer, VertexArray };

template <ObjectKind Kind>
class GlObject {
public:
    GlObject() = default;
    GlObject(const GlFunctions& gl, GLuint name) : gl_(&gl), name_(name) {}
    ~GlObject() { reset(); }

    GlObject(GlObject&& other) noexcept : gl_(other.gl_), name_(std::exchange(other.name_, 0u)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            gl_ = other.gl_;
            name_ = std::exchange(other.name_, 0u);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }

    void reset() {
        if (name_ == 0) return;
        if constexpr (Kind == ObjectKind::Shader) gl_->DeleteShader(name_);
        if constexpr (Kind == ObjectKind::Program) gl_->DeleteProgram(name_);
        if constexpr (Kind == ObjectKind::Buffer) gl_->DeleteBuffers(1, &name_);
        if constexpr (Kind == ObjectKind::Texture) gl_->DeleteTextures(1, &name_);
        if constexpr (Kind == ObjectKind::Framebuffer) gl_->DeleteFramebuffers(1, &name_);
        if constexpr (Kind == ObjectKind::VertexArray) gl_->DeleteVertexArrays(1, &name_);
        name_ = 0;
    }

private:
    const GlFunctions* gl_ = nullptr;
    GLuint name_ = 0;
};

using UniqueShader = GlObject<ObjectKind::Shader>;
using UniqueProgram = GlObject<ObjectKind::Program>;
using UniqueBuffer = GlObject<ObjectKind::Buffer>;
using UniqueTexture = GlObject<ObjectKind::Texture>;
using UniqueFramebuffer = GlObject<ObjectKind::Framebuffer>;
using UniqueVertexArray = GlObject<ObjectKind::VertexArray>;

// glGen* one name and own it.
inline UniqueBuffer make_buffer(const GlFunctions& gl) {
    GLuint name = 0;
    gl.GenBuffers(1, &name);
    return UniqueBuffer(gl, name);
}
inline UniqueTexture make_texture(const GlFunctions& gl) {
    GLuint name = 0;
    gl.GenTextures(1, &name);
    return UniqueTexture(gl, name);
}
inline UniqueFramebuffer make_framebuffer(const GlFunctions& gl) {
    GLuint name = 0;
    gl.GenFramebuffers(1, &name);
    return UniqueFramebuffer(gl, name);
}
inline UniqueVertexArray make_vertex_array(const GlFunctions& gl) {
    GLuint name = 0;
    gl.GenVertexArrays(1, &name);
    return UniqueVertexArray(gl, name);
}

}  // namespace crtforge::gl
