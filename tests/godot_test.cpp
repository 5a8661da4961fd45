// The Godot targets: dialect rules, inspector hints, both modes, materials, and that the Godot 3 and
// Godot 4 outputs differ only where the dialects differ.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "crtforge/files.hpp"
#include "crtforge/value.hpp"
#include "targets/float_literals.hpp"
#include "crtforge/runtime/godot3_engine.hpp"
#include "crtforge/validate/target_render.hpp"
#include "validate/consumers/consumer.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

const OutputFile& file(const TargetOutput& out, const std::string& role) { return test::file_with_role(out, role); }

TargetOutput emit(const std::string& preset, TargetId target, size_t pass = 0) {
    const TemplateLibrary& lib = test::shipped_library();
    auto c = compile_variant(lib, *lib.find_preset(preset), {}, Cache(), pass);
    REQUIRE(c.ok());
    auto out = emit_target(c.value(), target, Cache());
    REQUIRE(out.ok());
    return out.value();
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

}  // namespace

TEST_CASE("Godot 4 shaders are canvas_item code with no GLSL plumbing", "[godot]") {
    for (const Preset& p : test::shipped_library().presets())
      for (size_t pass = 0; pass < p.passes.size(); ++pass) {
        INFO(p.name << " pass " << p.passes[pass].alias);
        const TargetOutput out = emit(p.name, TargetId::Godot4, pass);
        for (const char* role : {"shader", "screenShader"}) {
            const std::string& text = file(out, role).data;
            CHECK_THAT(text, Catch::Contains("shader_type canvas_item;"));
            CHECK_THAT(text, Catch::Contains("void fragment()"));
            CHECK_THAT(text, Catch::Contains("COLOR = "));
            for (const char* banned : {"#version", "layout(", "precision ", "\nin ", "\nout ", "uniform CrtParams", "void main"})
                CHECK_THAT(text, !Catch::Contains(banned));
        }
        CHECK_THAT(file(out, "shader").data, Catch::Contains("UV"));
        if (!p.passes[pass].stages.empty()) {
            const std::string filter = filter_name(p.passes[pass].inputs.front().filter);
            CHECK_THAT(file(out, "screenShader").data,
                       Catch::Contains("uniform sampler2D screen_texture : hint_screen_texture, filter_" + filter + ", repeat_disable;"));
            CHECK_THAT(file(out, "screenShader").data, Catch::Contains("SCREEN_UV"));
        }
    }
}

TEST_CASE("every runtime param is an inspector uniform with range, step and default", "[godot]") {
    const TemplateLibrary& lib = test::shipped_library();
    CompiledVariant c = test::compile_or_fail(lib, "crt-pulse");
    const std::string text = file(emit("crt-pulse", TargetId::Godot4), "shader").data;
    for (const VariantParam* p : c.variant.uniforms()) {
        INFO(p->spec->name);
        if (p->spec->type == ParamType::Color)
            CHECK_THAT(text, Catch::Contains("uniform vec3 " + p->spec->name + " : source_color = vec3("));
        else
            CHECK(std::regex_search(text, std::regex("uniform float " + p->spec->name + R"( : hint_range\([-0-9.]+, [-0-9.]+, [0-9.e-]+\) = [-0-9.]+;)")));
    }
    CHECK_THAT(text, Catch::Contains("uniform float maskSize : hint_range(2.0, 24.0, 0.5) = 8.0;"));
    // Baked params are constants folded into the code, never uniforms.
    CHECK_THAT(text, !Catch::Contains("uniform float maskBorder"));
    // TIME wraps: the header says so and the fallback rounds the pulse speed to whole turns per wrap.
    CHECK_THAT(text, Catch::Contains("uses TIME, which wraps at rendering/limits/time/time_rollover_secs"));
    CHECK_THAT(text, Catch::Contains("round(pulseSpeed * 3600.0"));
    CHECK_THAT(file(emit("quiet-frame", TargetId::Godot4), "shader").data, !Catch::Contains("TIME"));
}

