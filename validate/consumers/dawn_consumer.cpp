// "dawn": WGSL as a WebGPU page uses it — Dawn (Chromium's WebGPU, npm webgpu) compiles the module
// with zero errors and zero warnings, and renders it from the bind-group layout crtforge describes.
#include <fmt/format.h>

#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

class DawnConsumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        auto engine = engines.dawn();
        if (!engine.ok()) return engine.error();
        auto messages = engine.value()->compile(f.data);
        if (!messages.ok()) return messages.error();
        // Zero errors and zero warnings: a warning in a user's browser console is a defect too.
        if (messages.value().empty()) return Ok{};
        const WgslMessage& m = messages.value().front();
        return make_validation_error(fmt::format("Dawn {}: {} ({} message{})", m.type, m.text, messages.value().size(),
                                                 messages.value().size() == 1 ? "" : "s"),
                                     "<wgsl>", m.line);
    }

    Result<Image> render(const TargetRenderRequest& r, ConsumerEngines& engines) const override {
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        auto uniforms = variant_uniforms(r);
        if (!uniforms.ok()) return uniforms.error();
        auto engine = engines.dawn();
        if (!engine.ok()) return engine.error();
        auto job = request_job<DawnJob>(r, std::move(uniforms.value()));
        job.wgsl = shader.value()->data;
        job.uses_texture = !r.compiled->reflection.textures.empty();
        return engine.value()->render(job);
    }

    std::string describe(ConsumerEngines& engines) const override {
        auto d = engines.dawn();
        return d.ok() ? d.value()->adapter_description() : std::string("Dawn unavailable");
    }
};

}  // namespace

const Consumer& dawn_consumer() {
    static const DawnConsumer consumer;
    return consumer;
}

}  // namespace crtforge
