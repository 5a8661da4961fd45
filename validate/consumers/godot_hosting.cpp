#include "validate/consumers/godot_hosting.hpp"

#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "targets/godot/godot_scene.hpp"

namespace crtforge::consumers {

Status pin_time(std::string& code) {
    static const std::regex time_token(R"(\bTIME\b)");
    if (!std::regex_search(code, time_token)) return Ok{};
    code = std::regex_replace(code, time_token, kPinnedTime);
    const size_t entry = code.find("void fragment()");
    if (entry == std::string::npos) return make_validation_error("the Godot shader has no fragment()");
    code.insert(entry, std::string("uniform float ") + kPinnedTime + ";\n");
    return Ok{};
}

namespace {

// The host has what the runners' scene mode drives: `passes` (its material is main/Pass's),
// `source`, `frame`, `playing`, `fit`, `seconds` (nothing reads it: the shader uses TIME).
constexpr const char* kHostScript3 = R"(extends Control
# crtforge validate's host: the exported shaders used as a user would without crtforge_pipeline.gd.
export var linear = true
var passes = [{"alias": "main"}]
var playing = false
var fit = "stretch"
var frame = 0
var seconds = 0.0
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

constexpr const char* kHostScript4 = R"(extends Control
# crtforge validate's host: the exported shaders used as a user would without crtforge_pipeline.gd.
@export var linear := true
var passes := [{"alias": "main"}]
var playing := false
var fit := "stretch"
var frame := 0
var seconds := 0.0
var source: Texture2D = null:
	set(texture):
		source = texture
		var picture = get_node_or_null("main/Picture")
		if picture == null:
			picture = get_node("main/Pass")
		picture.texture = texture
		picture.texture_filter = CanvasItem.TEXTURE_FILTER_LINEAR if linear else CanvasItem.TEXTURE_FILTER_NEAREST
)";

// What differs between Godot 3's and Godot 4's text scenes (format 2 and 3).
struct SceneDialect {
    int format;
    const char* ext_resource;  // {0} type, {1} path, {2} id
    const char* sub_resource;  // {0} id
    const char* reference;     // {0} "ExtResource" or "SubResource", {1} id
    const char* full_rect;     // a Control filling its parent, input passing through
    const char* stretch;       // a TextureRect's picture stretched over the rect
};

constexpr SceneDialect kScene3{2, "[ext_resource path=\"res://{1}\" type=\"{0}\" id={2}]\n", "[sub_resource type=\"ShaderMaterial\" id={0}]\n",
                               "{0}( {1} )", "anchor_right = 1.0\nanchor_bottom = 1.0\nmouse_filter = 2\n", "expand = true\n"};
constexpr SceneDialect kScene4{3, "[ext_resource type=\"{0}\" path=\"res://{1}\" id=\"{2}\"]\n", "[sub_resource type=\"ShaderMaterial\" id=\"{0}\"]\n",
                               "{0}(\"{1}\")",
                               "anchors_preset = 15\nanchor_right = 1.0\nanchor_bottom = 1.0\ngrow_horizontal = 2\ngrow_vertical = 2\nmouse_filter = 2\n",
                               "expand_mode = 1\n"};

std::string scene_text(const SceneDialect& d, const std::string& mode, const std::string& shader, const std::string& material, bool linear) {
    auto ref = [&](const char* kind, int id) { return fmt::format(fmt::runtime(d.reference), kind, id); };
    std::string resources = fmt::format(fmt::runtime(d.ext_resource), "Script", kHostScriptPath, 1), material_ref;
    if (mode == "material") {
        resources += fmt::format(fmt::runtime(d.ext_resource), "Material", material, 2);
        material_ref = ref("ExtResource", 2);
    } else {
        resources += fmt::format(fmt::runtime(d.ext_resource), "Shader", shader, 2) + "\n" + fmt::format(fmt::runtime(d.sub_resource), 1) +
                     "shader = " + ref("ExtResource", 2) + "\n";
        material_ref = ref("SubResource", 1);
    }
    std::string nodes = fmt::format("[node name=\"host\" type=\"Control\"]\n{}script = {}\nlinear = {}\n\n"
                                    "[node name=\"main\" type=\"Control\" parent=\".\"]\n{}\n",
                                    d.full_rect, ref("ExtResource", 1), linear ? "true" : "false", d.full_rect);
    if (mode == "screen")
        nodes += fmt::format("[node name=\"Picture\" type=\"TextureRect\" parent=\"main\"]\n{}{}\n"
                             "[node name=\"Pass\" type=\"ColorRect\" parent=\"main\"]\n{}material = {}\n",
                             d.full_rect, d.stretch, d.full_rect, material_ref);
    else
        nodes += fmt::format("[node name=\"Pass\" type=\"TextureRect\" parent=\"main\"]\n{}{}material = {}\n", d.full_rect, d.stretch,
                             material_ref);
    return fmt::format("[gd_scene load_steps=3 format={}]\n\n{}\n{}", d.format, resources, nodes);
}

}  // namespace