namespace {

// The end of the parenthesised group that starts at `from` (just after its '('): the ')' closing it.
size_t group_end(const std::string& line, size_t from) {
    int depth = 0;
    for (size_t i = from; i < line.size(); ++i) {
        if (line[i] == '(') ++depth;
        if (line[i] == ')' && depth-- == 0) return i;
    }
    FAIL("unbalanced parentheses in " << line);
    return line.size();
}

// Godot 3's screen reads, textureLod(SCREEN_TEXTURE, crt_flip_y(P), L), without the flip.
std::string unflip_screen_reads(std::string line) {
    static const std::string read = "textureLod(SCREEN_TEXTURE, crt_flip_y(";
    for (size_t at = line.find(read); at != std::string::npos; at = line.find(read, at + 1)) {
        const size_t open = at + read.size();
        const size_t close = group_end(line, open);
        line.erase(close, 1);
        line.erase(open - 11, 11);  // "crt_flip_y("
    }
    return line;
}

// Godot 4's texture(screen_texture, P) as the level-0 read Godot 3 makes of it.
std::string level_zero_reads(std::string line) {
    static const std::string read = "texture(screen_texture, ";
    for (size_t at = line.find(read); at != std::string::npos; at = line.find(read, at + 1)) {
        const size_t close = group_end(line, at + 8);
        line.insert(close, ", 0.0");
        line.replace(at, 8, "textureLod(");
    }
    return line;
}

// Every float literal of `line` (not in a uniform's default, which both keep as written) as the
// shortest text of the float32 it denotes.
std::string as_float32_literals(const std::string& line) {
    if (line.rfind("uniform ", 0) == 0) return line;
    return detail::rewrite_float_literals(line, [](const std::string& token, const std::string& suffix) {
        return suffix.empty() ? float_literal(std::strtof(token.c_str(), nullptr)) : token + suffix;
    });
}

}  // namespace

TEST_CASE("Godot 3 and Godot 4 outputs differ only where the dialects differ", "[godot]") {
    // Godot 3: hint_color on vec4 (read back as .rgb), SCREEN_TEXTURE instead of a hinted sampler,
    // and the version in the header. Everything else must be the same text.
    for (const Preset& p : test::shipped_library().presets())
      for (size_t pass = 0; pass < p.passes.size(); ++pass) {
        for (const char* role : {"shader", "screenShader"}) {
            INFO(p.name << " pass " << p.passes[pass].alias << " " << role);
            auto g4 = lines_of(file(emit(p.name, TargetId::Godot4, pass), role).data);
            auto g3 = lines_of(file(emit(p.name, TargetId::Godot3, pass), role).data);
            // Godot 3's colours are vec4 hint_color uniforms, read back as .rgb.
            std::vector<std::string> colours;
            static const std::regex colour_uniform(R"(uniform vec4 (\w+) : hint_color)");
            for (const std::string& line : g3) {
                std::smatch m;
                if (std::regex_search(line, m, colour_uniform)) colours.push_back(m[1]);
            }
            std::vector<std::string> normalised;
            for (std::string line : g3) {
                // Godot 3's screen counts rows from the bottom: crt_flip_y around SCREEN_UV and every
                // screen read, which reads the full-resolution level (textureLod ..., 0.0).
                if (line.rfind("// Godot 3's SCREEN_UV", 0) == 0 || line.rfind("vec2 crt_flip_y(", 0) == 0) continue;
                // Setup notes name each version's own nodes and settings.
                if (line.rfind("// Node mode:", 0) == 0 || line.rfind("// turn the texture's Filter", 0) == 0 ||
                    line.rfind("// Needs the GLES3 renderer", 0) == 0)
                    continue;
                line = unflip_screen_reads(line);
                line = std::regex_replace(line, std::regex(R"(crt_flip_y\(SCREEN_UV\))"), "SCREEN_UV");
                line = std::regex_replace(line, std::regex(R"(uniform vec4 (\w+) : hint_color = vec4\(([^,]+), ([^,]+), ([^,]+), 1\.0\);)"),
                                          "uniform vec3 $1 : source_color = vec3($2, $3, $4);");
                for (const std::string& c : colours) line = std::regex_replace(line, std::regex("\\b" + c + "\\.rgb\\b"), c);
                line = std::regex_replace(line, std::regex(R"(\bSCREEN_TEXTURE\b)"), "screen_texture");
                line = std::regex_replace(line, std::regex("// Godot 3 canvas_item"), "// Godot 4 canvas_item");
                // Godot 3 sets a texture's filter and repeat on the texture, Godot 4 in the uniform's hints.
                line = std::regex_replace(line, std::regex(R"( \(set its filter and repeat flags on the texture\)$)"), "");
                // Godot 3's for loops need an increment: a zero one where SPIR-V steps inside the body.
                line = std::regex_replace(line, std::regex(R"(for \(int crtforge_loop\d+ = 0; ([^;]*); crtforge_loop\d+ \+= 0\))"), "for (; $1; )");
                if (line.find("for (; true; )") != std::string::npos) line.replace(line.find("for (; true; )"), 14, "for (;;)");  // all three parts
                line = std::regex_replace(line, std::regex(R"(for \(((?:int|uint|float) (\w+) = [^;]*); ([^;]*); \2 \+= 0(?:\.0|u)?\))"), "for ($1; $3; )");
                // Godot 3 gets a float literal six printed digits would change as its bits: both sides'
                // literals are compared as the float32 they denote.
                static const std::regex bits(R"(uintBitsToFloat\(uint\((-?\d+)\)\))");
                for (std::smatch m; std::regex_search(line, m, bits);)
                    line.replace(static_cast<size_t>(m.position(0)), static_cast<size_t>(m.length(0)),
                                 float_literal(std::bit_cast<float>(static_cast<int32_t>(std::stol(m[1].str())))));
                normalised.push_back(as_float32_literals(line));
            }
            // Godot 4 declares the screen texture; Godot 3 has it built in.
            g4.erase(std::remove_if(g4.begin(), g4.end(),
                                    [](const std::string& l) {
                                        return l.find("hint_screen_texture") != std::string::npos || l.rfind("// Node mode:", 0) == 0 ||
                                               l.rfind("// set the node's texture_filter", 0) == 0 || l.rfind("group_uniforms", 0) == 0;
                                    }),
                     g4.end());
            for (std::string& line : g4) {
                line = std::regex_replace(line, std::regex(R"(^(uniform sampler2D \w+) : filter_\w+, repeat_\w+;$)"), "$1;");
                line = as_float32_literals(level_zero_reads(line));
            }
            // Blank runs left where lines were dropped count as one.
            auto collapse = [](std::vector<std::string>& v) {
                v.erase(std::unique(v.begin(), v.end(), [](const std::string& a, const std::string& b) { return a.empty() && b.empty(); }),
                        v.end());
            };
            collapse(normalised);
            collapse(g4);
            CHECK(normalised == g4);
        }
    }
}

