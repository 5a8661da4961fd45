// The GL GlEngine: check the job, compile and link the pair, create the job's texture, uniform
// buffer and framebuffer, draw one full-screen triangle, read the target back. The EGL display
// and context (GlContext) live as long as the engine; every GL object lives for one render().
#include "crtforge/runtime/gl_engine.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <optional>
#include <vector>

#include <fmt/core.h>

#include "runtime/gl/gl_context.hpp"
#include "runtime/gl/gl_functions.hpp"
#include "runtime/gl/gl_objects.hpp"
#include "runtime/gl/gl_program.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/pixel_conversion.hpp"

// Desktop-only enum (ES has no switch for it: sRGB attachments always encode there).
#ifndef GL_FRAMEBUFFER_SRGB
#define GL_FRAMEBUFFER_SRGB 0x8DB9
#endif

namespace crtforge {
namespace gl {
namespace {

using vulkan::TextureTexels;
using detail::job_error;
using detail::output_format_name;

GLenum output_internal_format(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm: return GL_RGBA8;
        case OutputFormat::Rgba8Srgb: return GL_SRGB8_ALPHA8;
        case OutputFormat::Rgba16Float: return GL_RGBA16F;
    }
    return GL_RGBA8;
}

// The largest output extent along one axis: a texture, a render target and a viewport at once.
int max_output_extent(const GlContextFacts& facts, bool horizontal) {
    return std::min({facts.max_texture_size, facts.max_renderbuffer_size, facts.max_viewport[horizontal ? 0 : 1]});
}

// Everything that can be said about a job before the driver sees its shaders.
Status check_job(const GlContext& context, const GlRenderJob& job) {
    const GlContextFacts& facts = context.facts();
    if (job.vertex_source.empty()) return job_error("vertex shader source is empty", "vertex_source");
    if (job.fragment_source.empty()) return job_error("fragment shader source is empty", "fragment_source");
    const detail::JobLimits limits{max_output_extent(facts, true), max_output_extent(facts, false),
                                   facts.max_texture_size, facts.renderer, "GL_MAX_TEXTURE_SIZE"};
    if (auto s = detail::check_job_extent(job.width, job.height, job.input, limits); !s.ok()) return s;
    if (!job.uniform_data.empty()) {
        if (job.uniform_block.empty()) return job_error("uniform data is given but no uniform block is named", "uniform_block");
        if (job.uniform_data.size() > static_cast<size_t>(facts.max_uniform_block_size)) {
            return job_error(fmt::format("uniform data is {} bytes, over GL_MAX_UNIFORM_BLOCK_SIZE of {}",
                                         job.uniform_data.size(), facts.max_uniform_block_size),
                             "uniform_data");
        }
    }
    return Ok{};
}

// How the input is uploaded: RGBA32F, unless ES cannot filter it (OES_texture_float_linear).
struct TextureUpload {
    GLenum internal_format = GL_RGBA32F;
    GLenum type = GL_FLOAT;
    TextureTexels texels = TextureTexels::Rgba32Float;
};

TextureUpload choose_upload(const GlContext& context, SamplerFilter filter) {
    const bool float_filterable = !context.is_es() || context.facts().has_extension("GL_OES_texture_float_linear");
    if (filter == SamplerFilter::Linear && !float_filterable) {
        return {GL_RGBA16F, GL_HALF_FLOAT, TextureTexels::Rgba16Float};
    }
    return {};
}

UniqueTexture create_input_texture(const GlContext& context, const GlRenderJob& job) {
    const GlFunctions& gl = context.functions();
    const Image blank = Image::make(1, 1);  // for shaders that sample nothing
    const Image& input = job.input.empty() ? blank : job.input;
    const TextureUpload upload = choose_upload(context, job.filter);
    std::vector<unsigned char> texels(input.pixel_count() * vulkan::texel_bytes(upload.texels));
    vulkan::write_texels(input, upload.texels, texels.data());  // row 0 first: t = 0 is the top row

    UniqueTexture texture = make_texture(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, texture.get());
    gl.TexStorage2D(GL_TEXTURE_2D, 1, upload.internal_format, input.width, input.height);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, input.width, input.height, GL_RGBA, upload.type, texels.data());
    const GLint filter = job.filter == SamplerFilter::Linear ? GL_LINEAR : GL_NEAREST;
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return texture;
}

// Puts the shared bindings back to their defaults when a render() leaves, after the job's objects
// are gone, so the next job starts from a known state.
class DefaultBindings {
public:
    explicit DefaultBindings(const GlFunctions& gl) : gl_(gl) {}
    ~DefaultBindings() {
        gl_.UseProgram(0);
        gl_.BindVertexArray(0);
        gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl_.BindBufferBase(GL_UNIFORM_BUFFER, 0, 0);
        gl_.BindBuffer(GL_UNIFORM_BUFFER, 0);
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindTexture(GL_TEXTURE_2D, 0);
    }
    DefaultBindings(const DefaultBindings&) = delete;
    DefaultBindings& operator=(const DefaultBindings&) = delete;

private:
    const GlFunctions& gl_;
};

// Rows come back bottom-first from glReadPixels; the image wants the top row first.
Image to_image(const std::vector<unsigned char>& pixels, int width, int height, OutputFormat format) {
    const size_t row_bytes = static_cast<size_t>(width) * (format == OutputFormat::Rgba16Float ? 16 : 4);
    std::vector<unsigned char> top_first(pixels.size());
    for (int y = 0; y < height; ++y) {
        std::memcpy(top_first.data() + static_cast<size_t>(y) * row_bytes,
                    pixels.data() + static_cast<size_t>(height - 1 - y) * row_bytes, row_bytes);
    }
    if (format != OutputFormat::Rgba16Float) return vulkan::read_texels(top_first.data(), width, height, format);
    Image image = Image::make(width, height);  // read as GL_FLOAT: the driver widened the halves exactly
    std::memcpy(image.rgba.data(), top_first.data(), top_first.size());
    return image;
}

class GlEngineImpl final : public GlEngine {
public:
    explicit GlEngineImpl(std::unique_ptr<GlContext> context) : context_(std::move(context)) {}

