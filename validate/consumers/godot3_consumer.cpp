// "godot3": a real Godot 3 (Debian's godot3 under Xvfb, runtime/godot3) renders the target. A scene
// runs as its users run it: the export's ready-made scene (<preset>.tscn, its pipeline script,
// every pass's shader and the LUTs) instanced in a game window, frame after frame. A lone pass
// (`crtforge render` of one pass) is the node-mode shader on a TextureRect. Both shaders also
// compile through the shim, which checks them as GLSL with Godot 3's builtins.
#include <algorithm>
#include <cmath>
#include <regex>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/runtime/godot3_engine.hpp"
#include "crtforge/uniforms.hpp"
#include "targets/godot/godot_compiler.hpp"
#include "targets/godot/godot_scene.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

// Godot's TIME is the wall clock; to render a given frame, the one TIME token becomes a uniform
// the host pins to the frame's time (the only change to the shipped text), wrapped as Godot wraps
// TIME (consumers::kGodotTimeRollover; the runner wraps a scene's frames alike).
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

// validate's host for the exported shaders used without crtforge_pipeline.gd (GoldenEntry's host
// modes): the node-mode shader on a TextureRect, with no param set or through the exported .tres,
// or the screen-mode shader on a ColorRect drawn over the picture. It has what the runner's scene
// mode drives: `passes` (its material is main/Pass's), `source`, `frame`, `playing`, `fit`.
constexpr const char* kHostScript = R"(extends Control
# crtforge validate's host: the exported shaders used as a user would without crtforge_pipeline.gd.
export var linear = true
var passes = [{"alias": "main"}]
var playing = false
var fit = "stretch"
var frame = 0
var seconds = 0.0  # the runner sets it; without crtforge_pipeline.gd nothing reads it (the shader uses TIME)
var source setget _set_source

func _set_source(texture):
	source = texture
	if texture != null:
		texture.flags = Texture.FLAG_FILTER if linear else 0
	var picture = get_node_or_null("main/Picture")
	if picture == null:
		picture = get_node("main/Pass")
	picture.texture = texture
)";

// The host scene for one mode over the pass's files.
Result<std::string> host_scene(const std::string& mode, const TargetOutput& files, bool linear) {
    std::string shader, screen, material;
    for (const OutputFile& f : files.files) {
        const std::string role = f.manifest_role();
        if (role == "shader") shader = f.path;
        if (role == "screenShader") screen = f.path;
        if (role == "material") material = f.path;
    }
    if (shader.empty() || screen.empty() || material.empty())
        return make_error("the Godot 3 export lacks the node shader, screen shader or .tres material");
    std::string resource, material_ref;
    if (mode == "defaults" || mode == "screen") {
        resource = fmt::format("[ext_resource path=\"res://{}\" type=\"Shader\" id=2]\n\n"
                               "[sub_resource type=\"ShaderMaterial\" id=1]\nshader = ExtResource( 2 )\n",
                               mode == "screen" ? screen : shader);
        material_ref = "SubResource( 1 )";
    } else if (mode == "material") {
        resource = fmt::format("[ext_resource path=\"res://{}\" type=\"Material\" id=2]\n", material);
        material_ref = "ExtResource( 2 )";
    } else {
        return make_error("unknown Godot host mode '" + mode + "' (defaults, material or screen)");
    }
    const std::string full = "anchor_right = 1.0\nanchor_bottom = 1.0\nmouse_filter = 2\n";
    std::string nodes = fmt::format("[node name=\"host\" type=\"Control\"]\n{}script = ExtResource( 1 )\nlinear = {}\n\n"
                                    "[node name=\"main\" type=\"Control\" parent=\".\"]\n{}\n",
                                    full, linear ? "true" : "false", full);
    if (mode == "screen")
        nodes += fmt::format("[node name=\"Picture\" type=\"TextureRect\" parent=\"main\"]\n{}expand = true\n\n"
                             "[node name=\"Pass\" type=\"ColorRect\" parent=\"main\"]\n{}material = {}\n",
                             full, full, material_ref);
    else
        nodes += fmt::format("[node name=\"Pass\" type=\"TextureRect\" parent=\"main\"]\n{}expand = true\nmaterial = {}\n",
                             full, material_ref);
    return fmt::format("[gd_scene load_steps=3 format=2]\n\n[ext_resource path=\"res://crtforge_validation_host.gd\" type=\"Script\" id=1]\n{}\n{}",
                       resource, nodes);
}

