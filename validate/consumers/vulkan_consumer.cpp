// "vulkan": SPIR-V as a Vulkan host uses it — spirv-val on each module, then the modules rendered
// by the Vulkan engine (lavapipe by default, any device by --device).
#include <cstring>

#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

class VulkanConsumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines&) const override {
        if (f.data.size() % 4 != 0) return make_validation_error("SPIR-V file size is not a multiple of 4");
        SpirvBinary words(f.data.size() / 4);
        std::memcpy(words.data(), f.data.data(), f.data.size());
        auto status = validate_spirv(words);
        if (!status.ok()) return as_validation(status.error());
        return status;
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        auto job = vulkan_job(std::move(r));
        if (!job.ok()) return job.error();
        return render_on_vulkan(job.value(), engines);
    }

    bool renders_on_vulkan() const override { return true; }

    std::string describe(ConsumerEngines& engines) const override { return "Vulkan: " + engines.vulkan_device_name(); }
};

}  // namespace

Result<RenderJob> vulkan_job(TargetRenderRequest r) {
    auto uniforms = variant_uniforms(r);
    if (!uniforms.ok()) return uniforms.error();
    auto textures = engine_textures(r, [&](const std::string& name) { return spirv_texture_binding(r, name); });
    if (!textures.ok()) return textures.error();
    auto job = request_job<RenderJob>(r, std::move(uniforms.value()), std::move(textures.value()));
    job.vertex_spirv = r.compiled->vertex;
    job.fragment_spirv = r.compiled->fragment;
    job.keep_on_device = r.keep_on_device;
    return job;
}

const Consumer& vulkan_consumer() {
    static const VulkanConsumer consumer;
    return consumer;
}

}  // namespace crtforge
