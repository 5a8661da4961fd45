// "hlsl": HLSL as a D3D host compiles it, through glslang's HLSL front end — each file must compile
// (then pass spirv-val), and the pair compiled to SPIR-V renders on Vulkan with D3D's y-up clip
// space emulated (rows flipped back), as a D3D-to-Vulkan layer would run it.
#include <fmt/format.h>

#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

void flip_rows(Image& image) {
    const size_t row = static_cast<size_t>(image.width) * 4;
    for (int y = 0; y < image.height / 2; ++y)
        std::swap_ranges(image.rgba.begin() + y * row, image.rgba.begin() + (y + 1) * row,
                         image.rgba.begin() + (image.height - 1 - y) * row);
}

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
        // Drawn upside down and flipped back below: the viewport goes where the flip brings it home.
        if (!job.viewport.full()) job.viewport.y = job.height - job.viewport.y - job.viewport.height;
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
        auto image = render_on_vulkan(job, engines);
        if (!image.ok()) return image;
        // The vertex shader targets D3D's y-up clip space; on Vulkan that draws the picture upside
        // down, exactly as D3D would show it the right way up. Flip back to compare.
        flip_rows(image.value());
        return image;
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
