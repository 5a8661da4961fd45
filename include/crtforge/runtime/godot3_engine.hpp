// The Godot 3 render engine: the Godot 3 canvas_item target proven by a real Godot 3 (Debian's
// `godot3`, 3.2.3, GLES3 video driver) drawing it with Mesa llvmpipe on a private Xvfb X server.
//
// One render_godot3() call is one Godot process, started on the runner project in
// tools/godot3-runner/ (see its README.md) and run in a fresh temporary directory that the call
// removes before it returns:
//   1. the job's shader, input pixels (raw float32) and params (JSON) are written there, with a
//      copy of the runner project, so Godot never writes into the source tree;
//   2. `Xvfb -displayfd` starts on a free display; `godot3` runs the runner on it, which puts the
//      input on a TextureRect filling an off-screen HDR Viewport of exactly width x height, with a
//      ShaderMaterial made of `shader_code`, renders `frames` frames and writes the pixels back;
//   3. Godot and Xvfb are waited for (no zombies); Godot is killed after `timeout_seconds`.
// No exception escapes; every failure is a Result error. Thread-safe: calls share nothing.
//
// What the shader sees (measured on 3.2.3, see tools/godot3-runner/README.md):
//  - TEXTURE is the input (RGBA32F, clamp to edge, no mipmaps, bilinear only for Linear) and UV is
//    (0, 0) at its top-left; COLOR on entry is the vertex colour (white), not the texture sample;
//  - FRAGCOORD and SCREEN_UV have a BOTTOM-left origin; SCREEN_PIXEL_SIZE = 1 / output size
//    (of the padded 2-pixel viewport when width or height is 1); TEXTURE_PIXEL_SIZE = 1 / input;
//  - the viewport is cleared to transparent black and the default `blend_mix` render mode applies,
//    so a COLOR with alpha a comes back as (rgb * a, a); write `render_mode blend_disabled;` (or
//    alpha 1) to get COLOR back unchanged.
// The read-back is half float (Godot's HDR viewport is RGBA16F): values above 1 and below 0 survive,
// with about 3 decimal digits (relative error < 2^-10: llvmpipe rounds to half toward zero, so 0.3
// comes back as 0.2998).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/value.hpp"

namespace crtforge {

struct Godot3Job {
    // A complete Godot 3 shader starting with `shader_type canvas_item;`.
    std::string shader_code;
    // The picture the shader reads through TEXTURE. An empty image gives a 1x1 transparent-black
    // texture, for shaders that sample nothing.
    Image input;
    SamplerFilter filter = SamplerFilter::Linear;
    int width = 0, height = 0;  // output size in pixels, 1..kMaxImageDimension
    // Uniform name -> value, set with ShaderMaterial.set_shader_param. Every name must be a uniform
    // the shader declares, and the value must fit its type: double -> float, int64_t -> int (or
    // float), bool -> bool, Color -> `vec4 : hint_color` (alpha 1) or vec3. Enum names (strings)
    // are refused: pass the enum's index as int64_t.
    std::map<std::string, Value> params;
    int frames = 2;             // frames rendered before the read-back, 1..1000
    int timeout_seconds = 60;   // Godot is killed after this long and the call fails
};

// Renders the job and returns the output image (width x height, row 0 = top, linear floats).
// Errors, all one line:
//  - godot3 or Xvfb not on PATH: ErrorKind::Input, naming the Debian packages godot3 and xvfb;
//  - a bad job (size, inconsistent input, empty shader, a param that is NaN or a string):
//    ErrorKind::Input with field "job.<name>";
//  - Godot's shader compiler rejects the code: ErrorKind::Validation,
//    "Godot 3 rejected the shader: line N: <Godot's message>"; an error the GL driver raises on
//    the code Godot generated: "Godot 3's GL driver rejected the shader: <log line>";
//  - a param Godot cannot set (no such uniform, wrong type): ErrorKind::Input;
//  - Godot crashes, times out or gives no pixels: ErrorKind::Validation.
Result<Image> render_godot3(const Godot3Job& job);

// Godot 3 (GLES3) running a whole project (its main scene) under a private Xvfb, as the renders
// do; returns what it printed. For checks of exported files in a real Godot 3 project (the
// overlay scene's test); errors as above.
Result<std::string> run_godot3_project(const std::string& project_dir, int timeout_seconds = 60);

// A crtforge scene exported for Godot 3 (<preset>.tscn with crtforge_pipeline.gd), run as a game
// runs it: the scene instanced in a W x H HDR viewport, its `source` an ImageTexture whose pixels
// change every frame, its `frame` set to each frame of `run` in turn.
struct Godot3SceneJob {
    // Files added to the runner project, by path under it: the export's addons/crtforge/ files.
    std::map<std::string, std::string> project_files;
    std::string scene;              // "res://addons/crtforge/<preset>.tscn"
    std::vector<Image> inputs;      // the original at each frame of `run`, all one size
    std::vector<int> run;           // the frames drawn, in order
    std::vector<int> capture;       // the frames whose display image comes back (each in `run`)
    double fps = 60;                // a uniform crtforge_validation_time, where declared, gets
    double start_time = 0;          // (start_time + frame / fps) mod 3600, as Godot wraps TIME
    int frame_count_base = 0;       // the scene's `frame` (shaders' frameCount) is frame_count_base + frame
    std::string fit;                // "": the scene's own display fit; else stretch, aspect or integer
    int width = 0, height = 0;      // the display, 2..kMaxImageDimension
    std::map<std::string, Value> params;  // set on every pass that declares the uniform
    int timeout_seconds = 120;
};

// The display images of job.capture, in that order (row 0 = top, linear floats, RGBA16F precision).
// Errors as render_godot3's; a GDScript error in the scene's script fails the render too.
Result<std::vector<Image>> render_godot3_scene(const Godot3SceneJob& job);

// A Godot 3 that stays up between renders: one Xvfb and one godot3 process running the runner in
// serve mode, fed one job per line (tools/godot3-runner/README.md). Each render gives what the
// one-shot functions above give, without the ~1.7 s start of Xvfb and Godot; a crash or timeout
// ends the process and the next render starts a fresh one. The project files of scene jobs stay in
// the process's project (Godot caches what it loaded): a job bringing different content for a path
// already there gets a fresh process. Not thread-safe: one per thread.
class Godot3Server {
public:
    Godot3Server();
    ~Godot3Server();
    Godot3Server(const Godot3Server&) = delete;
    Godot3Server& operator=(const Godot3Server&) = delete;

    Result<Image> render(const Godot3Job& job);
    Result<std::vector<Image>> render_scene(const Godot3SceneJob& job);

private:
    struct Process;
    Status start();
    void stop();
    Status run(const std::function<Result<std::vector<std::string>>(const std::filesystem::path&)>& prepare,
               const std::map<std::string, std::string>& project_files, int timeout_seconds,
               const std::function<Status(const std::filesystem::path&)>& collect);
    std::unique_ptr<Process> process_;
};

// The version `godot3 --version` prints, e.g. "3.2.3.stable.custom_build" on Debian 12; "" when
// godot3 is not installed. Runs godot3 once per process (the answer is cached).
std::string godot3_version();

}  // namespace crtforge
