// The GL GlEngine: check the job, compile and link the pair, create the job's textures, uniform
// buffer and framebuffer, clear, draw one full-screen triangle, read the target back. The EGL
// display and context (GlContext) live as long as the engine; every GL object lives for one
// render().
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
        case OutputFormat::Rgba32Float: return GL_RGBA32F;
        case OutputFormat::Rgb10A2Unorm: return GL_RGB10_A2;
        case OutputFormat::R16Float: return GL_R16F;
        case OutputFormat::Rg16Float: return GL_RG16F;
    }
    return GL_RGBA8;
}

// How a target of `format` is read back (the combinations GL ES 3.0 allows as well as desktop GL):
// glReadPixels' type, and the layout of what comes back. Float targets come as RGBA floats (the
// driver widens halves exactly and fills a channel the format lacks with 0, alpha with 1), 10-bit
// ones packed, 8-bit ones as bytes.
struct GlReadback {
    GLenum type;
    OutputFormat layout;
};
GlReadback readback_of(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm:
        case OutputFormat::Rgba8Srgb: return {GL_UNSIGNED_BYTE, format};
        case OutputFormat::Rgb10A2Unorm: return {GL_UNSIGNED_INT_2_10_10_10_REV, format};
        case OutputFormat::Rgba16Float:
        case OutputFormat::Rgba32Float:
        case OutputFormat::R16Float:
        case OutputFormat::Rg16Float: break;
    }
    return {GL_FLOAT, OutputFormat::Rgba32Float};
}

// The largest output extent along one axis: a texture, a render target and a viewport at once.
int max_output_extent(const GlContextFacts& facts, bool horizontal) {
    return std::min({facts.max_texture_size, facts.max_renderbuffer_size, facts.max_viewport[horizontal ? 0 : 1]});
}

// Extra textures are bound by name to units 1, 2, ...: each needs a name no other sampler of the
// job has (two at one name would be two textures at one binding) and a unit the context has.
Status check_textures(const GlRenderJob& job, const detail::JobLimits& limits, const GlContextFacts& facts) {
    if (auto s = detail::check_texture_images(job.textures, limits); !s.ok()) return s;
    if (job.textures.size() + 1 > static_cast<size_t>(std::max(facts.max_texture_units, 1))) {
        return job_error(fmt::format("the job binds {} textures, over GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS of {}",
                                     job.textures.size() + 1, facts.max_texture_units),
                         "textures");
    }
    for (size_t i = 0; i < job.textures.size(); ++i) {
        const std::string& name = job.textures[i].name;
        const std::string field = detail::texture_field(i, "name");
        if (name.empty())
            return job_error(fmt::format("texture {} has no sampler name (the engine binds by name)", i), field);
        if (name == job.sampler)
            return job_error(fmt::format("texture {} is named '{}', the name of the input's sampler", i, name), field);
        for (size_t j = 0; j < i; ++j) {
            if (job.textures[j].name == name)
                return job_error(fmt::format("textures {} and {} are both named '{}'", j, i, name), field);
        }
    }
    return Ok{};
}

