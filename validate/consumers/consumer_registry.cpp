// Consumer keys (as TargetInfo::consumer names them) -> consumers, and what the consumers share.
#include <algorithm>
#include <map>
#include <mutex>
#include <vector>

#include "crtforge/cache.hpp"
#include "crtforge/uniforms.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/scene_runner.hpp"

namespace crtforge {

const Consumer* find_consumer(const std::string& key) {
    static const std::map<std::string, const Consumer*> consumers = {
        {"vulkan", &vulkan_consumer()},   {"gl", &gl_consumer()},          {"gl-es", &gl_es_consumer()},
        {"gl-es-plain", &gl_es_plain_consumer()},
        {"hlsl", &hlsl_consumer()},       {"godot4", &godot4_consumer()},
        {"godot3", &godot3_consumer()},   {"dawn", &dawn_consumer()},
    };
    auto it = consumers.find(key);
    return it == consumers.end() ? nullptr : it->second;
}

Result<RenderEngine*> ConsumerEngines::vulkan() {
    if (!vulkan_) {
        auto engine = create_vulkan_engine(vulkan_options_);
        if (!engine.ok()) return engine.error();
        vulkan_ = std::move(engine.value());
    }
    return vulkan_.get();
}

Result<GlEngine*> ConsumerEngines::gl(bool es) {
    auto& slot = es ? gl_es_ : gl_core_;
    if (!slot) {
        auto engine = create_gl_engine(es ? GlApi::Es : GlApi::DesktopCore);
        if (!engine.ok()) return engine.error();
        slot = std::move(engine.value());
    }
    return slot.get();
}

namespace {

// Whether the pool below still exists: a ConsumerEngines that outlives it (a static one, made
// before the pool's first use, is destroyed after it at exit) stops its own Godot instead. A
// trivially destructible flag, so reading it during exit is defined.
bool godot3_pool_alive = false;

// Started Godot 3 servers no ConsumerEngines holds; destroyed (Godot stopped) at exit.
class Godot3Pool {
public:
    Godot3Pool() { godot3_pool_alive = true; }
    ~Godot3Pool() { godot3_pool_alive = false; }
    std::unique_ptr<Godot3Server> take() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (idle_.empty()) return std::make_unique<Godot3Server>();
        auto server = std::move(idle_.back());
        idle_.pop_back();
        return server;
    }
    void give(std::unique_ptr<Godot3Server> server) {
        std::lock_guard<std::mutex> lock(mutex_);
        idle_.push_back(std::move(server));
    }

private:
    std::mutex mutex_;
    std::vector<std::unique_ptr<Godot3Server>> idle_;
};

Godot3Pool& godot3_pool() {
    static Godot3Pool pool;
    return pool;
}

}  // namespace

ConsumerEngines::~ConsumerEngines() {
    if (godot3_ && godot3_pool_alive) godot3_pool().give(std::move(godot3_));
}

Godot3Server& ConsumerEngines::godot3() {
    if (!godot3_) godot3_ = godot3_pool().take();
    return *godot3_;
}

std::string ConsumerEngines::vulkan_device_name() {
    auto v = vulkan();
    return v.ok() ? v.value()->device().name : std::string("unavailable");
}

Result<const ConsumerEngines::Module*> ConsumerEngines::front_end(const std::string& source, const CompileOptions& options) {
    const std::string key = Cache::key({source, shader_stage_name(options.stage),
                                        options.language == SourceLanguage::Hlsl ? "hlsl" : "glsl"});
    auto found = modules_.find(key);
    if (found != modules_.end()) return &found->second;
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) return as_validation(spirv.error());
    auto reflection = reflect(spirv.value());
    if (!reflection.ok()) return reflection.error();
    return &modules_.emplace(key, Module{std::move(spirv.value()), std::move(reflection.value())}).first->second;
}

Result<const OutputFile*> file_with_role(const TargetRenderRequest& request, const std::string& role) {
    if (!request.output) return make_error(std::string("render request without the files of target ") + target_info(request.target).name);
    for (const auto& f : request.output->files)
        if (f.manifest_role() == role) return &f;
    return make_error(std::string(target_info(request.target).name) + " output has no " + role + " file");
}

