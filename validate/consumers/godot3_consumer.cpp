// "godot3": a real Godot 3 (Debian's godot3 under Xvfb, runtime/godot3) renders the target. A scene
// runs as its users run it: the export's ready-made scene (<preset>.tscn, its pipeline script,
// every pass's shader and the LUTs) instanced in a game window, frame after frame. A lone pass
// (`crtforge render` of one pass) is the node-mode shader on a TextureRect. Both shaders also
// compile through the shim, which checks them as GLSL with Godot 3's builtins.
#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/runtime/godot3_engine.hpp"
#include "targets/godot/godot_scene.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

// Godot's TIME is the wall clock; to render a given frame, the one TIME token becomes a uniform
// the host pins to the frame's time (the only change to the shipped text).
constexpr const char* kPinnedTime = "crtforge_validation_time";

Status pin_time(std::string& code) {
    static const std::regex time_token(R"(\bTIME\b)");
    if (!std::regex_search(code, time_token)) return Ok{};
    code = std::regex_replace(code, time_token, kPinnedTime);
    const size_t entry = code.find("void fragment()");
    if (entry == std::string::npos) return make_validation_error("the Godot 3 shader has no fragment()");
    code.insert(entry, std::string("uniform float ") + kPinnedTime + ";\n");
    return Ok{};
}

class Godot3Consumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        return consumers::compile_through_shim(f.data, 3, engines);
    }

    Result<Image> render(const TargetRenderRequest& r, ConsumerEngines& engines) const override {
        if (!r.textures.empty() || !r.viewport.full() || r.format != OutputFormat::Rgba16Float)
            return make_error("this Godot 3 pass reads extra textures, draws into a viewport or stores an 8-bit "
                              "framebuffer: Godot 3 runs such passes in the exported scene (render the preset, not the pass)");
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        Godot3Job job;
        job.shader_code = shader.value()->data;
        if (auto s = pin_time(job.shader_code); !s.ok()) return s.error();
        if (job.shader_code != shader.value()->data) job.params[kPinnedTime] = r.time;
        job.input = r.input;
        job.filter = r.filter;
        job.width = r.width;
        job.height = r.height;
        for (const VariantParam* p : r.compiled->variant.uniforms()) job.params[p->spec->name] = p->value;
        for (const auto& [name, value] : r.overrides) job.params[name] = value;
        return engines.godot3().render(job);
    }

    Result<std::vector<Image>> render_scene(const SceneRenderRequest& r, ConsumerEngines& engines) const override {
        if (!r.preset || !r.passes || !r.outputs || r.outputs->size() != r.passes->size() || !r.source)
            return make_error("a Godot 3 scene render needs the preset, its passes and their Godot 3 files");
        const Preset& preset = *r.preset;
        Godot3SceneJob job;
        // The export's files for this preset, as a user copies them into a project.
        for (const TargetOutput& pass : *r.outputs)
            for (const OutputFile& f : pass.files) {
                std::string data = f.data;
                if (f.is_shader())
                    if (auto s = pin_time(data); !s.ok()) return s.error();
                job.project_files[f.path] = std::move(data);
            }
        auto luts = lut_files(preset);
        if (!luts.ok()) return luts.error();
        auto scene = generate_target_scene(TargetId::Godot3, preset, *r.passes, *r.outputs, luts.value());
        if (!scene.ok()) return scene.error();
        for (const OutputFile& f : scene.value()) job.project_files[f.path] = f.data;
        job.scene = "res://" + godot::scene_path(preset);
        if (r.fit) job.fit = display_fit_name(*r.fit);

        // Every frame up to the last asked for when the scene keeps state; else only those.
        std::vector<int> run = r.frames;
        std::sort(run.begin(), run.end());
        run.erase(std::unique(run.begin(), run.end()), run.end());
        if ((preset.has_feedback() || preset.history_depth() > 0) && !run.empty()) {
            const int last = run.back();
            run.clear();
            for (int f = 0; f <= last; ++f) run.push_back(f);
        }
        for (int f : run) {
            auto input = r.source(f);
            if (!input.ok()) return input.error();
            job.inputs.push_back(std::move(input.value()));
        }
        job.run = run;
        job.capture = r.frames;
        std::sort(job.capture.begin(), job.capture.end());
        job.capture.erase(std::unique(job.capture.begin(), job.capture.end()), job.capture.end());
        job.fps = preset.scene.fps;
        job.width = r.width;
        job.height = r.height;
        job.params = r.overrides;
        auto images = engines.godot3().render_scene(job);
        if (!images.ok()) return images.error();
        std::vector<Image> out;
        for (int f : r.frames) {
            const size_t at = static_cast<size_t>(std::find(job.capture.begin(), job.capture.end(), f) - job.capture.begin());
            out.push_back(images.value()[at]);
        }
        return out;
    }

    // The exported scene's last pass is an 8-bit viewport (llvmpipe truncates to it).
    double output_quantum() const override { return 1.0 / 255.0; }

    std::string describe(ConsumerEngines&) const override {
        const std::string version = godot3_version();
        return version.empty() ? std::string("Godot 3 unavailable") : "Godot " + version + " (GLES3 on Mesa, Xvfb; the exported scene)";
    }
};

}  // namespace

const Consumer& godot3_consumer() {
    static const Godot3Consumer consumer;
    return consumer;
}

}  // namespace crtforge
