#include "targets/godot/godot_scene.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/scene.hpp"
#include "crtforge/version.hpp"
#include "generator/manifest.hpp"
#include "targets/godot/godot_writer.hpp"

namespace crtforge::godot {

namespace {

using json = nlohmann::ordered_json;

constexpr const char* kFolder = "addons/crtforge/";

// The copy every history and feedback viewport draws with: the texel as it is, alpha included.
constexpr const char* kCopyShader =
    "shader_type canvas_item;\nrender_mode blend_disabled;\n\nvoid fragment() {\n\tCOLOR = texture(TEXTURE, UV);\n}\n";

std::string lut_path(const Preset& preset, const std::string& lut) {
    return std::string(kFolder) + "luts/" + preset.name + "." + lut + ".png";
}

// A string in Godot's text resource syntax.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

json texture_spec(const PassInput& input) {
    json spec;
    switch (input.from.kind) {
        case TextureSource::Kind::Original:
            spec["from"] = "original";
            spec["frames_back"] = input.from.frames_back;
            break;
        case TextureSource::Kind::Pass: spec["from"] = "pass"; break;
        case TextureSource::Kind::Feedback: spec["from"] = "feedback"; break;
        case TextureSource::Kind::Lut: spec["from"] = "lut"; break;
    }
    if (input.from.kind != TextureSource::Kind::Original) spec["name"] = input.from.name;
    spec["filter"] = filter_name(input.filter);
    spec["wrap"] = wrap_name(input.wrap);
    if (input.mipmap) spec["mipmap"] = true;
    return spec;
}

// The inputs a pass's shader reads: its main input, then the textures its variant declares.
std::vector<const PassInput*> read_inputs(const Variant& variant) {
    std::vector<const PassInput*> out{&variant.pass->inputs.front()};
    for (const std::string& name : variant.textures)
        if (const PassInput* input = variant.pass->find_input(name)) out.push_back(input);
    return out;
}

// What Godot 3 cannot do as the pass asks; said in the scene file's header (Godot 4 samples each
// extra texture with its own hints, so only the first two apply to it).
std::vector<std::string> scene_notes(const SceneTargetInput& in, int version) {
    std::vector<std::string> notes;
    std::map<std::string, std::pair<std::string, std::string>> first;  // texture -> (reader, filter/wrap)
    for (size_t i = 0; i < in.passes.size(); ++i) {
        const Pass& pass = *in.passes[i]->pass;
        const bool display = i + 1 == in.passes.size();
        if (pass.format == PixelFormat::Rgba32F && !display)
            notes.push_back("pass " + pass.alias + " stores 32-bit floats; Godot viewports cannot: it is stored as half float");
        if (!format_reduction(pass.format).empty() && !display)
            notes.push_back(fmt::format("pass {} stores {}; Godot viewports cannot: it is stored as half float, its shader reducing the "
                                        "output to what {} holds", pass.alias, pixel_format_name(pass.format), pixel_format_name(pass.format)));
        for (const PassInput* input : read_inputs(*in.passes[i])) {
            if (input->mipmap && input->from.kind != TextureSource::Kind::Lut)
                notes.push_back("pass " + pass.alias + " reads " + input->from.str() +
                                " with mipmaps; Godot viewports have none: level 0 is read (a LUT's chain is made)");
            if (version >= 4 && input != &pass.inputs.front()) continue;
            const std::string sampling = std::string(filter_name(input->filter)) + "/" + wrap_name(input->wrap);
            const std::string reader = "pass " + pass.alias + " (" + input->binding + ")";
            auto [it, fresh] = first.emplace(input->from.str(), std::make_pair(reader, sampling));
            if (!fresh && it->second.second != sampling && version < 4)
                notes.push_back(reader + " reads " + input->from.str() + " " + sampling + ", but Godot 3 sets sampling per texture: " +
                                it->second.first + " set it to " + it->second.second);
        }
    }
    return notes;
}

// Writes a Godot text scene: resources first, then nodes, in the syntax of format 2 (Godot 3) or
// format 3 (Godot 4).
class SceneWriter {
public:
    explicit SceneWriter(int version) : version_(version) {}