    std::string renderer() const override {
        return fmt::format("{} | {}", context_->facts().renderer, context_->facts().version);
    }

    Result<Image> render(const GlRenderJob& job) override {
        try {
            auto scope = context_->make_current();
            if (!scope) return scope.error();
            take_gl_errors(context_->functions());  // errors from before this job are not its own
            if (auto s = check_job(*context_, job); !s) return s.error();
            const DefaultBindings defaults(context_->functions());  // outlives every job object below
            return run(job);
        } catch (const std::exception& e) {  // bad_alloc on a huge job: errors are values here
            return make_error(fmt::format("GL render failed: {}", e.what()));
        }
    }

private:
    Result<Image> run(const GlRenderJob& job) {
        const GlFunctions& gl = context_->functions();

        auto program = build_program(gl, job.vertex_source, job.fragment_source);
        if (!program) return program.error();
        auto bindings = bind_program_interface(gl, program.value().get(), job.uniform_block, job.sampler);
        if (!bindings) return bindings.error();
        // std140 rounds a block's GL_UNIFORM_BLOCK_DATA_SIZE up to 16 bytes, where SPIR-V
        // reflection (and so the Vulkan engine) ends it at its last member: data that covers every
        // member is accepted, and the tail padding is zero-filled.
        const std::optional<ProgramBindings::Block> block = bindings.value().uniform_block;
        if (block && job.uniform_data.size() < block->used_size) {
            return job_error(fmt::format("uniform data is {} bytes but the shader's block '{}' reads {} "
                                         "(GL_UNIFORM_BLOCK_DATA_SIZE {})",
                                         job.uniform_data.size(), job.uniform_block, block->used_size, block->data_size),
                             "uniform_data");
        }

        const UniqueTexture input = create_input_texture(*context_, job);

        UniqueBuffer uniforms;
        if (block) {
            std::vector<uint8_t> data = job.uniform_data;
            data.resize(std::max(data.size(), std::max<size_t>(block->data_size, 1)), 0);
            uniforms = make_buffer(gl);
            gl.BindBuffer(GL_UNIFORM_BUFFER, uniforms.get());
            gl.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(data.size()), data.data(), GL_STATIC_DRAW);
            gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, uniforms.get());
        }