TEST_CASE("materials carry the preset's values in each version's resource format", "[godot]") {
    const std::string g4 = file(emit("quiet-frame", TargetId::Godot4), "material").data;
    CHECK_THAT(g4, Catch::StartsWith("[gd_resource type=\"ShaderMaterial\" load_steps=2 format=3]"));
    CHECK_THAT(g4, Catch::Contains("path=\"res://addons/crtforge/quiet-frame.gdshader\""));
    CHECK_THAT(g4, Catch::Contains("shader_parameter/curvature = 0.1\n"));
    CHECK_THAT(g4, Catch::Contains("shader_parameter/bezelColor = Color(0, 0, 0, 1)\n"));
    const std::string g3 = file(emit("quiet-frame", TargetId::Godot3), "material").data;
    CHECK_THAT(g3, Catch::Contains("format=2"));
    CHECK_THAT(g3, Catch::Contains("res://addons/crtforge/quiet-frame.shader"));
    CHECK_THAT(g3, Catch::Contains("shader_param/bloomStrength = 1.4\n"));
    const TargetOutput out = emit("webgpu-post", TargetId::Godot4);
    CHECK(file(out, "shader").path == "addons/crtforge/webgpu-post.gdshader");
    CHECK(file(out, "readme").path == "addons/crtforge/README.md");
}