const char* host_script(int version) { return version == 3 ? kHostScript3 : kHostScript4; }

Result<std::string> host_scene(int version, const std::string& mode, const TargetOutput& files, bool linear) {
    if (mode != "defaults" && mode != "material" && mode != "screen")
        return make_error("unknown Godot host mode '" + mode + "' (defaults, material or screen)");
    std::string shader, screen, material;
    for (const OutputFile& f : files.files) {
        const std::string role = f.manifest_role();
        if (role == "shader") shader = f.path;
        if (role == "screenShader") screen = f.path;
        if (role == "material") material = f.path;
    }
    if (shader.empty() || screen.empty() || material.empty())
        return make_error(fmt::format("the Godot {} export lacks the node shader, screen shader or .tres material", version));
    const std::string& used = mode == "screen" ? screen : shader;
    return scene_text(version == 3 ? kScene3 : kScene4, mode, used, material, linear);
}

Result<std::map<std::string, std::string>> scene_project_files(int version, TargetId target,
                                                               const SceneRenderRequest& r, std::string& scene) {
    if (!r.preset || !r.passes || !r.outputs || r.outputs->size() != r.passes->size() || !r.source)
        return make_error(fmt::format("a Godot {} scene render needs the preset, its passes and their Godot {} files", version, version));
    const Preset& preset = *r.preset;
    std::map<std::string, std::string> files;
    // The export's files for this preset, as a user copies them into a project.
    for (const TargetOutput& pass : *r.outputs)
        for (const OutputFile& f : pass.files) {
            std::string data = f.data;
            if (f.is_shader())
                if (auto s = pin_time(data); !s.ok()) return s.error();
            files[f.path] = std::move(data);
        }
    if (r.host.empty()) {
        auto luts = lut_files(preset);
        if (!luts.ok()) return luts.error();
        auto made = generate_target_scene(target, preset, *r.passes, *r.outputs, luts.value());
        if (!made.ok()) return made.error();
        for (const OutputFile& f : made.value()) files[f.path] = f.data;
        scene = "res://" + godot::scene_path(preset);
        return files;
    }
    // The shaders used alone: a single pass that reads nothing but its picture.
    if (!preset.single_pass() || !r.passes->front().variant.textures.empty())
        return make_error("Godot host mode '" + r.host + "' needs a single-pass preset that reads only its picture");
    auto host = host_scene(version, r.host, r.outputs->front(), r.passes->front().variant.texture_filter("source") == Filter::Linear);
    if (!host.ok()) return host.error();
    // Named per mode and preset: a runner may cache scenes by path for its whole life.
    const std::string name = "crtforge_validation_" + r.host + "_" + preset.name + ".tscn";
    files[name] = host.value();
    files[kHostScriptPath] = host_script(version);
    scene = "res://" + name;
    return files;
}

}  // namespace crtforge::consumers
