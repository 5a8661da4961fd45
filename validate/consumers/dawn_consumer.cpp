// "dawn": WGSL as a WebGPU page uses it — Dawn (Chromium's WebGPU, npm webgpu) compiles the module
// with zero errors and zero warnings. A preset renders through the npm package the export ships
// (index.mjs, crt-webgpu.mjs, its manifest, WGSL and LUT files) exactly as a page runs it, so a bug
// in the shipped driver or its manifest fails validation; a lone pass (`crtforge render` of one
// pass, the stage checks) renders from the bind-group layout crtforge describes. The plan's
// `web = "three" | "pixi" | "babylon"` entries run the preset through that framework adapter of
// the package instead (examples/webgpu/check.mjs, on the framework's own device).
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/assembler.hpp"
#include "crtforge/exporter.hpp"
#include "runtime/dawn/framework_check.hpp"
#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

// The bindings of the module's textures and their samplers, as the manifest's bind-group layout
// gives them: a host needs nothing else to bind a pass.
struct WgslBindings {
    std::map<std::string, uint32_t> texture, sampler;  // texture name -> its binding, its sampler's binding
    std::set<std::string> border_in_shader;  // textures whose clamp_to_border the shader emulates
};

Result<WgslBindings> wgsl_bindings(const TargetOutput& output) {
    const auto manifest = nlohmann::json::parse(output.manifest_json, nullptr, false);
    if (manifest.is_discarded() || !manifest.contains("bindGroupLayout"))
        return make_validation_error("the wgsl output has no bind-group layout");
    std::map<std::string, uint32_t> sampler_by_name;
    WgslBindings out;
    for (const auto& e : manifest["bindGroupLayout"]["entries"]) {
        if (e.contains("sampler")) sampler_by_name[e.value("name", "")] = e.value("binding", 0u);
        if (e.contains("texture")) out.texture[e.value("name", "")] = e.value("binding", 0u);
    }
    for (const auto& e : manifest["bindGroupLayout"]["entries"])
        if (e.contains("texture") && e.contains("pairedSampler")) {
            auto s = sampler_by_name.find(e["pairedSampler"].get<std::string>());
            if (s != sampler_by_name.end()) out.sampler[e.value("name", "")] = s->second;
        }
    for (const auto& e : manifest["bindGroupLayout"]["entries"])
        if (e.contains("sampler") && e["sampler"].value("borderInShader", false) && e.contains("pairedTexture"))
            out.border_in_shader.insert(e["pairedTexture"].get<std::string>());
    return out;
}

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

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        auto bindings = wgsl_bindings(*r.output);
        if (!bindings.ok()) return bindings.error();
        auto lookup = [](const std::map<std::string, uint32_t>& map, const std::string& name) -> Result<uint32_t> {
            auto it = map.find(name);
            if (it == map.end()) return make_validation_error("the wgsl bind-group layout has no entry for '" + name + "'");
            return it->second;
        };
        auto uniforms = variant_uniforms(r);
        if (!uniforms.ok()) return uniforms.error();
        auto textures = engine_textures(
            r, [&](const std::string& name) { return lookup(bindings.value().texture, name); },
            [&](const std::string& name) { return lookup(bindings.value().sampler, name); });
        if (!textures.ok()) return textures.error();
        // As the shipped JS host does: a texture whose border the shader fades to samples
        // clamp-to-edge; any other clamp_to_border reaches Dawn, which refuses it.
        auto edge_if_emulated = [&](const std::string& name, WrapMode& wrap) {
            if (wrap == WrapMode::ClampToBorder && bindings.value().border_in_shader.count(name)) wrap = WrapMode::ClampToEdge;
        };
        for (TextureInput& t : textures.value()) edge_if_emulated(t.name, t.wrap);
        auto engine = engines.dawn();
        if (!engine.ok()) return engine.error();
        auto job = request_job<DawnJob>(r, std::move(uniforms.value()), std::move(textures.value()));
        job.wgsl = shader.value()->data;
        job.uses_texture = bindings.value().texture.count(kSourceTextureName) != 0;
        edge_if_emulated(kSourceTextureName, job.wrap);
        if (job.uses_texture) {
            job.texture_binding = bindings.value().texture.at(kSourceTextureName);
            auto sampler = lookup(bindings.value().sampler, kSourceTextureName);
            if (!sampler.ok()) return sampler.error();
            job.sampler_binding = sampler.value();
        }
        return engine.value()->render(job);
    }

    Result<std::vector<Image>> render_scene(const SceneRenderRequest& r, ConsumerEngines& engines) const override {
        // A host mode names a framework adapter of the package: the preset runs through it.
        if (!r.host.empty() && !detail::is_web_framework(r.host))
            return make_error("the WGSL target has no host mode '" + r.host + "' (three, pixi or babylon)");
        if (!r.preset || !r.passes || !r.outputs || r.outputs->size() != r.passes->size() || !r.source)
            return make_error("a Dawn scene render needs the preset, its passes and their WGSL files");
        DawnSceneJob job;
        auto package = preset_web_package(*r.preset, *r.passes, *r.outputs);
        if (!package.ok()) return package.error();
        job.package_files = std::move(package.value());
        job.preset = r.preset->name;
        const consumers::SceneFrames frames = consumers::scene_frames(*r.preset, r.frames);
        for (int f : frames.run) {
            auto input = r.source(f);
            if (!input.ok()) return input.error();
            job.inputs.push_back(std::move(input.value()));
            // The package's frame is the frame counter a game passes; its time, unless given, is
            // frame / fps: given only where the sequence starts elsewhere.
            job.run.push_back(r.frame_count_base + f);
            if (r.start_time != 0.0 || r.frame_count_base != 0) job.times.push_back(r.start_time + f / r.preset->scene.fps);
        }
        for (int f : frames.capture) job.capture.push_back(r.frame_count_base + f);
        if (r.fit) job.fit = display_fit_name(*r.fit);
        job.width = r.width;
        job.height = r.height;
        job.format = r.format;
        job.params = r.overrides;
        job.framework = r.host;
        auto engine = engines.dawn();
        if (!engine.ok()) return engine.error();
        auto images = engine.value()->render_scene(job);
        if (!images.ok()) return images.error();
        return consumers::in_request_order(r.frames, frames.capture, images.value());
    }

    // The package keeps an 8-bit pass (and every LUT) in rgba8unorm, as a page does, and llvmpipe
    // returns a linear sample of rgba8unorm in whole 1/255 steps (measured through Dawn: a 0 -> 255
    // ramp sampled at 64 points comes back as integers /255, up to 0.86/255 off; rgba16float's
    // samples are exact), which the per-pass path never met since it uploads floats.
    double filtered_8bit_step() const override { return 1.0 / 255.0; }

    std::string describe(ConsumerEngines& engines) const override {
        auto d = engines.dawn();
        return d.ok() ? d.value()->adapter_description() + "; presets through the exported npm package (crt-webgpu.mjs)"
                      : std::string("Dawn unavailable");
    }
};

}  // namespace

const Consumer& dawn_consumer() {
    static const DawnConsumer consumer;
    return consumer;
}

}  // namespace crtforge
