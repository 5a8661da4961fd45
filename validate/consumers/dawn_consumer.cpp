// "dawn": WGSL as a WebGPU page uses it — Dawn (Chromium's WebGPU, npm webgpu) compiles the module
// with zero errors and zero warnings, and renders it from the bind-group layout crtforge describes.
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/assembler.hpp"
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
