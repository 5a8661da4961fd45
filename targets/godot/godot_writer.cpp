#include "targets/godot/godot_writer.hpp"

#include <fmt/format.h>

#include "targets/godot/godot_compiler.hpp"
#include "targets/godot/godot_scene.hpp"

namespace crtforge::godot {

namespace {

std::string literal(double v) { return fmt::format("{}", v); }

// A ShaderMaterial resource with every runtime param at the preset's value, for the node-mode
// shader or (`suffix` ".screen") the screen-mode one.
std::string material_resource(const Variant& variant, int version, const std::string& suffix = "") {
    const std::string shader_path = "res://addons/crtforge/" + variant.file_stem() + suffix + shader_extension(version);
    std::string out;
    if (version >= 4) {
        out += "[gd_resource type=\"ShaderMaterial\" load_steps=2 format=3]\n\n";
        out += "[ext_resource type=\"Shader\" path=\"" + shader_path + "\" id=\"1\"]\n\n";
        out += "[resource]\nshader = ExtResource(\"1\")\n";
    } else {
        out += "[gd_resource type=\"ShaderMaterial\" load_steps=2 format=2]\n\n";
        out += "[ext_resource path=\"" + shader_path + "\" type=\"Shader\" id=1]\n\n";
        out += "[resource]\nshader = ExtResource( 1 )\n";
    }
    for (const std::string& line : material_param_lines(variant, version)) out += line + "\n";
    return out;
}

// The screen-mode shader ready to drop in: a CanvasLayer above the game (layer 100) holding a
// full-rect ColorRect with the preset's screen material, ignoring the mouse so the GUI below still
// gets every click.
std::string overlay_scene(const Variant& variant, int version) {
    const std::string material = "res://addons/crtforge/" + variant.file_stem() + ".screen.tres";
    std::string out;
    if (version >= 4) {
        out += "[gd_scene load_steps=2 format=3]\n\n";
        out += "[ext_resource type=\"ShaderMaterial\" path=\"" + material + "\" id=\"1\"]\n\n";
        out += "[node name=\"CrtOverlay\" type=\"CanvasLayer\"]\nlayer = 100\n\n";
        out += "[node name=\"Screen\" type=\"ColorRect\" parent=\".\"]\nmaterial = ExtResource(\"1\")\n"
               "anchors_preset = 15\nanchor_right = 1.0\nanchor_bottom = 1.0\ngrow_horizontal = 2\ngrow_vertical = 2\nmouse_filter = 2\n";
    } else {
        out += "[gd_scene load_steps=2 format=2]\n\n";
        out += "[ext_resource path=\"" + material + "\" type=\"ShaderMaterial\" id=1]\n\n";
        out += "[node name=\"CrtOverlay\" type=\"CanvasLayer\"]\nlayer = 100\n\n";
        out += "[node name=\"Screen\" type=\"ColorRect\" parent=\".\"]\nmaterial = ExtResource( 1 )\n"
               "anchor_right = 1.0\nanchor_bottom = 1.0\nmouse_filter = 2\n";
    }
    return out;
}

std::string readme(int version) {
    const std::string ext = shader_extension(version);
    std::string out = fmt::format("# crtforge CRT shaders for Godot {}\n\n", version);
    out += "Copy `addons/crtforge/` into your project. Each preset comes as:\n\n";
    out += "- `<preset>.tscn`: the whole preset, ready to run. Instance it, set its `source` to your picture\n"
           "  (e.g. the ViewportTexture of the " + std::string(version >= 4 ? "SubViewport" : "Viewport") +
           " your game draws into, placed before this scene in the tree)\n"
           "  and size it like any Control (it fills its parent). It runs every pass in its own viewport,\n"
           "  keeps the previous frames that feedback passes read, loads the LUTs from `luts/`, places the\n"
           "  screen in the node per the preset's display fit (black around it) and advances `frame`\n"
           "  (the shaders' frameCount). `crtforge_pipeline.gd` is the script that drives it.\n";
    out += "- `<preset>" + ext + "` (`<preset>.<pass>" + ext + "` for each pass of a multi-pass preset): node mode.\n"
           "  Assign it (or `<preset>.tres`, a ShaderMaterial with the preset's values) to the node that shows\n"
           "  the picture: a TextureRect, a Sprite, or a node showing a viewport's texture. Set the node's\n"
           "  texture filter as the shader's header says.\n";
    out += "- `<preset>.screen" + ext + "`: screen mode, for single-pass presets. Put a ColorRect over the whole\n"
           "  screen (anchors: full rect) and give it a ShaderMaterial with this shader; it post-processes\n"
           "  everything drawn below it. `<preset>.screen.tres` is that material with the preset's values.\n";
    out += "- `<preset>.overlay.tscn`: the screen mode ready to drop in, for single-pass presets: instance it\n"
           "  anywhere in your main scene. A CanvasLayer (layer 100) holds a full-rect ColorRect with the\n"
           "  screen material; its mouse filter is Ignore, so the GUI below still gets every click.\n\n";
    out += "## Stretch modes\n\n"
           "- `display/window/stretch/mode` = `disabled` or `" + std::string(version >= 4 ? "canvas_items" : "2d") + "`: the overlay works as is;\n"
           "  the shader runs at the window's resolution.\n"
           "- `" + std::string(version >= 4 ? "viewport" : "viewport") + "` (the usual pixel-art setup, e.g. 256x224): the whole canvas, overlay\n"
           "  included, is drawn at the low resolution and scaled up, so scanlines become several pixels\n"
           "  tall and text shreds. Use the scene instead: set the stretch mode to `disabled` (or\n"
           "  `" + std::string(version >= 4 ? "canvas_items" : "2d") + "`), draw the game into a " + std::string(version >= 4 ? "SubViewport" : "Viewport") +
           " of the low resolution (filter off on its\n"
           "  texture" + std::string(version >= 4 ? "" : "; Render Target > V Flip on, as Godot 3 stores viewport pictures\n"
           "  bottom-up") + "), and show that texture through `<preset>.tscn` filling the window: the effect then runs\n"
           "  after the upscale, at the window's resolution, and the scene keeps the picture's aspect\n"
           "  (its display fit). Checked in a real Godot 3 at 256x224 x3: the scanlines are shaped per\n"
           "  device pixel and match crtforge's Vulkan render of the same picture.\n\n";
    out += "Every runtime parameter shows in the inspector with its range; baked parameters are constants.\n";
    if (version < 4)
        out += "\nGodot 3 sets filtering per texture, not per read: where two passes read one texture with\n"
               "different filters, the scene file's header says which one applies.\n"
               "\nThe shaders need the GLES3 renderer (they read dFdx, which GLES2 lacks); under GLES2 the scene's\n"
               "script reports it as an error.\n";
    return out;
}

}  // namespace

std::vector<std::string> material_param_lines(const Variant& variant, int version) {
    std::vector<std::string> lines;
    const char* key = version >= 4 ? "shader_parameter/" : "shader_param/";
    for (const VariantParam* p : variant.uniforms()) {
        std::string value;
        if (auto d = std::get_if<double>(&p->value)) value = literal(*d);
        else if (auto i = std::get_if<int64_t>(&p->value)) value = std::to_string(*i);
        else if (auto c = std::get_if<Color>(&p->value))
            value = version >= 4 ? fmt::format("Color({}, {}, {}, 1)", literal((*c)[0]), literal((*c)[1]), literal((*c)[2]))
                                 : fmt::format("Color( {}, {}, {}, 1 )", literal((*c)[0]), literal((*c)[1]), literal((*c)[2]));
        else continue;
        lines.push_back(key + p->spec->name + " = " + value);
    }
    return lines;
}

const char* shader_extension(int version) { return version >= 4 ? ".gdshader" : ".shader"; }

Result<std::string> generate_shader(const TargetInput& input, const Options& options) {
    try {
        GodotCompiler compiler(*input.fragment, *input.variant, options);
        return compiler.compile_godot();
    } catch (const std::exception& e) {
        return make_validation_error(fmt::format("SPIRV-Cross cannot express the fragment shader in Godot {}: {}",
                                                 options.godot_version, e.what()));
    }
}

Result<TargetOutput> generate(const TargetInput& input, int version) {
    const std::string preset = input.variant->file_stem();
    const std::string ext = shader_extension(version);
    TargetOutput out;
    auto node = generate_shader(input, {version, Mode::NodeTexture});
    if (!node.ok()) return node.error();
    auto screen = generate_shader(input, {version, Mode::Screen});
    if (!screen.ok()) return screen.error();
    out.files.push_back({ShaderStage::Fragment, ext, node.value(), "shader", "addons/crtforge/" + preset + ext});
    out.files.push_back({ShaderStage::Fragment, ".screen" + ext, screen.value(), "screenShader",
                         "addons/crtforge/" + preset + ".screen" + ext});
    out.files.push_back({ShaderStage::Fragment, ".tres", material_resource(*input.variant, version), "material",
                         "addons/crtforge/" + preset + ".tres"});
    if (input.variant->preset->single_pass()) {
        out.files.push_back({ShaderStage::Fragment, ".screen.tres", material_resource(*input.variant, version, ".screen"),
                             "screenMaterial", "addons/crtforge/" + preset + ".screen.tres"});
        out.files.push_back({ShaderStage::Fragment, ".overlay.tscn", overlay_scene(*input.variant, version), "overlay",
                             "addons/crtforge/" + preset + ".overlay.tscn"});
    }
    out.files.push_back({ShaderStage::Fragment, ".md", readme(version), "readme", "addons/crtforge/README.md"});
    out.bindings.push_back({"source", "node mode: the node's TEXTURE at UV; screen mode: " +
                                          std::string(version >= 4 ? "screen_texture (hint_screen_texture)" : "SCREEN_TEXTURE") + " at SCREEN_UV"});
    out.bindings.push_back({"params", "one `uniform` per runtime param (inspector hints), set with set_shader_param"});
    return out;
}

std::vector<TargetInfo> records() {
    return {
        {TargetId::Godot4, "godot4", "Godot 4 canvas_item .gdshader + ShaderMaterial (node and screen modes)",
         {"shader", "screenShader"}, "godot4-shim", [](const TargetInput& in) { return generate(in, 4); },
         "godot4/spirv-cross-2021.01.15/v4", [](const SceneTargetInput& in) { return generate_scene(in, 4); }},
        {TargetId::Godot3, "godot3", "Godot 3 canvas_item .shader + ShaderMaterial (node and screen modes)",
         {"shader", "screenShader"}, "godot3", [](const TargetInput& in) { return generate(in, 3); },
         "godot3/spirv-cross-2021.01.15/v5", [](const SceneTargetInput& in) { return generate_scene(in, 3); }},
    };
}

}  // namespace crtforge::godot