TEST_CASE("Godot 4 groups each stage's params under its own inspector heading", "[godot]") {
    const std::vector<std::string> g4 = lines_of(file(emit("classic", TargetId::Godot4), "shader").data);
    std::vector<std::string> groups;
    std::string current;
    for (const std::string& line : g4) {
        if (line.rfind("group_uniforms", 0) == 0) {
            groups.push_back(line);
            current = line;
        }
        // Each param sits in its own stage's group: its comment names the stage.
        if (line.rfind("uniform float", 0) == 0 || line.rfind("uniform vec3", 0) == 0) CHECK(current != "group_uniforms;");
    }
    CHECK(groups == std::vector<std::string>{"group_uniforms curvature;", "group_uniforms aberration;", "group_uniforms scanlines;",
                                             "group_uniforms mask;", "group_uniforms vignette;", "group_uniforms;"});
    CHECK(consume_output(TargetId::Godot4, file(emit("classic", TargetId::Godot4), "shader")).ok());
    // Godot 3 has no groups, and its check refuses one.
    const OutputFile g3 = file(emit("classic", TargetId::Godot3), "shader");
    CHECK(g3.data.find("group_uniforms") == std::string::npos);
    OutputFile grouped = g3;
    grouped.data.replace(grouped.data.find("uniform float curvature"), 0, "group_uniforms curvature;\n");
    auto refused = consume_output(TargetId::Godot3, grouped);
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().message, Catch::Contains("Godot 4 syntax"));
}

TEST_CASE("the shim rejects what is not a crtforge canvas_item shader", "[godot][errors]") {
    OutputFile f{ShaderStage::Fragment, ".gdshader", "shader_type spatial;\nvoid fragment() {}\n", "shader", ""};
    auto r = consume_output(TargetId::Godot4, f);
    REQUIRE_FALSE(r.ok());
    CHECK_THAT(r.error().message, Catch::Contains("canvas_item"));
    f.data = "shader_type canvas_item;\nvoid fragment() { COLOR = vec4(undefinedThing); }\n";
    r = consume_output(TargetId::Godot4, f);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().kind == ErrorKind::Validation);
    CHECK_THAT(r.error().message, Catch::Contains("undefinedThing"));
}

TEST_CASE("the TIME-wrap rule follows the spec's angular_speed role, not a param's name", "[godot]") {
    test::ScratchTemplates scratch;
    auto rename = [&](const std::string& rel) {
        std::string text = scratch.read(rel);
        for (size_t at = text.find("pulseSpeed"); at != std::string::npos; at = text.find("pulseSpeed", at))
            text.replace(at, 10, "scrollRate");
        scratch.write(rel, text);
    };
    for (const char* rel : {"stages/glow.toml", "stages/glow.glsl", "presets/crt-pulse.toml"}) rename(rel);
    auto emit_shader = [&]() {
        auto lib = scratch.load();
        REQUIRE(lib.ok());
        CompiledVariant c = test::compile_or_fail(*lib.value(), "crt-pulse");
        auto out = emit_target(c, TargetId::Godot4, Cache());
        REQUIRE(out.ok());
        return file(out.value(), "shader").data;
    };
    const std::string renamed = emit_shader();
    CHECK_THAT(renamed, Catch::Contains("round(scrollRate * 3600.0 / 6.28318530717959)"));
    CHECK_THAT(renamed, Catch::Contains("// seconds reduced modulo 2*pi/scrollRate in double precision."));
    CHECK_THAT(renamed, Catch::Contains("uniform float hostTime = -1.0;"));

    // Without the role the speed is just a number: TIME goes in as it is.
    std::string spec = scratch.read("stages/glow.toml");
    spec.erase(spec.find("role = \"angular_speed\"\n"), std::string("role = \"angular_speed\"\n").size());
    scratch.write("stages/glow.toml", spec);
    const std::string plain = emit_shader();
    CHECK_THAT(plain, !Catch::Contains("round(scrollRate"));
    CHECK_THAT(plain, Catch::Contains("TIME * scrollRate"));
    CHECK_THAT(plain, !Catch::Contains("hostTime"));
}

TEST_CASE("each Godot version's setup notes use that version's names, and Godot 3 states its renderer", "[godot]") {
    const std::string g4 = file(emit("classic", TargetId::Godot4, 0), "shader").data;
    const std::string g3 = file(emit("classic", TargetId::Godot3, 0), "shader").data;
    CHECK_THAT(g4, Catch::Contains("Sprite2D") && Catch::Contains("SubViewport") && Catch::Contains("texture_filter to Linear"));
    CHECK_THAT(g3, Catch::Contains("Sprite, a Viewport") && !Catch::Contains("Sprite2D") && !Catch::Contains("SubViewport"));
    CHECK_THAT(g3, Catch::Contains("Filter flag on") && Catch::Contains("Needs the GLES3 renderer"));
    // The nearest-filtered palette presets say so.
    CHECK_THAT(file(emit("atari-16", TargetId::Godot3, 0), "shader").data, Catch::Contains("Filter flag off"));
}