Result<std::vector<uint8_t>> variant_uniforms(const TargetRenderRequest& r) {
    // The pass works on the pixels it draws: the viewport's when it has one.
    const int width = r.viewport.full() ? r.width : r.viewport.width, height = r.viewport.full() ? r.height : r.viewport.height;
    FrameInfo frame{width, height, r.input->width, r.input->height, r.time, r.frame_count, r.screen_width, r.screen_height};
    return pack_uniforms(*r.compiled, frame, r.overrides);
}

Result<std::vector<TextureInput>> engine_textures(TargetRenderRequest& r,
                                                  const std::function<Result<uint32_t>(const std::string&)>& binding_of,
                                                  const std::function<Result<uint32_t>(const std::string&)>& sampler_binding_of) {
    std::vector<TextureInput> out;
    for (PassTexture& t : r.textures) {
        // A texture the optimiser removed (a program declares it and never samples it) binds nothing.
        if (r.compiled && std::none_of(r.compiled->reflection.textures.begin(), r.compiled->reflection.textures.end(),
                                       [&](const ReflectedTexture& rt) { return rt.name == t.name; }))
            continue;
        TextureInput input;
        input.name = t.name;
        auto binding = binding_of(t.name);
        if (!binding.ok()) return binding.error();
        input.binding = binding.value();
        if (sampler_binding_of) {
            auto sampler = sampler_binding_of(t.name);
            if (!sampler.ok()) return sampler.error();
            input.sampler_binding = sampler.value();
        }
        input.image = std::move(t.image);
        input.filter = t.filter;
        input.wrap = t.wrap;
        input.mipmap = t.mipmap;
        input.mip_filter = t.mip_filter;
        input.unorm8 = t.unorm8;
        out.push_back(std::move(input));
    }
    return out;
}

Result<uint32_t> spirv_texture_binding(const TargetRenderRequest& r, const std::string& name) {
    for (const ReflectedTexture& t : r.compiled->reflection.textures)
        if (t.name == name) return t.binding;
    return make_validation_error("the compiled pass declares no texture '" + name + "'");
}

Result<std::vector<Image>> Consumer::render_scene(const SceneRenderRequest& request, ConsumerEngines& engines) const {
    if (!request.host.empty())
        return make_error("host mode '" + request.host + "' is Godot's or a web framework's: target " + target_info(request.target).name +
                          " has none");
    return run_scene(request, [&](TargetRenderRequest pass) { return render(std::move(pass), engines); });
}

Result<Image> render_on_vulkan(const RenderJob& job, ConsumerEngines& engines) {
    auto engine = engines.vulkan();
    if (!engine.ok()) return engine.error();
    auto image = engine.value()->render(job);
    if (!image.ok()) return as_validation(image.error());
    return image;
}

Diagnostic as_validation(Diagnostic d) {
    d.kind = ErrorKind::Validation;
    return d;
}

namespace consumers {

SceneFrames scene_frames(const Preset& preset, const std::vector<int>& frames) {
    SceneFrames out;
    out.capture = frames;
    std::sort(out.capture.begin(), out.capture.end());
    out.capture.erase(std::unique(out.capture.begin(), out.capture.end()), out.capture.end());
    if (preset.keeps_state() && !out.capture.empty()) {
        for (int f = 0; f <= out.capture.back(); ++f) out.run.push_back(f);
    } else {
        out.run = out.capture;
    }
    return out;
}

std::vector<Image> in_request_order(const std::vector<int>& frames, const std::vector<int>& capture,
                                    const std::vector<Image>& images) {
    std::vector<Image> out;
    for (int f : frames) {
        const size_t at = static_cast<size_t>(std::find(capture.begin(), capture.end(), f) - capture.begin());
        out.push_back(images[at]);
    }
    return out;
}

}  // namespace consumers

}  // namespace crtforge