    std::string ext_resource(const std::string& type, const std::string& path) {
        const int id = static_cast<int>(ext_.size()) + 1;
        ext_.push_back(version_ >= 4 ? fmt::format("[ext_resource type=\"{}\" path=\"{}\" id=\"{}\"]", type, path, id)
                                     : fmt::format("[ext_resource path=\"{}\" type=\"{}\" id={}]", path, type, id));
        return version_ >= 4 ? fmt::format("ExtResource(\"{}\")", id) : fmt::format("ExtResource( {} )", id);
    }

    std::string sub_resource(const std::string& type, const std::vector<std::string>& properties) {
        const int id = static_cast<int>(subs_count_) + 1;
        ++subs_count_;
        std::string text = version_ >= 4 ? fmt::format("[sub_resource type=\"{}\" id=\"{}_{}\"]\n", type, type, id)
                                         : fmt::format("[sub_resource type=\"{}\" id={}]\n", type, id);
        for (const std::string& p : properties) text += p + "\n";
        subs_.push_back(text);
        return version_ >= 4 ? fmt::format("SubResource(\"{}_{}\")", type, id) : fmt::format("SubResource( {} )", id);
    }

    void node(const std::string& name, const std::string& type, const std::string& parent,
              const std::vector<std::string>& properties) {
        std::string text = "[node name=\"" + name + "\" type=\"" + type + "\"" + (parent.empty() ? "" : " parent=\"" + parent + "\"") + "]\n";
        for (const std::string& p : properties) text += p + "\n";
        nodes_.push_back(text);
    }

    std::string vector2(double x, double y, bool integer = false) const {
        if (version_ >= 4) return fmt::format("{}({}, {})", integer ? "Vector2i" : "Vector2", x, y);
        return fmt::format("Vector2( {}, {} )", x, y);
    }

