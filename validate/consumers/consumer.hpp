// A consumer proves a target's output by doing with it what the target's users do: the compiler of
// its language accepts every shader file, and it renders frames that are judged against the
// goldens. Each lives in its own file in this folder; a TargetInfo names its consumer by key, and
// consumer_registry.cpp maps the keys to them.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/reflection.hpp"
#include "crtforge/runtime/dawn_engine.hpp"
#include "crtforge/runtime/gl_engine.hpp"
#include "crtforge/runtime/godot3_engine.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/validate/target_render.hpp"

namespace crtforge {

// The engines one validation thread works with, created on first use and reused (Vulkan, GL core,
// GL ES; Dawn is one per process), and the SPIR-V that consumer front ends (HLSL, the Godot shim)
// made of a target's text — compiled once per distinct source, since every golden of a preset
// renders the same shader.
class ConsumerEngines {
public:
    explicit ConsumerEngines(EngineOptions vulkan_options) : vulkan_options_(std::move(vulkan_options)) {}
    ~ConsumerEngines();  // hands a started Godot 3 back to the process's pool
    ConsumerEngines(const ConsumerEngines&) = delete;
    ConsumerEngines& operator=(const ConsumerEngines&) = delete;

    Result<RenderEngine*> vulkan();
    Result<GlEngine*> gl(bool es);
    Result<DawnEngine*> dawn() { return shared_dawn_engine(); }
    // This thread's Godot 3, started on its first use and kept for the next ones; when the engines
    // go, it returns to a process-wide pool, so the next engines in the process (the next validate
    // run of a test, of the mutation catalogue) take it started instead of starting Godot again.
    Godot3Server& godot3();
    // "llvmpipe (LLVM 15.0.6, 256 bits)", or "unavailable".
    std::string vulkan_device_name();

