// "godot4-shim": no Godot 4 is installable here, so Godot 4 canvas_item shaders are proven through
// the shim (godot_shim.hpp): each shader, wrapped in declarations of what Godot provides, must
// compile in glslang, and the node-mode shader renders on Vulkan with Godot's builtins filled in
// for the frame.
#include <cmath>

#include "crtforge/uniforms.hpp"
#include "targets/godot/godot_compiler.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

// The shim's block: Godot's builtins for this frame, then the shader's uniforms at the variant's
// values (colours are vec3 in Godot 4).
Result<std::vector<uint8_t>> pack_shim_uniforms(const Reflection& reflection, const TargetRenderRequest& r) {
    if (reflection.uniform_blocks.empty()) return std::vector<uint8_t>{};
    const auto values = effective_values(r.compiled->variant, r.overrides);
    return pack_block(reflection.uniform_blocks.front(), [&](const ReflectedMember& m) -> Result<MemberData> {
        if (m.name == "TEXTURE_PIXEL_SIZE") return MemberData{std::vector<float>{1.0f / r.input.width, 1.0f / r.input.height}};
        if (m.name == "SCREEN_PIXEL_SIZE") return MemberData{std::vector<float>{1.0f / r.width, 1.0f / r.height}};
        if (m.name == "TIME") return MemberData{std::vector<float>{static_cast<float>(std::fmod(r.time, consumers::kGodotTimeRollover))}};
        if (m.name == "frameCount") return MemberData{static_cast<int32_t>(r.frame_count & 0x7fffffff)};
        // What crtforge_pipeline.gd sets: the time reduced exactly (the TIME fallback is for hosts without it).
        if (m.name == godot::GodotCompiler::kHostTime)
            return MemberData{std::vector<float>{static_cast<float>(shader_time(r.compiled->variant, values, r.time))}};
        auto v = values.find(m.name);
        if (v == values.end())
            return make_validation_error("the Godot shader declares uniform '" + m.name + "' that the variant has no value for");
        return member_data(v->second, m.type);
    });
}

class Godot4ShimConsumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        return consumers::compile_through_shim(f.data, 4, engines);
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        auto shim = consumers::wrap_in_shim(shader.value()->data, 4);
        if (!shim.ok()) return shim.error();
        CompileOptions options;
        options.optimize = false;
        options.source_name = "<godot4 shim>";
        auto module = engines.front_end(shim.value().glsl, options);
        if (!module.ok()) return module.error();
        auto bytes = pack_shim_uniforms(module.value()->reflection, r);
        if (!bytes.ok()) return bytes.error();
        const std::vector<consumers::ShimTexture>& declared = shim.value().textures;
        auto textures = engine_textures(r, [&](const std::string& name) -> Result<uint32_t> {
            for (const auto& t : declared)
                if (t.name == name) return t.binding;
            return make_validation_error("the Godot shader declares no sampler '" + name + "'");
        });
        if (!textures.ok()) return textures.error();
        auto job = request_job<RenderJob>(r, std::move(bytes.value()), std::move(textures.value()));
        job.vertex_spirv = r.compiled->vertex;
        job.fragment_spirv = module.value()->spirv;
        return render_on_vulkan(job, engines);
    }

    bool renders_on_vulkan() const override { return true; }

    std::string describe(ConsumerEngines& engines) const override {
        return "Godot 4 shim (Godot builtins as Vulkan resources) -> glslang -> Vulkan: " + engines.vulkan_device_name();
    }
};

}  // namespace

const Consumer& godot4_shim_consumer() {
    static const Godot4ShimConsumer consumer;
    return consumer;
}

}  // namespace crtforge