    std::string text(const std::vector<std::string>& header) const {
        std::string out;
        for (const std::string& line : header) out += "; " + line + "\n";
        out += fmt::format("[gd_scene load_steps={} format={}]\n\n", ext_.size() + subs_.size() + 1, version_ >= 4 ? 3 : 2);
        for (const std::string& e : ext_) out += e + "\n";
        if (!ext_.empty()) out += "\n";
        for (const std::string& s : subs_) out += s + "\n";
        for (size_t i = 0; i < nodes_.size(); ++i) out += nodes_[i] + (i + 1 < nodes_.size() ? "\n" : "");
        return out;
    }

private:
    int version_;
    std::vector<std::string> ext_, subs_, nodes_;
    size_t subs_count_ = 0;
};

// Godot 3 draws its active viewports in the order of a sort whose comparison only knows "a
// viewport inside another" (VisualServerViewport's ViewportSort): siblings compare equal, and its
// introsort keeps their (tree) order only up to 16 elements; past that it swaps them each frame,
// so a pass reads another's output of an earlier frame or none (measured with Godot 3.2.3: a chain
// of copy passes draws right with 16 active viewports in all, black with 17). Every viewport of
// the game counts: the root, the one the game draws its own picture into, and the scene's passes
// and copies; so a scene may use 14.
constexpr size_t kGodot3OrderedViewports = 16, kGodot3GameViewports = 2;

Status check_godot3_viewport_count(const Preset& preset, size_t passes, size_t feedback, int history, int version) {
    const size_t needed = passes + feedback + static_cast<size_t>(history);
    if (version >= 4 || needed + kGodot3GameViewports <= kGodot3OrderedViewports) return Ok{};
    return make_error(fmt::format("needs {} viewports in Godot 3 ({} passes, {} feedback copies, {} history copies), but Godot 3 draws "
                                  "viewports in order only while a game has at most {} (it re-sorts more each frame, so passes read "
                                  "stale or empty outputs); {} are left beside the root and the game's own picture: export it for "
                                  "Godot 4, which orders any number",
                                  needed, passes, feedback, history, kGodot3OrderedViewports,
                                  kGodot3OrderedViewports - kGodot3GameViewports),
                      preset.where.file, preset.where.line, "godot3");
}

}  // namespace

OnePixelAxes one_pixel_axes(const Preset& preset, size_t pass_index) {
    OnePixelAxes out;
    if (pass_index + 1 >= preset.passes.size()) return out;  // the last pass draws the display
    const Pass& pass = preset.passes[pass_index];
    auto thin = [](const PassScale& s) { return s.type == PassScale::Type::Absolute && std::lround(s.factor) < 2; };
    out.x = thin(pass.scale_x);
    out.y = thin(pass.scale_y);
    return out;
}

OnePixelAxes one_pixel_axes(const Preset& preset, const TextureSource& from) {
    if (from.kind != TextureSource::Kind::Pass && from.kind != TextureSource::Kind::Feedback) return {};
    const Pass* pass = preset.find_pass(from.name);
    return pass ? one_pixel_axes(preset, static_cast<size_t>(pass - preset.passes.data())) : OnePixelAxes{};
}

std::string scene_path(const Preset& preset) { return std::string(kFolder) + preset.name + ".tscn"; }

Result<std::vector<OutputFile>> generate_scene(const SceneTargetInput& in, int version) {
    if (!in.preset || in.passes.empty() || in.passes.size() != in.outputs.size())
        return make_error("a scene needs every pass's variant and files");
    const Preset& preset = *in.preset;
    const bool v4 = version >= 4;
    std::vector<OutputFile> files;
    SceneWriter w(version);

    const std::string script = w.ext_resource("Script", std::string("res://") + kFolder + "crtforge_pipeline.gd");
    const std::string copy_shader = w.sub_resource("Shader", {"code = " + quoted(kCopyShader)});
    const std::string copy_material = w.sub_resource("ShaderMaterial", {"shader = " + copy_shader});

    // Sizes the scene opens with, for a picture of the preset's source size (320x240 when it has
    // none) on a 1280x960 display; the script resizes everything to the real ones.
    const PixelSize source{preset.scene.source_width ? preset.scene.source_width : 320,
                           preset.scene.source_height ? preset.scene.source_height : 240};
    const PixelRect screen = screen_rect(preset, {1280, 960}, source);
    const std::vector<PixelSize> sizes = pass_sizes(preset, source, {screen.width, screen.height});

    // The pipeline description the script reads, and the sets of copies it needs.
    json passes = json::array();
    std::vector<std::string> feedback;
    std::vector<std::string> materials;
    for (size_t i = 0; i < in.passes.size(); ++i) {
        const Variant& variant = *in.passes[i];
        const Pass& pass = *variant.pass;
        // Godot draws nothing into a viewport under 2 pixels: a program pass is drawn into 2 (see
        // one_pixel_axes); a pass of crtforge's own shaders, whose coordinates are the node's, is
        // refused rather than exported black.
        const OnePixelAxes thin = one_pixel_axes(preset, i);
        if (thin.any() && !variant.program_form())
            return make_error(fmt::format("pass {} is 1 pixel {} on {}; Godot draws nothing into a viewport under 2 pixels", pass.alias,
                                          thin.x ? "wide" : "tall", v4 ? "Godot 4" : "Godot 3"),
                              pass.where.file, pass.where.line, "scale");
        const OutputFile* shader = nullptr;
        for (const OutputFile& f : in.outputs[i]->files)
            if (f.manifest_role() == "shader") shader = &f;
        if (!shader) return make_error("pass " + pass.alias + " has no node-mode shader");
        std::vector<std::string> material = {"resource_local_to_scene = true",
                                             "shader = " + w.ext_resource("Shader", "res://" + shader->path)};
        for (const std::string& line : material_param_lines(variant, version)) material.push_back(line);
        materials.push_back(w.sub_resource("ShaderMaterial", material));

        json entry;
        entry["alias"] = pass.alias;
        entry["scale"] = {scale_type_name(pass.scale_x.type), pass.scale_x.factor, scale_type_name(pass.scale_y.type), pass.scale_y.factor};
        // Float only where the pass asks for it: Godot 3 draws 2D into a float (3D-usage HDR)
        // viewport with sRGB decoding of 8-bit textures, which would darken an imported source.
        entry["hdr"] = pass.format != PixelFormat::Rgba8;
        entry["input"] = texture_spec(pass.inputs.front());
        entry["textures"] = json::object();
        for (const PassInput* input : read_inputs(variant)) {
            if (input != &pass.inputs.front()) entry["textures"][input->binding] = texture_spec(*input);
            if (input->from.kind == TextureSource::Kind::Feedback &&
                std::find(feedback.begin(), feedback.end(), input->from.name) == feedback.end())
                feedback.push_back(input->from.name);
        }
        entry["frame_count"] = std::find(variant.builtins.begin(), variant.builtins.end(), Builtin::FrameCount) != variant.builtins.end();
        entry["frame_count_mod"] = pass.frame_count_mod;
        // A program pass (an imported RetroArch shader) gets its output and screen sizes as uniforms.
        if (variant.program_form()) entry["sizes"] = true;
        // The speed `seconds` is reduced by for the pass's hostTime: a uniform's name or the baked value.
        if (variant.angular_speed()) entry["time_speed"] = json(detail::time_reduce_by(variant));
        passes.push_back(std::move(entry));
    }
    std::sort(feedback.begin(), feedback.end());
    json luts = json::object();
    for (const LutSpec& lut : preset.luts) {
        auto data = in.lut_files.find(lut.name);
        if (data == in.lut_files.end()) return make_error("no file for LUT '" + lut.name + "'", lut.where.file, lut.where.line);
        files.push_back({ShaderStage::Fragment, ".png", data->second, "lut:" + lut.name, lut_path(preset, lut.name)});
        luts[lut.name] = {{"path", "res://" + lut_path(preset, lut.name)}, {"filter", filter_name(lut.filter)}, {"wrap", wrap_name(lut.wrap)}};
        // A LUT some pass reads through a mip chain is loaded with one (Image.generate_mipmaps).
        for (const Pass& pass : preset.passes)
            for (const PassInput& input : pass.inputs)
                if (input.mipmap && input.from.kind == TextureSource::Kind::Lut && input.from.name == lut.name) luts[lut.name]["mipmap"] = true;
    }
    const int history = preset.history_depth();
    if (auto s = check_godot3_viewport_count(preset, in.passes.size(), feedback.size(), history, version); !s.ok()) return s.error();
    auto index_of = [&](const std::string& alias) {
        for (size_t i = 0; i < preset.passes.size(); ++i)
            if (preset.passes[i].alias == alias) return i;
        return size_t{0};
    };

    const std::string dimension_x = v4 ? "offset_right" : "margin_right", dimension_y = v4 ? "offset_bottom" : "margin_bottom";
    auto viewport = [&](const std::string& name, PixelSize size, bool hdr, const std::string& child, const std::string& material) {
        std::vector<std::string> props;
        if (v4) {
            props = {"transparent_bg = true", std::string("use_hdr_2d = ") + (hdr ? "true" : "false"), "disable_3d = true",
                     "size = " + w.vector2(size.width, size.height, true), "render_target_update_mode = 4"};
        } else {
            // Godot 3 keeps floats only in a 3D-usage HDR viewport (RGBA16F); 2D usage is RGBA8.
            props = {"size = " + w.vector2(size.width, size.height), "transparent_bg = true",
                     std::string("hdr = ") + (hdr ? "true" : "false"), std::string("usage = ") + (hdr ? "3" : "0"),
                     "render_target_v_flip = true", "render_target_update_mode = 3"};
        }
        w.node(name, v4 ? "SubViewport" : "Viewport", ".", props);
        std::vector<std::string> rect = {"material = " + material, dimension_x + fmt::format(" = {}.0", size.width),
                                         dimension_y + fmt::format(" = {}.0", size.height), "mouse_filter = 2"};
        if (v4) {
            rect.push_back("expand_mode = 1");
        } else {
            rect.push_back("expand = true");
            rect.push_back("stretch_mode = 1");
        }
        w.node(child, "TextureRect", name, rect);
    };

    std::vector<std::string> root = {"anchor_right = 1.0", "anchor_bottom = 1.0", "mouse_filter = 2", "script = " + script};
    if (v4) root.insert(root.begin(), {"layout_mode = 3", "anchors_preset = 15"});
    root.push_back("pixel_aspect = " + w.vector2(preset.scene.pixel_aspect_x, preset.scene.pixel_aspect_y));
    root.push_back("screen_aspect = " + w.vector2(preset.scene.screen_aspect_x, preset.scene.screen_aspect_y));
    root.push_back(std::string("fit = ") + quoted(display_fit_name(preset.scene.fit)));
    root.push_back("passes = " + passes.dump());
    root.push_back("feedback = " + json(feedback).dump());
    root.push_back(fmt::format("history = {}", history));
    root.push_back("luts = " + luts.dump());
    w.node(preset.name, "Control", "", root);

    // Drawing order: feedback copies (last frame's outputs), the passes, the history (oldest first).
    for (const std::string& alias : feedback) {
        const size_t i = index_of(alias);
        viewport("previous-" + alias, sizes[i], passes[i]["hdr"].get<bool>(), "Copy", copy_material);
    }
    for (size_t i = 0; i < in.passes.size(); ++i)
        viewport(in.passes[i]->pass->alias, sizes[i], passes[i]["hdr"].get<bool>(), "Pass", materials[i]);
    for (int n = history; n >= 1; --n) viewport(fmt::format("history-{}", n), source, true, "Copy", copy_material);

    std::vector<std::string> background = {"anchor_right = 1.0", "anchor_bottom = 1.0", "mouse_filter = 2", "color = Color( 0, 0, 0, 1 )"};
    if (v4) {
        background = {"layout_mode = 1", "anchors_preset = 15", "anchor_right = 1.0", "anchor_bottom = 1.0", "mouse_filter = 2",
                      "color = Color(0, 0, 0, 1)"};
    }
    w.node("crt-background", "ColorRect", ".", background);
    std::vector<std::string> display = {"material = " + copy_material,
                                        (v4 ? "offset_left = " : "margin_left = ") + fmt::format("{}.0", screen.x),
                                        (v4 ? "offset_top = " : "margin_top = ") + fmt::format("{}.0", screen.y),
                                        dimension_x + fmt::format(" = {}.0", screen.x + screen.width),
                                        dimension_y + fmt::format(" = {}.0", screen.y + screen.height), "mouse_filter = 2"};
    if (v4) {
        display.push_back("texture_filter = 1");
        display.push_back("expand_mode = 1");
    } else {
        display.push_back("expand = true");
        display.push_back("stretch_mode = 1");
    }
    w.node("crt-display", "TextureRect", ".", display);

    std::vector<std::string> header = {
        fmt::format("crtforge {}: the {} scene of preset {} ({} pass{}). Instance it and set `source`", CRTFORGE_VERSION, v4 ? "Godot 4" : "Godot 3",
                    preset.name, in.passes.size(), in.passes.size() == 1 ? "" : "es"),
        "to the picture; crtforge_pipeline.gd explains the nodes. Generated: edit the crtforge preset, not this file."};
    for (const std::string& note : scene_notes(in, version)) header.push_back("Note: " + note + ".");
    files.push_back({ShaderStage::Fragment, ".tscn", w.text(header), "scene", scene_path(preset)});
    files.push_back({ShaderStage::Fragment, ".gd", pipeline_script(version), "script", std::string(kFolder) + "crtforge_pipeline.gd"});
    return files;
}

}  // namespace crtforge::godot
