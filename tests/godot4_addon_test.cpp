// The Godot 4 addon beyond the shaders, in a real Godot 4 (4.6's web build, runtime/godot4): the
// overlay scene and the CrtOverlay node the editor plugin registers post-process what is drawn
// below them and let clicks through, and the node lists the exported presets. (The EditorPlugin
// itself needs the editor, which an export template does not have: its text is checked in
// godot_test.cpp; the node it adds is what runs here.)
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>

#include "crtforge/files.hpp"
#include "crtforge/runtime/godot4_engine.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

// The export's addons/crtforge/ files, by res:// path.
std::map<std::string, std::string> exported_addon(const std::string& presets) {
    test::TempDir dir;
    auto exported = test::run_crtforge("--no-cache export -q --preset " + presets + " --target godot4 --out " + (dir / "export"));
    REQUIRE(exported.exit_code == 0);
    std::map<std::string, std::string> files;
    const std::filesystem::path root = dir / "export/godot4";
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        auto text = read_text_file(entry.path().string());
        REQUIRE(text.ok());
        files[std::filesystem::relative(entry.path(), root).string()] = text.value();
    }
    return files;
}

constexpr const char* kMainScene = R"([gd_scene load_steps=2 format=3]

[ext_resource type="Script" path="res://main.gd" id="1"]

[node name="Main" type="Control"]
layout_mode = 3
offset_right = 320.0
offset_bottom = 240.0
script = ExtResource("1")

[node name="White" type="ColorRect" parent="."]
offset_right = 160.0
offset_bottom = 240.0
color = Color(1, 1, 1, 1)

[node name="Black" type="ColorRect" parent="."]
offset_left = 160.0
offset_right = 320.0
offset_bottom = 240.0
color = Color(0, 0, 0, 1)

[node name="Button" type="Button" parent="."]
offset_left = 10.0
offset_top = 200.0
offset_right = 90.0
offset_bottom = 235.0
)";

// Prints the window's pixels at the white half's middle and the corner after `label`.
constexpr const char* kPixels = R"(
func _print_pixels(label: String) -> void:
	for i in range(3):
		await RenderingServer.frame_post_draw
	var img := get_viewport().get_texture().get_image()
	var c := img.get_pixel(80, 120)
	var e := img.get_pixel(1, 1)
	print("%s %f %f %f" % [label, c.r, c.g, c.b])
	print("%s-CORNER %f %f %f" % [label, e.r, e.g, e.b])


func _click() -> void:
	for pressed in [true, false]:
		var ev := InputEventMouseButton.new()
		ev.button_index = MOUSE_BUTTON_LEFT
		ev.position = Vector2(40, 220)
		ev.global_position = ev.position
		ev.pressed = pressed
		get_viewport().push_input(ev)
	await get_tree().process_frame
)";

std::array<double, 3> rgb(const std::string& log, const std::string& label) {
    std::smatch m;
    const std::regex line("(^|\n)" + label + R"( ([0-9.]+) ([0-9.]+) ([0-9.]+))");
    REQUIRE(std::regex_search(log, m, line));
    return {std::stod(m[2]), std::stod(m[3]), std::stod(m[4])};
}

}  // namespace

TEST_CASE("the overlay scene and the plugin's CrtOverlay node shade the screen in a real Godot 4 and let clicks through", "[godot4][overlay][plugin]") {
    std::map<std::string, std::string> files = exported_addon("classic,crt-pulse");
    files["main.tscn"] = kMainScene;
    files["main.gd"] = std::string(R"(extends Control
var done := false
var clicked := 0


func _ready() -> void:
	$Button.pressed.connect(func(): clicked += 1)
	var scene = load("res://addons/crtforge/classic.overlay.tscn").instantiate()
	add_child(scene)
	await _print_pixels("SCENE")
	await _click()
	print("SCENE-CLICKED %d" % clicked)
	scene.queue_free()
	var overlay = load("res://addons/crtforge/crtforge_overlay.gd").new()
	overlay.preset = "classic"
	add_child(overlay)
	await _print_pixels("NODE")
	await _click()
	print("NODE-CLICKED %d" % clicked)
	print("PRESETS %s" % ",".join(overlay.presets()))
	print("LAYER %d" % overlay.layer)
	var material = load("res://addons/crtforge/classic.screen.tres")
	print("SCREEN-TRES %s" % str(material is ShaderMaterial and material.shader != null))
	overlay.preset = "no-such-preset"
	print("HIDDEN %s" % str(not overlay.get_node("Screen").visible))
	done = true
)") + kPixels;
    auto log = shared_godot4_server().run_project(files, "res://main.tscn", 320, 240, 120);
    INFO((log.ok() ? log.value() : log.error().str()));
    REQUIRE(log.ok());
    for (const char* label : {"SCENE", "NODE"}) {
        INFO(label);
        // The white half comes out shaded by classic (scanline, mask, vignette), neither untouched
        // nor blanked; the corner is the bezel's black.
        const auto white = rgb(log.value(), label);
        CHECK(white[0] < 0.99);
        CHECK(white[0] > 0.5);
        CHECK(white[1] < white[0]);  // classic's aperture mask dims two channels per column
        const auto corner = rgb(log.value(), std::string(label) + "-CORNER");
        CHECK(corner[0] + corner[1] + corner[2] == 0.0);
    }
    CHECK_THAT(log.value(), Catch::Contains("SCENE-CLICKED 1"));
    CHECK_THAT(log.value(), Catch::Contains("NODE-CLICKED 2"));
    CHECK_THAT(log.value(), Catch::Contains("PRESETS classic,crt-pulse"));
    CHECK_THAT(log.value(), Catch::Contains("LAYER 100"));
    CHECK_THAT(log.value(), Catch::Contains("SCREEN-TRES true"));
    CHECK_THAT(log.value(), Catch::Contains("no preset 'no-such-preset' here"));
    CHECK_THAT(log.value(), Catch::Contains("HIDDEN true"));
    // Nothing else went wrong: the only error Godot logged is the one asked for.
    const std::string rest = std::regex_replace(log.value(), std::regex("ERROR: [^\n]*no preset 'no-such-preset' here[^\n]*"), "");
    CHECK(rest.find("ERROR:") == std::string::npos);
}
