#include "crtforge/target_render.hpp"

#include <cstring>
#include <mutex>
#include <regex>

#include "crtforge/dawn_engine.hpp"
#include "crtforge/gl_engine.hpp"
#include "crtforge/godot3_engine.hpp"
#include "crtforge/reflection.hpp"
#include "targets/godot/godot_shim.hpp"

namespace crtforge {

Result<DawnEngine*> shared_dawn_engine() {
    static std::mutex mutex;
    static std::unique_ptr<DawnEngine> engine;
    std::lock_guard<std::mutex> lock(mutex);
    if (!engine) {
        auto created = DawnEngine::create();
        if (!created.ok()) return created.error();
        engine = std::move(created.value());
    }
    return engine.get();
}

TargetRenderer::TargetRenderer(EngineOptions vulkan_options) : vulkan_options_(std::move(vulkan_options)) {}
TargetRenderer::~TargetRenderer() = default;

Result<RenderEngine*> TargetRenderer::vulkan() {
    if (!vulkan_) {
        auto engine = create_vulkan_engine(vulkan_options_);
        if (!engine.ok()) return engine.error();
        vulkan_ = std::move(engine.value());
    }
    return vulkan_.get();
}

Result<const TargetRenderer::ConsumerModule*> TargetRenderer::consumer_module(const std::string& source,
                                                                             const CompileOptions& options) {
    const std::string key = Cache::key({source, shader_stage_name(options.stage),
                                        options.language == SourceLanguage::Hlsl ? "hlsl" : "glsl"});
    auto found = consumer_modules_.find(key);
    if (found != consumer_modules_.end()) return &found->second;
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) {
        Diagnostic d = spirv.error();
        d.kind = ErrorKind::Validation;  // our output was rejected
        return d;
    }
    auto reflection = reflect(spirv.value());
    if (!reflection.ok()) return reflection.error();
    return &consumer_modules_.emplace(key, ConsumerModule{std::move(spirv.value()), std::move(reflection.value())}).first->second;
}

Result<GlEngine*> TargetRenderer::gl(bool es) {
    auto& slot = es ? gl_es_ : gl_core_;
    if (!slot) {
        auto engine = create_gl_engine(es ? GlApi::Es : GlApi::DesktopCore);
        if (!engine.ok()) return engine.error();
        slot = std::move(engine.value());
    }
    return slot.get();
}

std::string TargetRenderer::consumer(TargetId target) {
    switch (target) {
        case TargetId::Spirv: {
            auto v = vulkan();
            return "Vulkan: " + (v.ok() ? v.value()->device().name : std::string("unavailable"));
        }
        case TargetId::Glsl450:
        case TargetId::Glsl330:
        case TargetId::GlslEs300: {
            auto g = gl(target == TargetId::GlslEs300);
            return g.ok() ? g.value()->renderer() : std::string("OpenGL unavailable");
        }
        case TargetId::Hlsl50:
        case TargetId::Hlsl60: {
            auto v = vulkan();
            return "glslang HLSL -> SPIR-V -> Vulkan: " + (v.ok() ? v.value()->device().name : std::string("unavailable"));
        }
        case TargetId::Godot4: {
            auto v = vulkan();
            return "Godot 4 shim (Godot builtins as Vulkan resources) -> glslang -> Vulkan: " +
                   (v.ok() ? v.value()->device().name : std::string("unavailable"));
        }
        case TargetId::Wgsl: {
            auto d = shared_dawn_engine();
            return d.ok() ? d.value()->adapter_description() : std::string("Dawn unavailable");
        }
        case TargetId::Godot3: {
            const std::string version = godot3_version();
            return version.empty() ? std::string("Godot 3 unavailable") : "Godot " + version + " (GLES3 on Mesa, Xvfb)";
        }
    }
    return "?";
}

namespace {

const OutputFile* file_of(const TargetOutput& out, ShaderStage stage) {
    for (const auto& f : out.files)
        if (f.stage == stage) return &f;
    return nullptr;
}

// The fields the Vulkan and GL jobs share.
template <typename Job>
Job common_job(const TargetRenderRequest& r, std::vector<uint8_t> uniforms) {
    Job job;
    job.input = r.input;
    job.filter = r.filter;
    job.width = r.width;
    job.height = r.height;
    job.format = r.format;
    job.uniform_data = std::move(uniforms);
    return job;
}

const OutputFile* file_with_role(const TargetOutput& out, const std::string& role) {
    for (const auto& f : out.files)
        if (f.manifest_role() == role) return &f;
    return nullptr;
}

// The shim's block: Godot's builtins for this frame, then the shader's uniforms at the variant's
// values (colours are vec3 in Godot 4 and vec4 in Godot 3).
Result<std::vector<uint8_t>> pack_shim_uniforms(const Reflection& reflection, const TargetRenderRequest& r) {
    if (reflection.uniform_blocks.empty()) return std::vector<uint8_t>{};
    const auto values = effective_values(r.compiled->variant, r.overrides);
    return pack_block(reflection.uniform_blocks.front(), [&](const ReflectedMember& m) -> Result<MemberData> {
        if (m.name == "TEXTURE_PIXEL_SIZE") return MemberData{std::vector<float>{1.0f / r.input.width, 1.0f / r.input.height}};
        if (m.name == "SCREEN_PIXEL_SIZE") return MemberData{std::vector<float>{1.0f / r.width, 1.0f / r.height}};
        if (m.name == "TIME") return MemberData{std::vector<float>{static_cast<float>(r.time)}};
        auto v = values.find(m.name);
        if (v == values.end())
            return make_validation_error("the Godot shader declares uniform '" + m.name + "' that the variant has no value for");
        return member_data(v->second, m.type);
    });
}

void flip_rows(Image& image) {
    const size_t row = static_cast<size_t>(image.width) * 4;
    for (int y = 0; y < image.height / 2; ++y)
        std::swap_ranges(image.rgba.begin() + y * row, image.rgba.begin() + (y + 1) * row,
                         image.rgba.begin() + (image.height - 1 - y) * row);
}

}  // namespace

