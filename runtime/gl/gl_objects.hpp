// Move-only owners for the GL objects of one job, so every object is deleted on every path out of
// render() — early error returns included. They must be destroyed while the engine's context is
// current (the engine keeps its current-context scope alive longer than any job object).
#pragma once

#include <utility>

#include "runtime/gl/gl_functions.hpp"

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
template <ObjectKind Kind>
GlObject<Kind> generate(const GlFunctions& gl) {
    GLuint name = 0;
    if constexpr (Kind == ObjectKind::Buffer) gl.GenBuffers(1, &name);
    if constexpr (Kind == ObjectKind::Texture) gl.GenTextures(1, &name);
    if constexpr (Kind == ObjectKind::Framebuffer) gl.GenFramebuffers(1, &name);
    if constexpr (Kind == ObjectKind::VertexArray) gl.GenVertexArrays(1, &name);
    return GlObject<Kind>(gl, name);
}
inline UniqueBuffer make_buffer(const GlFunctions& gl) { return generate<ObjectKind::Buffer>(gl); }
inline UniqueTexture make_texture(const GlFunctions& gl) { return generate<ObjectKind::Texture>(gl); }
inline UniqueFramebuffer make_framebuffer(const GlFunctions& gl) { return generate<ObjectKind::Framebuffer>(gl); }
inline UniqueVertexArray make_vertex_array(const GlFunctions& gl) { return generate<ObjectKind::VertexArray>(gl); }

}  // namespace crtforge::gl
