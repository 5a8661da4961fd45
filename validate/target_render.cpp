// TargetRenderer and consume_output: each target's consumer, found by the key its record names.
#include "crtforge/validate/target_render.hpp"

#include <mutex>

#include "validate/consumers/consumer.hpp"

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

namespace {

Result<const Consumer*> consumer_of(TargetId target) {
    const TargetInfo& info = target_info(target);
    if (const Consumer* c = find_consumer(info.consumer)) return c;
    return make_error(std::string("target ") + info.name + " names consumer '" + info.consumer +
                      "', which validate/consumers does not register");
}

}  // namespace

TargetRenderer::TargetRenderer(EngineOptions vulkan_options)
    : engines_(std::make_unique<ConsumerEngines>(std::move(vulkan_options))) {}
TargetRenderer::~TargetRenderer() = default;

Result<Image> TargetRenderer::render(TargetRenderRequest r) {
    if (!r.compiled) return make_error("render request without a compiled variant");
    auto consumer = consumer_of(r.target);
    if (!consumer.ok()) return consumer.error();
    return consumer.value()->render(std::move(r), *engines_);
}

Result<std::vector<Image>> TargetRenderer::render_scene(const SceneRenderRequest& r) {
    auto consumer = consumer_of(r.target);
    if (!consumer.ok()) return consumer.error();
    return consumer.value()->render_scene(r, *engines_);
}

Status TargetRenderer::compile(TargetId target, const OutputFile& file) {
    if (!file.is_shader()) return Ok{};
    auto consumer = consumer_of(target);
    if (!consumer.ok()) return consumer.error();
    return consumer.value()->compile(file, *engines_);
}

std::string TargetRenderer::consumer(TargetId target) {
    auto consumer = consumer_of(target);
    return consumer.ok() ? consumer.value()->describe(*engines_) : consumer.error().message;
}

double TargetRenderer::output_quantum(TargetId target) {
    auto consumer = consumer_of(target);
    return consumer.ok() ? consumer.value()->output_quantum() : 0.0;
}

bool samples_8bit_linearly(const Preset& preset) {
    for (const Pass& pass : preset.passes)
        for (const PassInput& in : pass.inputs) {
            if (in.filter != Filter::Linear) continue;
            switch (in.from.kind) {
                case TextureSource::Kind::Lut: return true;  // every LUT is an 8-bit picture
                case TextureSource::Kind::Pass:
                case TextureSource::Kind::Feedback:
                    if (const Pass* from = preset.find_pass(in.from.name); from && stores_bytes(from->format)) return true;
                    break;
                case TextureSource::Kind::Original: break;  // hosts upload it as floats
            }
        }
    return false;
}

double TargetRenderer::filtered_8bit_step(TargetId target, const Preset& preset) {
    auto consumer = consumer_of(target);
    if (!consumer.ok() || consumer.value()->filtered_8bit_step() == 0.0) return 0.0;
    return samples_8bit_linearly(preset) ? consumer.value()->filtered_8bit_step() : 0.0;
}

bool TargetRenderer::renders_on_vulkan(TargetId target) {
    auto consumer = consumer_of(target);
    return consumer.ok() && consumer.value()->renders_on_vulkan();
}

bool TargetRenderer::draws_on_swiftshader(TargetId target) {
    auto consumer = consumer_of(target);
    return consumer.ok() && consumer.value()->draws_on_swiftshader();
}

Status consume_output(TargetId target, const OutputFile& file) {
    TargetRenderer renderer;
    return renderer.compile(target, file);
}

}  // namespace crtforge
