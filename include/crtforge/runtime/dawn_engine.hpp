// The Dawn engine: WGSL compiled and rendered by Dawn, Chromium's WebGPU implementation, as the
// npm package `webgpu` (0.6.2, dawn.node) ships it — the real consumer of crtforge's WGSL target.
//
// One DawnEngine is one persistent Node.js process running tools/wgsl-runner/runner.mjs (see its
// README.md), started by create() and kept for the engine's lifetime:
//   - Dawn runs its OpenGL ES backend (`backend=opengles`, compatibility feature level) on Mesa
//     llvmpipe through EGL with EGL_PLATFORM=surfaceless — no window system, no Vulkan;
//   - requests and replies are JSON lines on pipes; shader text, pixels and uniform bytes travel
//     as files in a private temporary directory that the destructor removes;
//   - the destructor ends the runner (EOF on its stdin, SIGKILL after 2 s) and reaps it.
// Calls are thread-safe (a mutex serialises them: one request at a time). No exception escapes.
// If the runner dies or a request runs past 120 s, that call fails (ErrorKind::Validation, with
// the runner's last log line), the runner is killed, and the next call starts a fresh one.
//
// What the shader sees (measured with webgpu 0.6.2 on Mesa 22.3.6 llvmpipe, GLES 3.2):
//  - @group(0) only: the uniform buffer at uniform_binding (a `var<uniform>`), the input at
//    texture_binding (`texture_2d<f32>`) and its sampler at sampler_binding, and each of
//    `textures` as a `texture_2d<f32>` at its `binding` with a `sampler` at its `sampler_binding`,
//    each visible to both stages; only the bindings the job says are used are in the layout;
//  - the vertex stage draws a full-screen triangle from @builtin(vertex_index) (draw(3), no
//    vertex buffers); @builtin(position) in the fragment stage is in pixels of the whole target
//    (not of the viewport) with (0.5, 0.5) at the centre of the TOP-left pixel; texture coordinate
//    (0, 0) is the top-left of the input (of every texture);
//  - every texture is rgba32float (exact) for Nearest, sampled as unfilterable-float with a
//    non-filtering sampler; for Linear it is rgba16float (converted, round to nearest even)
//    unless the adapter has 'float32-filterable' (llvmpipe's GLES backend does not); addressed by
//    its wrap mode (clamp-to-edge, repeat, mirror-repeat), no mipmaps;
//  - the target is cleared to clear_color, then the triangle is drawn inside `viewport`
//    (setViewport + setScissorRect, rows from the top) without blending.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/value.hpp"