Result<Image> TargetRenderer::render(const TargetRenderRequest& r) {
    if (!r.compiled) return make_error("render request without a compiled variant");
    FrameInfo frame{r.width, r.height, r.input.width, r.input.height, r.time};
    auto uniforms = pack_uniforms(*r.compiled, frame, r.overrides);
    if (!uniforms.ok()) return uniforms.error();
    if (r.target != TargetId::Spirv && !r.output) return make_error("render request without the target's files");

    if (r.target == TargetId::Glsl450 || r.target == TargetId::Glsl330 || r.target == TargetId::GlslEs300) {
        auto engine = gl(r.target == TargetId::GlslEs300);
        if (!engine.ok()) return engine.error();
        auto job = common_job<GlRenderJob>(r, std::move(uniforms.value()));
        job.vertex_source = file_of(*r.output, ShaderStage::Vertex)->data;
        job.fragment_source = file_of(*r.output, ShaderStage::Fragment)->data;
        return engine.value()->render(job);
    }

    if (r.target == TargetId::Wgsl) {  // Dawn, the WebGPU implementation in Chrome
        auto engine = shared_dawn_engine();
        if (!engine.ok()) return engine.error();
        const OutputFile* shader = file_with_role(*r.output, "shader");
        if (!shader) return make_error("wgsl output without a shader");
        auto job = common_job<DawnJob>(r, std::move(uniforms.value()));
        job.wgsl = shader->data;
        job.uses_texture = !r.compiled->reflection.textures.empty();
        return engine.value()->render(job);
    }

    if (r.target == TargetId::Godot3) {  // a real Godot 3, node mode
        const OutputFile* shader = file_with_role(*r.output, "shader");
        if (!shader) return make_error("godot3 output without a shader");
        Godot3Job job;
        job.shader_code = shader->data;
        // Godot's TIME is the wall clock; to render a given frame, the one TIME token becomes a
        // uniform pinned to the frame's time (the only change to the shipped text).
        const std::string pinned = "crtforge_validation_time";
        static const std::regex time_token(R"(\bTIME\b)");
        if (std::regex_search(job.shader_code, time_token)) {
            job.shader_code = std::regex_replace(job.shader_code, time_token, pinned);
            job.shader_code.insert(job.shader_code.find("void fragment()"), "uniform float " + pinned + ";\n");
            job.params[pinned] = r.time;
        }
        job.input = r.input;
        job.filter = r.filter;
        job.width = r.width;
        job.height = r.height;
        for (const VariantParam* p : r.compiled->variant.uniforms()) job.params[p->spec->name] = p->value;
        for (const auto& [name, value] : r.overrides) job.params[name] = value;
        return render_godot3(job);
    }

    auto job = common_job<RenderJob>(r, std::move(uniforms.value()));
    if (r.target == TargetId::Godot4) {  // the shim: Godot's builtins as Vulkan resources
        const OutputFile* shader = file_with_role(*r.output, "shader");
        if (!shader) return make_error("godot4 output without a shader");
        auto shim = godot::wrap_in_shim(shader->data, 4);
        if (!shim.ok()) return shim.error();
        CompileOptions options;
        options.optimize = false;
        options.source_name = "<godot4 shim>";
        auto module = consumer_module(shim.value().glsl, options);
        if (!module.ok()) return module.error();
        auto bytes = pack_shim_uniforms(module.value()->reflection, r);
        if (!bytes.ok()) return bytes.error();
        job.uniform_data = std::move(bytes.value());
        job.vertex_spirv = r.compiled->vertex;
        job.fragment_spirv = module.value()->spirv;
    } else if (r.target == TargetId::Spirv) {
        job.vertex_spirv = r.compiled->vertex;
        job.fragment_spirv = r.compiled->fragment;
    } else {  // HLSL: compile the emitted text back to SPIR-V, as a D3D-to-Vulkan layer would
        for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
            CompileOptions options;
            options.stage = stage;
            options.language = SourceLanguage::Hlsl;
            options.optimize = false;
            options.source_name = std::string("<") + target_info(r.target).name + " " + shader_stage_name(stage) + ">";
            auto module = consumer_module(file_of(*r.output, stage)->data, options);
            if (!module.ok()) return module.error();
            (stage == ShaderStage::Vertex ? job.vertex_spirv : job.fragment_spirv) = module.value()->spirv;
        }
    }
    auto engine = vulkan();
    if (!engine.ok()) return engine.error();
    auto image = engine.value()->render(job);
    if (!image.ok()) {
        Diagnostic d = image.error();
        d.kind = ErrorKind::Validation;
        return d;
    }
    // The HLSL vertex shader targets D3D's y-up clip space; on Vulkan that draws the picture upside
    // down, exactly as D3D would show it the right way up. Flip back to compare.
    if (r.target == TargetId::Hlsl50 || r.target == TargetId::Hlsl60) flip_rows(image.value());
    return image;
}

}  // namespace crtforge