        const UniqueTexture target = make_texture(gl);
        gl.BindTexture(GL_TEXTURE_2D, target.get());
        gl.TexStorage2D(GL_TEXTURE_2D, 1, output_internal_format(job.format), job.width, job.height);
        gl.BindTexture(GL_TEXTURE_2D, input.get());  // unit 0 samples the input again

        const UniqueFramebuffer framebuffer = make_framebuffer(gl);
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.get(), 0);
        const GLenum draw_buffer = GL_COLOR_ATTACHMENT0;
        gl.DrawBuffers(1, &draw_buffer);
        gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
        if (const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER); status != GL_FRAMEBUFFER_COMPLETE) {
            return job_error(fmt::format("output format {} cannot be rendered to on '{}' (framebuffer status 0x{:04X})",
                                         output_format_name(job.format), renderer(), status),
                             "format");
        }
        if (auto errors = take_gl_errors(gl); !errors.empty()) {
            return make_validation_error(fmt::format("GL error while setting up the render: {}", gl_error_name(errors.front())));
        }

        const UniqueVertexArray vertex_array = make_vertex_array(gl);  // core profile draws need one, even empty
        gl.BindVertexArray(vertex_array.get());
        gl.Disable(GL_DITHER);  // on by default; an 8-bit target must get the shader's value, rounded
        gl.Disable(GL_BLEND);
        gl.Disable(GL_DEPTH_TEST);
        gl.Disable(GL_SCISSOR_TEST);
        gl.Disable(GL_CULL_FACE);
        const bool srgb_switch = !context_->is_es() && job.format == OutputFormat::Rgba8Srgb;
        if (srgb_switch) gl.Enable(GL_FRAMEBUFFER_SRGB);  // desktop GL encodes on store only when asked
        gl.Viewport(0, 0, job.width, job.height);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        if (srgb_switch) gl.Disable(GL_FRAMEBUFFER_SRGB);  // and never decode on read

        const bool floats = job.format == OutputFormat::Rgba16Float;
        std::vector<unsigned char> pixels(static_cast<size_t>(job.width) * static_cast<size_t>(job.height) *
                                          (floats ? 16 : 4));
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadPixels(0, 0, job.width, job.height, GL_RGBA, floats ? GL_FLOAT : GL_UNSIGNED_BYTE, pixels.data());
        if (auto errors = take_gl_errors(gl); !errors.empty()) {
            return make_validation_error(fmt::format("GL error during the render: {}{}", gl_error_name(errors.front()),
                                                     errors.size() > 1 ? fmt::format(" (and {} more)", errors.size() - 1)
                                                                       : std::string()));
        }
        return to_image(pixels, job.width, job.height, job.format);
    }

    std::unique_ptr<GlContext> context_;
};

}  // namespace
}  // namespace gl

Result<std::unique_ptr<GlEngine>> create_gl_engine(GlApi api) {
    try {
        auto context = gl::GlContext::create(api);
        if (!context) return context.error();
        return std::unique_ptr<GlEngine>(std::make_unique<gl::GlEngineImpl>(std::move(context).value()));
    } catch (const std::exception& e) {
        return make_error(fmt::format("creating the GL engine failed: {}", e.what()));
    }
}

}  // namespace crtforge