class Godot3Consumer final : public Consumer {
public:
    // The shim first (its errors name GLSL lines precisely), then the real Godot 3: its own shader
    // language parser is stricter than GLSL in places the shim cannot know (a user's stage once
    // passed the shim and was rejected by Godot). The persistent server keeps this cheap.
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        if (auto shim = consumers::compile_through_shim(f.data, 3, engines); !shim.ok()) return shim;
        if (f.manifest_role() != "shader") return Ok{};  // screen shaders: the matrix's host modes render them
        Godot3Job job;
        job.shader_code = f.data;
        job.width = job.height = 2;
        job.frames = 1;
        auto drawn = engines.godot3().render(job);
        if (!drawn.ok()) return drawn.error();
        return Ok{};
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        if (!r.textures.empty() || !r.viewport.full() || r.format != OutputFormat::Rgba16Float)
            return make_error("this Godot 3 pass reads extra textures, draws into a viewport or stores an 8-bit "
                              "framebuffer: Godot 3 runs such passes in the exported scene (render the preset, not the pass)");
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        Godot3Job job;
        job.shader_code = shader.value()->data;
        if (auto s = pin_time(job.shader_code); !s.ok()) return s.error();
        if (job.shader_code != shader.value()->data) job.params[kPinnedTime] = std::fmod(r.time, consumers::kGodotTimeRollover);
        job.input = std::move(r.input);
        job.filter = r.filter;
        job.width = r.width;
        job.height = r.height;
        for (const VariantParam* p : r.compiled->variant.uniforms()) job.params[p->spec->name] = p->value;
        for (const auto& [name, value] : r.overrides) job.params[name] = value;
        // What crtforge_pipeline.gd sets every frame: the time reduced exactly.
        if (r.compiled->variant.angular_speed())
            job.params[godot::GodotCompiler::kHostTime] =
                shader_time(r.compiled->variant, effective_values(r.compiled->variant, r.overrides), r.time);
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
        if (r.host.empty()) {
            auto luts = lut_files(preset);
            if (!luts.ok()) return luts.error();
            auto scene = generate_target_scene(TargetId::Godot3, preset, *r.passes, *r.outputs, luts.value());
            if (!scene.ok()) return scene.error();
            for (const OutputFile& f : scene.value()) job.project_files[f.path] = f.data;
            job.scene = "res://" + godot::scene_path(preset);
        } else {
            // The shaders used alone: a single pass that reads nothing but its picture.
            if (!preset.single_pass() || !r.passes->front().variant.textures.empty())
                return make_error("Godot host mode '" + r.host + "' needs a single-pass preset that reads only its picture");
            auto host = host_scene(r.host, r.outputs->front(), r.passes->front().variant.texture_filter("source") == Filter::Linear);
            if (!host.ok()) return host.error();
            // Named per mode and preset: the runner caches scenes by path for its whole life.
            const std::string name = "crtforge_validation_" + r.host + "_" + preset.name + ".tscn";
            job.project_files[name] = host.value();
            job.project_files["crtforge_validation_host.gd"] = kHostScript;
            job.scene = "res://" + name;
        }
        if (r.fit) job.fit = display_fit_name(*r.fit);

        // Every frame up to the last asked for when the scene keeps state; else only those.
        std::vector<int> run = r.frames;
        std::sort(run.begin(), run.end());
        run.erase(std::unique(run.begin(), run.end()), run.end());
        if (preset.keeps_state() && !run.empty()) {
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
        job.start_time = r.start_time;
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
        return version.empty() ? std::string("Godot 3 unavailable")
                               : "Godot " + version + " (GLES3 on Mesa, Xvfb): compiles every node shader, renders the exported scene";
    }
};

}  // namespace

const Consumer& godot3_consumer() {
    static const Godot3Consumer consumer;
    return consumer;
}

}  // namespace crtforge
