// What validate's two real-Godot consumers (Godot 3 under Xvfb, Godot 4 in Chromium) share: pinning
// TIME to the frame being rendered, and the host scenes that use the exported shaders without
// crtforge_pipeline.gd (the matrix's host modes).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/uniforms.hpp"
#include "crtforge/validate/target_render.hpp"
#include "targets/godot/godot_compiler.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge::consumers {

// Godot's TIME is the wall clock; to render a given frame, the one TIME token becomes a uniform
// the host pins to the frame's time (the only change to the shipped text), wrapped as Godot wraps
// TIME (kGodotTimeRollover). The runners set it on every material that declares it.
inline constexpr const char* kPinnedTime = "crtforge_validation_time";
Status pin_time(std::string& code);

// The host scene (.tscn text, Godot `version` 3 or 4) for one host mode over a pass's files:
// "defaults" (the node-mode shader on a TextureRect, no param set), "material" (the exported
// .tres) or "screen" (the screen-mode shader on a ColorRect over the picture). Its script is
// host_script(version), saved as res://crtforge_validation_host.gd.
Result<std::string> host_scene(int version, const std::string& mode, const TargetOutput& files, bool linear);
const char* host_script(int version);
inline constexpr const char* kHostScriptPath = "crtforge_validation_host.gd";

// The project files of a scene render: the export's files for the preset (TIME pinned in every
// shader) and the exported scene, or validate's host scene for `request.host`; `scene` gets the
// res:// path to instance.
Result<std::map<std::string, std::string>> scene_project_files(int version, TargetId target,
                                                               const SceneRenderRequest& request, std::string& scene);

// A lone pass's job (Godot3Job, Godot4Job: the same fields): the node-mode shader with TIME
// pinned, the request's picture, and every param the host sets, as crtforge_pipeline.gd would set
// them (the time reduced exactly as hostTime). Only a pass that reads nothing but its picture
// into a full float viewport runs alone; the others run in the exported scene.
template <typename Job>
Status fill_pass_job(int version, TargetRenderRequest& r, Job& job) {
    if (!r.textures.empty() || !r.viewport.full() || r.format != OutputFormat::Rgba16Float)
        return make_error(fmt::format("this Godot {0} pass reads extra textures, draws into a viewport or stores an 8-bit "
                                      "framebuffer: Godot {0} runs such passes in the exported scene (render the preset, not the pass)",
                                      version));
    auto shader = file_with_role(r, "shader");
    if (!shader.ok()) return shader.error();
    job.shader_code = shader.value()->data;
    if (auto s = pin_time(job.shader_code); !s.ok()) return s.error();
    if (job.shader_code != shader.value()->data) job.params[kPinnedTime] = std::fmod(r.time, kGodotTimeRollover);
    job.input = *r.input;
    job.filter = r.filter;
    job.width = r.width;
    job.height = r.height;
    for (const VariantParam* p : r.compiled->variant.uniforms()) job.params[p->spec->name] = p->value;
    for (const auto& [name, value] : r.overrides) job.params[name] = value;
    if (r.compiled->variant.angular_speed())
        job.params[godot::GodotCompiler::kHostTime] =
            shader_time(r.compiled->variant, effective_values(r.compiled->variant, r.overrides), r.time);
    return Ok{};
}

// A Godot scene job (Godot3SceneJob, Godot4SceneJob: the same fields) filled from the request:
// the project files, the frames to draw with each frame's original, the frames to capture, time
// and params as a game would run them.
template <typename Job>
Status fill_scene_job(int version, TargetId target, const SceneRenderRequest& r, Job& job) {
    auto files = scene_project_files(version, target, r, job.scene);
    if (!files.ok()) return files.error();
    job.project_files = std::move(files.value());
    if (r.fit) job.fit = display_fit_name(*r.fit);
    const SceneFrames frames = scene_frames(*r.preset, r.frames);
    for (int f : frames.run) {
        auto input = r.source(f);
        if (!input.ok()) return input.error();
        job.inputs.push_back(std::move(input.value()));
    }
    job.run = frames.run;
    job.capture = frames.capture;
    job.fps = r.preset->scene.fps;
    job.start_time = r.start_time;
    job.frame_count_base = r.frame_count_base;
    job.width = r.width;
    job.height = r.height;
    job.params = r.overrides;
    return Ok{};
}

}  // namespace crtforge::consumers
