// "godot3": a real Godot 3 (Debian's godot3 under Xvfb, runtime/godot3) renders the node-mode shader;
// both shaders also compile through the shim, which checks them as GLSL with Godot 3's builtins.
#include <regex>

#include <fmt/format.h>

#include "crtforge/runtime/godot3_engine.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

class Godot3Consumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        return consumers::compile_through_shim(f.data, 3, engines);
    }

    Result<Image> render(const TargetRenderRequest& r, ConsumerEngines&) const override {
        if (!r.textures.empty() || !r.viewport.full() || r.format != OutputFormat::Rgba16Float)
            return make_error("this Godot 3 pass reads extra textures, draws into a viewport or stores an 8-bit "
                              "framebuffer: Godot 3 runs such scenes through the exported scene");
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        Godot3Job job;
        job.shader_code = shader.value()->data;
        // Godot's TIME is the wall clock; to render a given frame, the one TIME token becomes a
        // uniform pinned to the frame's time (the only change to the shipped text).
        const std::string pinned = "crtforge_validation_time";
        static const std::regex time_token(R"(\bTIME\b)");
        if (std::regex_search(job.shader_code, time_token)) {
            job.shader_code = std::regex_replace(job.shader_code, time_token, pinned);
            const size_t entry = job.shader_code.find("void fragment()");
            if (entry == std::string::npos) return make_validation_error("the Godot 3 shader has no fragment()");
            job.shader_code.insert(entry, "uniform float " + pinned + ";\n");
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

    std::string describe(ConsumerEngines&) const override {
        const std::string version = godot3_version();
        return version.empty() ? std::string("Godot 3 unavailable") : "Godot " + version + " (GLES3 on Mesa, Xvfb)";
    }
};

}  // namespace

const Consumer& godot3_consumer() {
    static const Godot3Consumer consumer;
    return consumer;
}

}  // namespace crtforge