    struct Module {
        SpirvBinary spirv;
        Reflection reflection;
    };
    // glslang (GLSL or HLSL front end) on a consumer's source; a rejection is ErrorKind::Validation.
    Result<const Module*> front_end(const std::string& source, const CompileOptions& options);

private:
    EngineOptions vulkan_options_;
    std::unique_ptr<RenderEngine> vulkan_;
    std::unique_ptr<GlEngine> gl_core_, gl_es_;
    std::unique_ptr<Godot3Server> godot3_;
    std::map<std::string, Module> modules_;
};

class Consumer {
public:
    virtual ~Consumer() = default;
    // Feeds one shader file (OutputFile::is_shader()) to the compiler its users run. A rejection is
    // ErrorKind::Validation; a missing tool (no driver, no Node.js) keeps its own kind.
    virtual Status compile(const OutputFile& file, ConsumerEngines& engines) const = 0;
    // Renders one pass of one frame with the target's files, as a host of that language would.
    // The request is the consumer's own: its pictures move into the engine's job, so a large input
    // is not held twice.
    virtual Result<Image> render(TargetRenderRequest request, ConsumerEngines& engines) const = 0;
    // Renders a scene's frames. By default validate's pipeline host (scene_runner.hpp) drives
    // render() pass by pass; a consumer that runs whole scenes itself (Godot 3 and its exported
    // scene) overrides it.
    virtual Result<std::vector<Image>> render_scene(const SceneRenderRequest& request, ConsumerEngines& engines) const;
    // One line naming what really runs the shader, for reports.
    virtual std::string describe(ConsumerEngines& engines) const = 0;
    // The step of the displayed values when the consumer's display is coarser than half floats
    // (the judge allows for it); 0 for the float displays validation reads back.
    virtual double output_quantum() const { return 0.0; }
    // The step of the values its GPU returns when it filters an 8-bit texture linearly, where that
    // is coarser than floats (0: not); a preset that samples such a texture linearly is judged with
    // the step's rounding added to its RMSE bounds (with_filter_step in golden.hpp).
    virtual double filtered_8bit_step() const { return 0.0; }
    // Whether its renders run on the Vulkan engine (so a second Vulkan driver can run them too).
    virtual bool renders_on_vulkan() const { return false; }
    // Whether its GPU is SwiftShader whatever the Vulkan device (Godot 4's web build: WebGL 2 in
    // Chromium on SwiftShader), so that the same SPIR-V on Vulkan over SwiftShader is its peer.
    virtual bool draws_on_swiftshader() const { return false; }
};

// The consumer registered under `key`, or nullptr.
const Consumer* find_consumer(const std::string& key);

// The consumers, one function per file of this folder.
const Consumer& vulkan_consumer();
const Consumer& gl_consumer();
const Consumer& gl_es_consumer();
const Consumer& gl_es_plain_consumer();
const Consumer& hlsl_consumer();
const Consumer& godot3_consumer();
const Consumer& godot4_consumer();
const Consumer& dawn_consumer();

// ---- shared by the consumers -------------------------------------------------------------------

// The file of `output` with manifest role `role`; an error naming the target when there is none.
Result<const OutputFile*> file_with_role(const TargetRenderRequest& request, const std::string& role);

// The std140 bytes of the variant's uniform block for the request's frame (empty: no block).
Result<std::vector<uint8_t>> variant_uniforms(const TargetRenderRequest& request);

// The fields the Vulkan, GL and Dawn jobs share, from the request. `textures` are the engine's
// texture inputs (see engine_textures()). The request's input moves into the job.
template <typename Job>
Job request_job(TargetRenderRequest& r, std::vector<uint8_t> uniforms, std::vector<TextureInput> textures = {}) {
    Job job;
    job.input = std::move(r.input);
    job.filter = r.filter;
    job.wrap = r.wrap;
    job.mipmap = r.mipmap;
    job.mip_filter = r.mip_filter;
    job.unorm8 = r.unorm8;
    job.textures = std::move(textures);
    job.width = r.width;
    job.height = r.height;
    job.viewport = r.viewport;
    job.clear_color = r.clear_color;
    job.format = r.format;
    job.uniform_data = std::move(uniforms);
    return job;
}

// The request's extra textures as engine inputs, each at the binding `binding_of(name)` gives
// (and `sampler_binding_of` for WGSL's separate samplers); an error when a name has none. The
// request's texture pictures move into the result.
Result<std::vector<TextureInput>> engine_textures(
    TargetRenderRequest& r, const std::function<Result<uint32_t>(const std::string&)>& binding_of,
    const std::function<Result<uint32_t>(const std::string&)>& sampler_binding_of = {});

// The binding of a texture in the compiled SPIR-V (what the Vulkan, HLSL and WGSL outputs keep).
Result<uint32_t> spirv_texture_binding(const TargetRenderRequest& r, const std::string& name);

// Renders a job on this thread's Vulkan engine; a failed render is a validation failure.
Result<Image> render_on_vulkan(const RenderJob& job, ConsumerEngines& engines);

// The Vulkan job for a pass with the compiled SPIR-V as it is (the "vulkan" consumer's; the
// benchmark times the same jobs).
Result<RenderJob> vulkan_job(TargetRenderRequest request);

// The same diagnostic as a validation failure: crtforge's output was rejected.
Diagnostic as_validation(Diagnostic d);

namespace consumers {

// The frames a consumer that runs whole scenes itself must draw to show `frames`: every frame up
// to the last when the scene keeps state, else only those (sorted, unique); and the frames to
// capture (sorted, unique).
struct SceneFrames {
    std::vector<int> run, capture;
};
SceneFrames scene_frames(const Preset& preset, const std::vector<int>& frames);

// The captured pictures in the order `frames` asked for them.
std::vector<Image> in_request_order(const std::vector<int>& frames, const std::vector<int>& capture,
                                    const std::vector<Image>& images);

}  // namespace consumers

}  // namespace crtforge
