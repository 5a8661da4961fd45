// "hlsl": HLSL as a D3D host compiles it, through glslang's HLSL front end — each file must compile
// (then pass spirv-val), and the pair compiled to SPIR-V renders on Vulkan with D3D's y-up clip
// space emulated by a flipped viewport, as a D3D-to-Vulkan layer (vkd3d, DXVK) runs it.
#include <fmt/format.h>

#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

class HlslConsumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines&) const override {
        auto status = check_hlsl(f.data, f.stage, "main");
        if (!status.ok()) return as_validation(status.error());
        return status;
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        auto uniforms = variant_uniforms(r);
        if (!uniforms.ok()) return uniforms.error();
        // register(tN) of each texture is its SPIR-V binding (SPIRV-Cross keeps it, glslang maps it back).
        auto textures = engine_textures(r, [&](const std::string& name) { return spirv_texture_binding(r, name); });
        if (!textures.ok()) return textures.error();
        auto job = request_job<RenderJob>(r, std::move(uniforms.value()), std::move(textures.value()));
        // The vertex shader targets D3D's y-up clip space: drawn through a flipped viewport, as a
        // D3D-to-Vulkan layer draws it, so SV_Position counts rows from the top as on D3D.
        job.clip_y_up = true;
        job.keep_on_device = r.keep_on_device;
        for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
            auto file = file_with_role(r, stage == ShaderStage::Vertex ? "vertex" : "fragment");
            if (!file.ok()) return file.error();
            CompileOptions options;
            options.stage = stage;
            options.language = SourceLanguage::Hlsl;
            options.optimize = false;
            options.source_name = fmt::format("<{} {}>", target_info(r.target).name, shader_stage_name(stage));
            auto module = engines.front_end(file.value()->data, options);
            if (!module.ok()) return module.error();
            (stage == ShaderStage::Vertex ? job.vertex_spirv : job.fragment_spirv) = module.value()->spirv;
        }
        return render_on_vulkan(job, engines);
    }

    bool renders_on_vulkan() const override { return true; }

    std::string describe(ConsumerEngines& engines) const override {
        return "glslang HLSL -> SPIR-V -> Vulkan: " + engines.vulkan_device_name();
    }
};

}  // namespace

const Consumer& hlsl_consumer() {
    static const HlslConsumer consumer;
    return consumer;
}

}  // namespace crtforge