// Everything that can be said about a job before the driver sees its shaders.
Status check_job(const GlContext& context, const GlRenderJob& job) {
    const GlContextFacts& facts = context.facts();
    if (job.vertex_source.empty()) return job_error("vertex shader source is empty", "vertex_source");
    if (job.fragment_source.empty()) return job_error("fragment shader source is empty", "fragment_source");
    const detail::JobLimits limits{max_output_extent(facts, true), max_output_extent(facts, false),
                                   facts.max_texture_size, facts.renderer, "GL_MAX_TEXTURE_SIZE"};
    if (auto s = detail::check_job_extent(job.width, job.height, *job.input, limits); !s.ok()) return s;
    if (auto s = check_textures(job, limits, facts); !s.ok()) return s;
    if (auto s = detail::check_viewport(job.viewport, job.width, job.height); !s.ok()) return s;
    if (auto s = detail::check_clear_color(job.clear_color); !s.ok()) return s;
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

// How a texture is uploaded: RGBA32F, unless ES cannot filter it (OES_texture_float_linear) or
// make its mip chain (ES renders only half floats): RGBA16F there. The chain of an 8-bit picture
// (`unorm8`) is RGBA8, as RetroArch's of its RGBA8 framebuffers and LUTs.
struct TextureUpload {
    GLenum internal_format = GL_RGBA32F;
    GLenum type = GL_FLOAT;
    TextureTexels texels = TextureTexels::Rgba32Float;
};

TextureUpload choose_upload(const GlContext& context, SamplerFilter filter, bool mipmap, bool unorm8) {
    if (mipmap && unorm8) return {GL_RGBA8, GL_UNSIGNED_BYTE, TextureTexels::Rgba8Unorm};
    const bool float_filterable = !context.is_es() || context.facts().has_extension("GL_OES_texture_float_linear");
    if ((mipmap && context.is_es()) || (filter == SamplerFilter::Linear && !float_filterable)) {
        return {GL_RGBA16F, GL_HALF_FLOAT, TextureTexels::Rgba16Float};
    }
    return {};
}

GLint gl_wrap(WrapMode wrap) {
    switch (wrap) {
        case WrapMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case WrapMode::Repeat: return GL_REPEAT;
        case WrapMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
        case WrapMode::ClampToBorder: return GL_CLAMP_TO_BORDER;  // border colour (0, 0, 0, 0): GL's default
    }
    return GL_CLAMP_TO_EDGE;
}

// The one upload path of the input and of every extra texture: `image` (empty = a 1x1
// transparent-black texture, for shaders that sample nothing) bound to texture unit `unit`, where
// it stays for the draw. With `mipmap`, a full chain from glGenerateMipmap (Mesa fills each level
// by a linear blit of the one above, as the Vulkan engine does), in choose_upload's format.
UniqueTexture create_sampled_texture(const GlContext& context, const Image& image, SamplerFilter filter, WrapMode wrap,
                                     bool mipmap, SamplerFilter mip_filter, bool unorm8, GLuint unit) {
    const GlFunctions& gl = context.functions();
    const Image blank = Image::make(1, 1);
    const Image& source = image.empty() ? blank : image;
    const TextureUpload upload = choose_upload(context, filter, mipmap, unorm8);
    std::vector<unsigned char> texels(source.pixel_count() * vulkan::texel_bytes(upload.texels));
    vulkan::write_texels(source, upload.texels, texels.data());  // row 0 first: t = 0 is the top row

    const GLsizei levels = mipmap ? static_cast<GLsizei>(mip_level_count(source.width, source.height)) : 1;
    UniqueTexture texture = make_texture(gl);
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    gl.BindTexture(GL_TEXTURE_2D, texture.get());
    gl.TexStorage2D(GL_TEXTURE_2D, levels, upload.internal_format, source.width, source.height);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, source.width, source.height, GL_RGBA, upload.type, texels.data());
    const bool linear = filter == SamplerFilter::Linear;
    GLint min_filter = linear ? GL_LINEAR : GL_NEAREST;
    if (levels > 1) {
        gl.GenerateMipmap(GL_TEXTURE_2D);
        const bool blend = mip_filter == SamplerFilter::Linear;
        min_filter = linear ? (blend ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST)
                            : (blend ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
    }
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, gl_wrap(wrap));
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, gl_wrap(wrap));
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    gl.ActiveTexture(GL_TEXTURE0);
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
Image to_image(const std::vector<unsigned char>& pixels, int width, int height, OutputFormat layout) {
    const size_t row_bytes = static_cast<size_t>(width) * vulkan::texel_bytes(layout);
    std::vector<unsigned char> top_first(pixels.size());
    for (int y = 0; y < height; ++y) {
        std::memcpy(top_first.data() + static_cast<size_t>(y) * row_bytes,
                    pixels.data() + static_cast<size_t>(height - 1 - y) * row_bytes, row_bytes);
    }
    return vulkan::read_texels(top_first.data(), width, height, layout);
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
        // The input on unit 0, the extra textures on 1, 2, ... in order.
        std::vector<SamplerUnit> samplers{{job.sampler, 0}};
        for (size_t i = 0; i < job.textures.size(); ++i) {
            samplers.push_back({job.textures[i].name, static_cast<GLint>(i + 1)});
        }
        auto bindings = bind_program_interface(gl, program.value().get(), job.uniform_block, samplers);
        if (!bindings) return bindings.error();
        if (auto plain = set_plain_uniforms(gl, program.value().get(), job.plain_uniforms); !plain.ok()) return plain.error();
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
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, target.get());
        gl.TexStorage2D(GL_TEXTURE_2D, 1, output_internal_format(job.format), job.width, job.height);
        // After the target, so each texture stays bound to its unit (unit 0 holds the input again).
        std::vector<UniqueTexture> textures;
        textures.push_back(create_sampled_texture(*context_, *job.input, job.filter, job.wrap, job.mipmap, job.mip_filter, job.unorm8, 0));
        for (size_t i = 0; i < job.textures.size(); ++i) {
            const TextureInput& t = job.textures[i];
            const auto unit = static_cast<GLuint>(i + 1);
            textures.push_back(create_sampled_texture(*context_, *t.image, t.filter, t.wrap, t.mipmap, t.mip_filter, t.unorm8, unit));
        }

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
        gl.ClearBufferfv(GL_COLOR, 0, job.clear_color.data());  // the whole target: no scissor is on
        // The job's viewport counts rows from the top; GL's from the bottom (the image is flipped
        // on readback), so its bottom edge is height - y - h rows up.
        if (job.viewport.full()) {
            gl.Viewport(0, 0, job.width, job.height);
        } else {
            gl.Viewport(job.viewport.x, job.height - job.viewport.y - job.viewport.height, job.viewport.width,
                        job.viewport.height);
        }
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        if (srgb_switch) gl.Disable(GL_FRAMEBUFFER_SRGB);  // and never decode on read

        const GlReadback readback = readback_of(job.format);
        std::vector<unsigned char> pixels(static_cast<size_t>(job.width) * static_cast<size_t>(job.height) * vulkan::texel_bytes(readback.layout));
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadPixels(0, 0, job.width, job.height, GL_RGBA, readback.type, pixels.data());
        if (auto errors = take_gl_errors(gl); !errors.empty()) {
            return make_validation_error(fmt::format("GL error during the render: {}{}", gl_error_name(errors.front()),
                                                     errors.size() > 1 ? fmt::format(" (and {} more)", errors.size() - 1)
                                                                       : std::string()));
        }
        return to_image(pixels, job.width, job.height, readback.layout);
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