TEST_CASE("the overlay scene post-processes the screen in a real Godot 3 and lets clicks through", "[godot][godot3][overlay]") {
    // A project as a user's: a picture (white left half, black right half), a Button, and the
    // exported overlay instanced on top; it prints pixels of its own window and whether the click
    // on the button went through the overlay.
    test::TempDir project;
    auto exported = test::run_crtforge("--no-cache export -q --preset classic --target godot3 --out " + (project / "export"));
    REQUIRE(exported.exit_code == 0);
    std::filesystem::rename(project / "export/godot3/addons", project / "addons");
    REQUIRE(write_file_atomic(project / "project.godot",
                              "config_version=4\n\n[application]\nrun/main_scene=\"res://main.tscn\"\n\n[display]\n"
                              "window/size/width=320\nwindow/size/height=240\n")
                .ok());
    REQUIRE(write_file_atomic(project / "main.gd", R"(extends Node2D
var clicked = false
func _ready():
	add_child(load("res://addons/crtforge/classic.overlay.tscn").instance())
	$Button.connect("pressed", self, "_on_pressed")
	yield(get_tree(), "idle_frame")
	yield(VisualServer, "frame_post_draw")
	yield(VisualServer, "frame_post_draw")
	var img = get_viewport().get_texture().get_data()
	img.flip_y()
	img.lock()
	var c = img.get_pixel(80, 120)
	var d = img.get_pixel(240, 120)
	var e = img.get_pixel(1, 1)
	print("WHITE %f %f %f" % [c.r, c.g, c.b])
	print("BLACK %f %f %f" % [d.r, d.g, d.b])
	print("CORNER %f %f %f" % [e.r, e.g, e.b])
	for pressed in [true, false]:
		var ev = InputEventMouseButton.new()
		ev.button_index = BUTTON_LEFT
		ev.position = Vector2(40, 220)
		ev.global_position = ev.position
		ev.pressed = pressed
		get_tree().input_event(ev)
	yield(get_tree(), "idle_frame")
	print("CLICKED %s" % str(clicked))
	get_tree().quit()
func _on_pressed():
	clicked = true
)").ok());
    REQUIRE(write_file_atomic(project / "main.tscn", R"([gd_scene load_steps=2 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[node name="Main" type="Node2D"]
script = ExtResource( 1 )

[node name="White" type="ColorRect" parent="."]
margin_right = 160.0
margin_bottom = 240.0
color = Color( 1, 1, 1, 1 )

[node name="Black" type="ColorRect" parent="."]
margin_left = 160.0
margin_right = 320.0
margin_bottom = 240.0
color = Color( 0, 0, 0, 1 )

[node name="Button" type="Button" parent="."]
margin_left = 10.0
margin_top = 200.0
margin_right = 90.0
margin_bottom = 235.0
)").ok());
    auto log = run_godot3_project(project.path());
    REQUIRE(log.ok());
    auto rgb = [&](const std::string& label) {
        std::smatch m;
        const std::regex line(label + R"( ([0-9.]+) ([0-9.]+) ([0-9.]+))");
        REQUIRE(std::regex_search(log.value(), m, line));
        return std::array<double, 3>{std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
    };
    // The white half comes out shaded by the preset (scanline, mask, vignette), neither untouched
    // nor blanked; the corner is the bezel's black; the click reached the button below.
    const auto white = rgb("WHITE");
    CHECK(white[0] < 0.99);
    CHECK(white[0] > 0.5);
    CHECK(white[1] < white[0]);  // classic's aperture mask dims two channels per column
    const auto corner = rgb("CORNER");
    CHECK(corner[0] + corner[1] + corner[2] == 0.0);
    CHECK_THAT(log.value(), Catch::Contains("CLICKED True"));
}

TEST_CASE("under viewport stretch the scene runs the effect after a x3 upscale, at device pixels like Vulkan", "[godot][godot3][stretch]") {
    // The addon README's setup for the usual pixel-art project: the game draws into a 256x224
    // Viewport (V Flip on), the window is x3 (768x672), and <preset>.tscn shows its texture filling
    // the window. The scanlines must then be shaped per device pixel (the shader at 768x672), not
    // per game pixel in blocks of 3, and match crtforge's Vulkan render of the same picture.
    constexpr int kGameW = 256, kGameH = 224, kScale = 3, kColumn = 385;  // the middle of game column 128
    test::TempDir project;
    auto exported = test::run_crtforge("--no-cache export -q --preset classic --target godot3 --out " + (project / "export"));
    REQUIRE(exported.exit_code == 0);
    std::filesystem::rename(project / "export/godot3/addons", project / "addons");
    REQUIRE(write_file_atomic(project / "project.godot",
                              fmt::format("config_version=4\n\n[application]\nrun/main_scene=\"res://main.tscn\"\n\n[display]\n"
                                          "window/size/width={}\nwindow/size/height={}\nwindow/stretch/mode=\"disabled\"\n",
                                          kGameW * kScale, kGameH * kScale)).ok());
    REQUIRE(write_file_atomic(project / "main.gd", fmt::format(R"(extends Control
func _ready():
	var crt = load("res://addons/crtforge/classic.tscn").instance()
	add_child(crt)
	crt.source = $Game.get_texture()
	for i in range(4):
		yield(VisualServer, "frame_post_draw")
	var img = get_viewport().get_texture().get_data()
	img.flip_y()
	img.lock()
	print("SIZE %d %d" % [img.get_width(), img.get_height()])
	for y in range(img.get_height()):
		var c = img.get_pixel({}, y)
		print("ROW %d %f %f %f" % [y, c.r, c.g, c.b])
	get_tree().quit()
)", kColumn)).ok());
    REQUIRE(write_file_atomic(project / "main.tscn", fmt::format(R"([gd_scene load_steps=2 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[node name="Main" type="Control"]
anchor_right = 1.0
anchor_bottom = 1.0
script = ExtResource( 1 )

[node name="Game" type="Viewport" parent="."]
size = Vector2( {0}, {1} )
usage = 0
render_target_update_mode = 3
render_target_v_flip = true

[node name="White" type="ColorRect" parent="Game"]
margin_right = {0}.0
margin_bottom = {2}.0
color = Color( 1, 1, 1, 1 )

[node name="Grey" type="ColorRect" parent="Game"]
margin_top = {2}.0
margin_right = {0}.0
margin_bottom = {1}.0
color = Color( 0.5, 0.5, 0.5, 1 )
)", kGameW, kGameH, kGameH / 2)).ok());
    auto log = run_godot3_project(project.path());
    REQUIRE(log.ok());
    REQUIRE_THAT(log.value(), Catch::Contains(fmt::format("SIZE {} {}", kGameW * kScale, kGameH * kScale)));
    std::vector<std::array<float, 3>> godot(kGameH * kScale);
    static const std::regex row(R"(ROW (\d+) ([0-9.]+) ([0-9.]+) ([0-9.]+))");
    size_t rows = 0;
    for (auto it = std::sregex_iterator(log.value().begin(), log.value().end(), row); it != std::sregex_iterator(); ++it, ++rows)
        godot.at(std::stoul((*it)[1])) = {std::stof((*it)[2]), std::stof((*it)[3]), std::stof((*it)[4])};
    REQUIRE(rows == godot.size());

    // The same preset on Vulkan at the window's size, from the same game picture: the top half
    // white, the bottom half grey (so a picture upside down shows too).
    Image white = Image::make(kGameW, kGameH);
    for (int y = 0; y < kGameH; ++y)
        for (int x = 0; x < kGameW; ++x) {
            const float v = y < kGameH / 2 ? 1.0f : 0.5f;
            white.set_pixel(x, y, {v, v, v, 1.0f});
        }
    const CompiledVariant compiled = test::compile_or_fail(test::shipped_library(), "classic");
    TargetRenderRequest r;
    r.compiled = &compiled;
    r.target = TargetId::Spirv;
    r.input = white;
    r.width = kGameW * kScale;
    r.height = kGameH * kScale;
    static TargetRenderer renderer;
    auto vulkan = renderer.render(r);
    REQUIRE(vulkan.ok());

    double worst = 0.0;
    int varying_groups = 0;
    for (int y = 0; y < kGameH * kScale; ++y) {
        const auto v = vulkan.value().pixel(kColumn, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(double(godot[size_t(y)][size_t(c)]) - v[size_t(c)]));
    }
    // Within the 3 device rows of one game row the brightness changes (a shader run at 256x224
    // and scaled up would give 3 equal rows).
    for (int g = 0; g < kGameH; ++g) {
        const float a = godot[size_t(g * kScale)][0], b = godot[size_t(g * kScale + 1)][0], c = godot[size_t(g * kScale + 2)][0];
        varying_groups += std::max({a, b, c}) - std::min({a, b, c}) > 0.02f;  // 8-bit steps are 0.004
    }
    INFO("max |Godot - Vulkan| over column " << kColumn << ": " << worst << "; game rows whose 3 device rows differ: " << varying_groups);
    CHECK(worst < 0.02);
    CHECK(varying_groups > kGameH * 9 / 10);
}

TEST_CASE("Godot 3 compile checks run in the real engine, not only the shim", "[godot][godot3]") {
    // An exported node shader passes; the same with a hint Godot 3 does not have is refused by Godot
    // itself (the shim reads Godot's builtins, not its hint grammar).
    auto out = emit("classic", TargetId::Godot3, 0);
    OutputFile shader = file(out, "shader");
    ConsumerEngines engines(EngineOptions{});
    CHECK(godot3_consumer().compile(shader, engines).ok());
    const size_t at = shader.data.find(": hint_range(");
    REQUIRE(at != std::string::npos);
    shader.data.replace(at, 13, ": hint_nonsense(");
    auto refused = godot3_consumer().compile(shader, engines);
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().message, Catch::Contains("Godot 3 rejected the shader"));
}

TEST_CASE("real Godot 3 accepts the Godot 3 shader of every snapshot construct (loops with no head test too)", "[godot][godot3]") {
    // The snapshot library holds one construct family per preset (loops SPIRV-Cross writes as
    // `for (;;)`, loop-carried values, int switches): their exported Godot 3 shaders, compiled by
    // the engine itself.
    const std::string dir = std::string(CRTFORGE_SOURCE_DIR) + "/tests/snapshots/expected/godot3/addons/crtforge";
    ConsumerEngines engines(EngineOptions{});
    size_t compiled = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".shader") continue;
        OutputFile shader;
        shader.path = entry.path().filename().string();
        shader.data = read_text_file(entry.path().string()).value();
        INFO(shader.path);
        auto result = godot3_consumer().compile(shader, engines);
        CHECK(result.ok());
        if (!result.ok()) UNSCOPED_INFO(result.error().message);
        ++compiled;
    }
    CHECK(compiled >= 10);
}

namespace {
std::string read_or_empty(const std::string& path) {
    auto text = read_text_file(path);
    return text.ok() ? text.value() : std::string();
}
}  // namespace

TEST_CASE("the editor plugin's CrtOverlay node shades the screen in a real Godot 3 and lists the presets", "[godot][godot3][plugin]") {
    // The editor itself crashes under Xvfb here (Godot 3.2.3, with or without the plugin), so the
    // plugin script is checked by loading it in the running game (a parse error makes it unusable),
    // and the node it registers is made from its script, as a game without the plugin would.
    test::TempDir project;
    auto exported = test::run_crtforge("--no-cache export -q --preset classic,crt-pulse --target godot3,godot4 --out " + (project / "export"));
    REQUIRE(exported.exit_code == 0);
    const std::string plugin4 = read_or_empty(project / "export/godot4/addons/crtforge/crtforge_plugin.gd");
    CHECK_THAT(plugin4, Catch::StartsWith("@tool\nextends EditorPlugin"));
    CHECK_THAT(plugin4, Catch::Contains("add_custom_type(\"CrtOverlay\", \"CanvasLayer\""));
    CHECK_THAT(read_or_empty(project / "export/godot4/addons/crtforge/crtforge_overlay.gd"), Catch::Contains("func _validate_property("));
    std::filesystem::rename(project / "export/godot3/addons", project / "addons");
    CHECK_THAT(read_or_empty(project / "addons/crtforge/plugin.cfg"), Catch::Contains("script=\"crtforge_plugin.gd\""));
    REQUIRE(write_file_atomic(project / "project.godot",
                              "config_version=4\n\n[application]\nrun/main_scene=\"res://main.tscn\"\n\n[display]\n"
                              "window/size/width=320\nwindow/size/height=240\n").ok());
    // The script's start, for the 2D and the 3D scene: a CrtOverlay node made from its script, three
    // frames drawn, the window's pixel at (80, 120) printed after `label`.
    auto overlay_script = [](const char* extends, const char* label) {
        return fmt::format(R"(extends {}
func _ready():
	var overlay = preload("res://addons/crtforge/crtforge_overlay.gd").new()
	overlay.preset = "classic"
	add_child(overlay)
	for i in range(3):
		yield(VisualServer, "frame_post_draw")
	var img = get_viewport().get_texture().get_data()
	img.flip_y()
	img.lock()
	var c = img.get_pixel(80, 120)
	print("{} %f %f %f" % [c.r, c.g, c.b])
)", extends, label);
    };
    REQUIRE(write_file_atomic(project / "main.gd", overlay_script("Control", "WHITE") + R"(	var e = img.get_pixel(1, 1)
	print("CORNER %f %f %f" % [e.r, e.g, e.b])
	print("PRESETS %s" % PoolStringArray(overlay.presets()).join(","))
	print("LAYER %d" % overlay.layer)
	var plugin = load("res://addons/crtforge/crtforge_plugin.gd")
	print("PLUGIN %s" % str(plugin != null and plugin.can_instance()))
	overlay.preset = "no-such-preset"
	print("HIDDEN %s" % str(not overlay.get_node("Screen").visible))
	get_tree().quit()
)").ok());
    REQUIRE(write_file_atomic(project / "main.tscn", R"([gd_scene load_steps=2 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[node name="Main" type="Control"]
anchor_right = 1.0
anchor_bottom = 1.0
script = ExtResource( 1 )

[node name="White" type="ColorRect" parent="."]
margin_right = 320.0
margin_bottom = 240.0
color = Color( 1, 1, 1, 1 )
)").ok());
    auto log = run_godot3_project(project.path());
    REQUIRE(log.ok());
    INFO(log.value());
    std::smatch m;
    REQUIRE(std::regex_search(log.value(), m, std::regex(R"(WHITE ([0-9.]+) ([0-9.]+) ([0-9.]+))")));
    CHECK(std::stod(m[1]) < 0.99);  // shaded by classic: scanline, mask, vignette
    CHECK(std::stod(m[1]) > 0.5);
    CHECK(std::stod(m[2]) < std::stod(m[1]));
    CHECK_THAT(log.value(), Catch::Contains("CORNER 0.000000 0.000000 0.000000"));
    CHECK_THAT(log.value(), Catch::Contains("PRESETS classic,crt-pulse"));
    CHECK_THAT(log.value(), Catch::Contains("LAYER 100"));
    CHECK_THAT(log.value(), Catch::Contains("PLUGIN True"));
    CHECK_THAT(log.value(), Catch::Contains("crtforge: no preset 'no-such-preset' here"));
    CHECK_THAT(log.value(), Catch::Contains("HIDDEN True"));

    // Over a 3D scene: a Camera looking at an unshaded white wall is shaded like the white 2D picture.
    REQUIRE(write_file_atomic(project / "main.gd", overlay_script("Spatial", "WHITE3D") + "\tget_tree().quit()\n").ok());
    REQUIRE(write_file_atomic(project / "main.tscn", R"([gd_scene load_steps=4 format=2]

[ext_resource path="res://main.gd" type="Script" id=1]

[sub_resource type="SpatialMaterial" id=1]
flags_unshaded = true
albedo_color = Color( 1, 1, 1, 1 )

[sub_resource type="QuadMesh" id=2]
material = SubResource( 1 )
size = Vector2( 40, 40 )

[node name="Main" type="Spatial"]
script = ExtResource( 1 )

[node name="Camera" type="Camera" parent="."]
transform = Transform( 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 5 )
current = true

[node name="Wall" type="MeshInstance" parent="."]
mesh = SubResource( 2 )
)").ok());
    auto log3d = run_godot3_project(project.path());
    REQUIRE(log3d.ok());
    INFO(log3d.value());
    std::smatch w;
    REQUIRE(std::regex_search(log3d.value(), w, std::regex(R"(WHITE3D ([0-9.]+) ([0-9.]+) ([0-9.]+))")));
    for (int c = 1; c <= 3; ++c) CHECK(std::fabs(std::stod(w[c]) - std::stod(m[c])) < 0.01);
}
