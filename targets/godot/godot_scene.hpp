// The ready-made Godot scene of a preset (godot4 and godot3 targets): <preset>.tscn runs the whole
// pipeline — one viewport per pass in drawing order, copies of the passes read as feedback and of
// the original's history, the last pass at the screen's rectangle over black — driven by
// crtforge_pipeline.gd (targets/godot/crtforge_pipeline{3,4}.gd, the same file for every preset),
// which sizes the passes for the node's size and the source's, wires each pass's textures and
// advances frameCount. LUTs ship as PNG files beside it.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::godot {

// The scene, the pipeline script and the LUT files, paths under the target's folder
// (addons/crtforge/...). Roles: "scene", "script", "lut:<name>".
Result<std::vector<OutputFile>> generate_scene(const SceneTargetInput& input, int godot_version);

// The text of crtforge_pipeline.gd for a Godot major version (embedded at build time).
const char* pipeline_script(int godot_version);
// The editor plugin (adds the CrtOverlay node type) and the CrtOverlay node's script.
const char* plugin_script(int godot_version);
const char* overlay_script(int godot_version);

// Godot draws nothing into a viewport under 2 pixels on an axis (godotengine/godot#26187). A pass
// other than the last with an absolute scale of 1 on an axis is drawn into 2 pixels there, both
// computing the pixel's one value (its quad corner held at 0.5 on that axis), so every filter and
// wrap reads the two texels as the one; its readers' size queries are told 1 (godot_compiler).
struct OnePixelAxes {
    bool x = false, y = false;
    bool any() const { return x || y; }
};
OnePixelAxes one_pixel_axes(const Preset& preset, size_t pass_index);
// Of the pass a texture comes from (a pass output or its feedback); none for the others.
OnePixelAxes one_pixel_axes(const Preset& preset, const TextureSource& from);

// The scene file's path under the target's folder: "addons/crtforge/<preset>.tscn".
std::string scene_path(const Preset& preset);

}  // namespace crtforge::godot
