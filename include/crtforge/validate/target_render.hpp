// Renders a target's emitted shaders through the consumer that proves them (TargetInfo::consumer,
// validate/consumers/): SPIR-V on Vulkan (lavapipe by default); GLSL on Mesa's OpenGL / OpenGL ES
// driver through EGL surfaceless; HLSL through glslang's HLSL front end to SPIR-V on Vulkan (D3D's
// y-up clip space emulated); Godot 4 through a shim of Godot's builtins on Vulkan; Godot 3 in a real
// Godot 3 under Xvfb; WGSL in Dawn (Chromium's WebGPU) on Mesa's GLES driver.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>

#include "crtforge/exporter.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/reflection.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/uniforms.hpp"

namespace crtforge {

// Feeds one emitted shader file to the compiler of its target's consumer, as a host would: SPIR-V
// through spirv-val, GLSL re-parsed by glslang in the profile of its #version line, HLSL compiled by
// glslang's HLSL front end (then spirv-val), Godot shaders through the shim, WGSL compiled by Dawn,
// which must report no error and no warning. Rejections are ErrorKind::Validation; files that are
// not shaders (materials, READMEs) pass.
Status consume_output(TargetId target, const OutputFile& file);

class DawnEngine;
// The process's Dawn engine (one Node.js runner for every thread; its calls are serialised),
// started on first use. A failure to start is returned and retried on the next call.
Result<DawnEngine*> shared_dawn_engine();

// A texture a pass reads besides its main input, as the pass samples it.
struct PassTexture {
    std::string name;  // the sampler's name in the pass's shader
    SharedImage image;
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    bool mipmap = false;  // sampled through a mip chain (RenderJob::mipmap)
    SamplerFilter mip_filter = SamplerFilter::Linear;
    bool unorm8 = false;  // an 8-bit picture (RenderJob::unorm8)
};

// One pass of one frame, through one target's consumer.
struct TargetRenderRequest {
    const CompiledVariant* compiled = nullptr;
    TargetId target = TargetId::Spirv;
    // The emitted files of that pass; spirv renders the compiled modules and needs none.
    const TargetOutput* output = nullptr;
    SharedImage input;  // the main input ("source"), shared: a pass output reaches its reader without a copy
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    bool mipmap = false;
    SamplerFilter mip_filter = SamplerFilter::Linear;
    bool unorm8 = false;                 // the main input is an 8-bit picture (RenderJob::unorm8)
    std::vector<PassTexture> textures;  // the pass's other textures
    int width = 0, height = 0;           // the target's size
    Viewport viewport;                   // where the pass draws (default: the whole target)
    // The screen's size in the display (the viewportSize builtin); 0: where this pass draws.
    int screen_width = 0, screen_height = 0;
    std::array<float, 4> clear_color = {0, 0, 0, 0};
    double time = 0.0;
    long long frame_count = 0;
    OutputFormat format = OutputFormat::Rgba16Float;  // float output: no 8-bit quantisation in comparisons
    std::map<std::string, Value> overrides;
    // Only later passes of this scene, on this consumer, read the output (RenderJob::keep_on_device).
    bool keep_on_device = false;
};

// A scene over a sequence of frames through one target's consumer: every pass each frame, each
// intermediate output stored in its pass's format, feedback and history kept between frames, the
// last pass drawn into the screen's rectangle of the display over opaque black.
struct SceneRenderRequest {
    const Preset* preset = nullptr;
    const std::vector<CompiledVariant>* passes = nullptr;  // compile_scene()
    TargetId target = TargetId::Spirv;
    const std::vector<TargetOutput>* outputs = nullptr;    // the target's files, per pass (spirv: may be null)
    std::function<Result<Image>(int frame)> source;        // the original at each frame
    int width = 0, height = 0;                             // the display
    std::optional<DisplayFit> fit;                         // default: the preset's
    std::vector<int> frames;                               // the frames whose display image is returned
    OutputFormat format = OutputFormat::Rgba16Float;       // the display's
    std::map<std::string, Value> overrides;
    std::map<std::string, SharedImage> file_luts;          // images of the preset's file LUTs, by name
    double start_time = 0.0;                               // seconds at frame 0 (frame n: + n / fps)
    // frameCount at frame 0 (frame n: + n, before a pass's frame_count_mod): RetroArch's Vulkan
    // driver runs its first frame with FrameCount 1.
    int frame_count_base = 0;
    // Called after each frame a pipeline host draws (done, total): a long --frame N shows progress.
    // Engines that run the whole sequence themselves (Godot) do not call it.
    std::function<void(size_t done, size_t total)> on_frame;
    // How the host uses the target's files, where a target ships more than one way (Godot): empty
    // for its ready scene; "defaults" (the node-mode shader with no param set), "material" (the
    // exported .tres) or "screen" (the screen-mode shader over the drawn picture); for WGSL, a
    // framework adapter of the npm package: "three", "pixi" or "babylon". A consumer that has no
    // such mode refuses the request.
    std::string host;
};

// The images of a preset's file LUTs (not the generated ones), by name: SceneRenderRequest::file_luts.
Result<std::map<std::string, SharedImage>> read_file_luts(const Preset& preset);

class ConsumerEngines;

// Whether a pass of the preset samples an 8-bit texture (an rgba8 or rgba8_srgb pass's output, or a
// LUT) linearly.
bool samples_8bit_linearly(const Preset& preset);

// Owns the engines of one thread, created on first use and reused.
class TargetRenderer {
public:
    explicit TargetRenderer(EngineOptions vulkan_options = {});
    ~TargetRenderer();
    // One pass. Pass the request with std::move to let its pictures move into the engine's job.
    Result<Image> render(TargetRenderRequest request);
    // A scene: the display images of request.frames, in that order.
    Result<std::vector<Image>> render_scene(const SceneRenderRequest& request);
    // consume_output() with this renderer's engines.
    Status compile(TargetId target, const OutputFile& file);
    // One line naming the consumer used for a target (for reports).
    std::string consumer(TargetId target);
    // The step of the target's displayed values where coarser than half floats (0 otherwise).
    double output_quantum(TargetId target);
    // The step of the target's linear samples of 8-bit textures where the preset takes such samples
    // and the consumer's GPU returns them coarser than floats (0 otherwise).
    double filtered_8bit_step(TargetId target, const Preset& preset);
    // Whether the target's consumer renders on the Vulkan engine.
    bool renders_on_vulkan(TargetId target);
    // Whether the target's consumer draws on SwiftShader, whatever the Vulkan device.
    bool draws_on_swiftshader(TargetId target);

private:
    std::unique_ptr<ConsumerEngines> engines_;
};

}  // namespace crtforge
