// The OpenGL / OpenGL ES render engine: the GLSL targets proven by the real GL driver compiler.
// It runs one full-screen pass of a GLSL vertex + fragment pair (as SPIRV-Cross emits them) over
// an input image and reads the result back as floats, exactly like the Vulkan RenderEngine does for
// SPIR-V. The driver is reached through EGL on Mesa's surfaceless platform (no window, no X server,
// no EGL_PLATFORM in the environment needed); Mesa llvmpipe serves it with no GPU.
//
// Lifecycle:
//   1. create  — create_gl_engine() opens the surfaceless EGL display and one context of the
//                requested API; it fails with a one-line Diagnostic (no EGL / GL driver, API or
//                version not available).
//   2. render  — render(job) any number of times, one job at a time (not thread-safe: use one
//                engine per thread). The context is made current on the calling thread for the
//                call and the caller's previous current context is restored afterwards. Every GL
//                object a job needs is created for that call and deleted before it returns.
//   3. destroy — the destructor deletes the context (and the display with the last engine).
// No exception escapes any of these calls; every failure is a Result error.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge {

enum class GlApi {
    DesktopCore,  // OpenGL 4.5 core profile: serves "#version 450" and "#version 330" sources
    Es,           // OpenGL ES 3.x: serves "#version 300 es" sources
};

// One full-screen pass. Conventions shared with the GLSL targets:
//  - the vertex shader draws a full-screen triangle from gl_VertexID (glDrawArrays(3) with an
//    empty vertex array object) and writes vTexCoord; it flips y itself (gl_Position.y =
//    -gl_Position.y), so texture coordinate (0, 0) is the top-left of `input` and of the picture;
//  - output row 0 is the top row (the same orientation the Vulkan engine returns);
//  - bindings written in the source (layout(binding = N)) are not relied on: the engine binds the
//    uniform block by name to uniform buffer binding 0, the input's sampler by name (`sampler`) to
//    texture unit 0 and each of `textures` by its `name` to units 1, 2, ... in order;
//  - the target is cleared to clear_color and the triangle drawn only inside `viewport` (rows
//    counted from the top, as in render_engine.hpp); gl_FragCoord stays in target pixels with
//    GL's bottom-left origin, so coordinates come from vTexCoord.
// A top-level uniform set by name (glUniform*), as WebGL 2 frameworks set them: `components`
// values of `kind`, read from `values` (floats) or `ints` (int and uint, bool as int).
struct PlainUniform {
    enum class Kind { Float, Int, Uint } kind = Kind::Float;
    std::string name;
    int components = 1;  // 1..4
    std::array<float, 4> values{};
    std::array<int32_t, 4> ints{};
};

struct GlRenderJob {
    // Complete GLSL, #version line included.
    std::string vertex_source, fragment_source;
    // Uploaded as an RGBA32F texture (RGBA16F on ES when float32 linear filtering is unavailable
    // and `filter` is Linear), addressed by `wrap` (clamp-to-edge by default). An empty image
    // binds a 1x1 transparent-black texture, for shaders that sample nothing. Shared, as `textures`
    // are: a scene's pass output reaches the next pass without a copy.
    SharedImage input;
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    bool mipmap = false;  // a mip chain, as RenderJob::mipmap (glGenerateMipmap)
    SamplerFilter mip_filter = SamplerFilter::Linear;
    bool unorm8 = false;  // as RenderJob::unorm8: a chain of an 8-bit picture is RGBA8
    // More textures, uploaded like `input` with their own filter and wrap, each bound by its
    // `name` (non-empty, unique, not `sampler`) to texture unit 1 + its index; `binding` and
    // `sampler_binding` are not used here. A name the shader does not use is skipped.
    std::vector<TextureInput> textures;
    int width = 0, height = 0;  // output size in pixels
    Viewport viewport;          // where inside width x height the pass draws; default: everywhere
    std::array<float, 4> clear_color = {0, 0, 0, 0};  // linear RGBA the whole target starts as
    // Rgba8Unorm and Rgba16Float always work; Rgba8Srgb is an error where the context cannot
    // render to it. Readback follows render_engine.hpp: bytes / 255, sRGB decoded, halves exact.
    OutputFormat format = OutputFormat::Rgba8Unorm;
    // The std140 bytes of the uniform block named `uniform_block`. Empty = the shader has no
    // active uniform block. It must cover every active member of the block (up to the end of the
    // last one, as SPIR-V reflection sizes it); the tail padding std140 adds to the block's
    // GL_UNIFORM_BLOCK_DATA_SIZE is zero-filled by the engine.
    std::vector<uint8_t> uniform_data;
    std::string uniform_block = "CrtParams";
    // Uniforms outside any block, set by name after linking. Every active plain uniform of the
    // program (samplers aside) must be here; one the program lacks (the compiler may drop an
    // unused one) is skipped.
    std::vector<PlainUniform> plain_uniforms;
    // The sampler2D uniform bound to texture unit 0 (it may be absent from the shader).
    std::string sampler = "source";
};

class GlEngine {
public:
    virtual ~GlEngine() = default;
    // GL_RENDERER and GL_VERSION of the context, e.g.
    // "llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6".
    virtual std::string renderer() const = 0;
    // Renders `job` and returns the output image (job.width x job.height, linear floats).
    // A shader the driver does not compile or link is an ErrorKind::Validation error whose message
    // starts "GL driver rejected the vertex shader: " / "... fragment shader: " (or "... the
    // program at link: ") followed by the first line of the driver's log. A bad job (zero or
    // oversized output, empty source, too-short uniform data, a uniform block the job does not
    // provide, a texture with no name or a name another sampler has, a malformed or oversized
    // texture, a viewport outside the target, a non-finite clear colour) is an ErrorKind::Input
    // error with field "job.<name>"; a GL error raised by the pass is reported too.
    virtual Result<Image> render(const GlRenderJob& job) = 0;
};

Result<std::unique_ptr<GlEngine>> create_gl_engine(GlApi api);

}  // namespace crtforge