namespace crtforge {

// One message of Dawn's shader compiler (GPUCompilationMessage).
struct WgslMessage {
    std::string type;          // "error", "warning" or "info"
    int line = 0, column = 0;  // 1-based; 0 when Dawn gives no position
    std::string text;          // one line
};

struct DawnJob {
    std::string wgsl;  // one module holding both entry points
    std::string vertex_entry = "vs_main", fragment_entry = "fs_main";
    // The picture bound at texture_binding. An empty image binds a 1x1 transparent-black texture.
    // Ignored when uses_texture is false. Shared, as `textures` are (no copy per pass).
    SharedImage input;
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;  // the input's address mode, both axes
    bool mipmap = false;                    // a mip chain, as RenderJob::mipmap (the shipped driver's)
    SamplerFilter mip_filter = SamplerFilter::Linear;
    bool unorm8 = false;                    // as RenderJob::unorm8: the chain of an 8-bit picture is rgba8unorm
    // More textures, uploaded like `input` with their own filter and wrap: each a texture_2d<f32>
    // at `binding` plus a sampler at `sampler_binding` (`name` is not used here). Bound whether or
    // not uses_texture is set.
    std::vector<TextureInput> textures;
    int width = 0, height = 0;  // output size in pixels, 1..kMaxImageDimension
    Viewport viewport;          // where inside width x height the pass draws; default: everywhere
    std::array<float, 4> clear_color = {0, 0, 0, 0};  // linear RGBA the whole target starts as
    // Rgba16Float: half floats, read back exactly; Rgba8Unorm: byte / 255; Rgba8Srgb: the
    // rgba8unorm-srgb target, read back decoded to linear (as the Vulkan engine does).
    OutputFormat format = OutputFormat::Rgba16Float;
    // The bytes of the uniform buffer as the shader lays it out. Empty = no uniform buffer bound.
    // The binding is exactly this long (rounded up to 4), so a shorter buffer than the shader's
    // block is a validation error.
    std::vector<uint8_t> uniform_data;
    bool uses_texture = true;  // false = no texture and no sampler in the layout
    uint32_t uniform_binding = 0, texture_binding = 1, sampler_binding = 2;
};

// A whole preset run by the npm package an export ships (`crtforge-presets`: index.mjs's
// loadCrtPreset over crt-webgpu.mjs's createCrtScene), as a page or a Node app runs it: the
// package's own manifest, WGSL and LUT files, and its own pass sizes, feedback, history, uniforms
// and time. The runner adds only what an app adds: the original uploaded as a float texture
// (rgba32float, or rgba16float where a pass filters it linearly and the device cannot filter
// float32), one scene.encode() per frame, and the read-back.
struct DawnSceneJob {
    std::map<std::string, std::string> package_files;  // by path inside the package folder
    std::string preset;
    std::vector<Image> inputs;   // the original at each frame of `run`, all one size
    std::vector<int> run;        // the frames drawn, in order: encode()'s `frame`
    std::vector<int> capture;    // the frames whose display image comes back (each in `run`)
    std::vector<double> times;   // seconds at each frame of `run`; empty: the package's own (frame / fps)
    std::string fit;             // "": the preset's display fit; else stretch, aspect or integer
    int width = 0, height = 0;   // the display
    OutputFormat format = OutputFormat::Rgba16Float;
    std::map<std::string, Value> params;  // scene.setParam() before the first frame
    // "": the package's scene on the runner's device. "three", "pixi" or "babylon": through that
    // adapter of the package (crtforge-presets/three, ...) on the framework's own device, by
    // examples/webgpu/check.mjs (a process per sequence; the target is then rgba16float).
    std::string framework;
};

class DawnEngine {
public:
    // Starts the runner and waits for its adapter. Errors (ErrorKind::Input, one line):
    //  - `node` not on PATH: names the Debian packages nodejs and npm;
    //  - tools/wgsl-runner/node_modules/webgpu missing or not 0.6.2: says to run scripts/setup.sh;
    //  - Dawn finds no adapter: says it needs Mesa's GLES through EGL_PLATFORM=surfaceless;
    //  - the runner fails to start otherwise: its last log line.
    static Result<std::unique_ptr<DawnEngine>> create();
    // The first two checks of create() without starting anything: for a clear exit 2 before a run.
    static Status check_setup();
    ~DawnEngine();
    DawnEngine(const DawnEngine&) = delete;
    DawnEngine& operator=(const DawnEngine&) = delete;

    // Every message Dawn's compiler gives for the module (createShaderModule +
    // getCompilationInfo), in order; empty = clean. The caller decides whether warnings fail.
    // An error here is about the runner (died, timed out), not the shader.
    Result<std::vector<WgslMessage>> compile(const std::string& wgsl);

    // Renders the job and returns the output image (width x height, row 0 = top, linear floats).
    // Errors, all one line:
    //  - a bad job (size <= 0 or > kMaxImageDimension, inconsistent input or texture, empty WGSL or
    //    entry point, clashing bindings, a viewport outside the target, a non-finite clear colour):
    //    ErrorKind::Input with field "job.<name>", before any work;
    //  - a compile error: ErrorKind::Validation, "Dawn rejected the WGSL: L:C: <message>" with
    //    Diagnostic::line/column set (warnings do not fail a render: see compile());
    //  - a validation error from the pipeline, bind group or pass (wrong entry point, a binding
    //    the shader uses that the job lacks, a too-short uniform buffer, ...): ErrorKind::Validation;
    //  - the runner died or timed out: ErrorKind::Validation.
    Result<Image> render(const DawnJob& job);

    // The display images of job.capture, in that order (row 0 = top, linear floats). Errors, one
    // line: a bad job (ErrorKind::Input, field "job.<name>"); the package failing to load, a WGSL
    // compile error, the package refusing a param, or any WebGPU validation error while it runs
    // (ErrorKind::Validation).
    Result<std::vector<Image>> render_scene(const DawnSceneJob& job);

    // E.g. "Dawn (npm webgpu 0.6.2), opengles backend, compatibility: llvmpipe-llvm-15-0-6-256-bits-
    // (OpenGL version OpenGL ES 3.2 Mesa 22.3.6)".
    std::string adapter_description() const;

private:
    struct Impl;
    explicit DawnEngine(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace crtforge
