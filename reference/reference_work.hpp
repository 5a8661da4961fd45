// The work a render of a scene asks for, counted before it starts, so that a value that makes a
// loop of the reference (and of the shader it mirrors) run billions of times per pixel is refused
// with its name instead of rendering for hours (the reference) or being cut short silently (a GPU
// driver's watchdog). Not part of the oracle's hash: it changes no image, only what is refused.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/scene.hpp"

namespace crtforge::reference {

// Samples x loop steps one frame of a render may ask for: 125 times the heaviest golden of the shipped plan
// (atari-ntsc at 1280x960, its palette search 128 steps a sample: 1.6e8, 1.7 s for the reference on
// 2 cores). It bounds what a value can lengthen, not a stage's fixed cost (super-win at 1920x1080
// counts 5e6 and takes 3.4 s): a render past it would run for hours, or be cut short by a driver.
inline constexpr double kMaxSceneWork = 2e10;

struct SceneWorkJob {
    const Preset* preset = nullptr;
    std::map<std::string, Value> overrides;              // param -> value, in every pass that reads it
    PixelSize source, display;                           // the original's size and the display's
    std::optional<DisplayFit> fit;
    int supersample = 1;                                 // samples per display pixel per side
    std::function<PixelSize(const std::string& lut)> lut_size;  // a LUT's size by name
};

// The estimate for one frame: for each pass, its pixels x samples x (1 + the steps of the loops
// its stages run per sample), summed over the passes. Frames are not counted: how many a render
// draws is bounded on its own (--frame), and each reports its progress; what a value can blow up
// is the work inside one.
double scene_work(const SceneWorkJob& job);

// An error naming the pass, stage and param whose loop makes the work exceed kMaxSceneWork; else Ok.
Status check_scene_work(const SceneWorkJob& job);

// The job of a reference scene render: its source's size (`source` where the caller has read it
// already, else from the first frame's original), its LUTs' sizes from the job's images and the
// preset's generators.
Result<SceneWorkJob> scene_work_job(const ReferenceSceneJob& job, std::optional<PixelSize> source = {});

// check_scene_work of a reference scene render.
Status check_reference_work(const ReferenceSceneJob& job, std::optional<PixelSize> source = {});

}  // namespace crtforge::reference
