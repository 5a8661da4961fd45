// A real Godot 4 (4.6's official web build in headless Chromium, runtime/godot4): the engine's
// conventions (UV top-left, the read-back's orientation and its 8-bit step), its own shader
// compiler refusing what the shim accepts, and every snapshot construct's Godot 4 shader compiled
// by it. One Godot 4 serves the whole test process (shared_godot4_server), as it serves a validate
// run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "crtforge/files.hpp"
#include "crtforge/runtime/godot4_engine.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

using namespace crtforge;
using Catch::Matchers::Contains;

namespace {

// A 2 x 2 picture: red, green / blue, white (row 0 = top).
Image quadrants() {
    Image image = Image::make(2, 2);
    const float px[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 4; ++c) image.rgba[static_cast<size_t>(i * 4 + c)] = px[i][c];
    return image;
}


}  // namespace

TEST_CASE("godot4: TEXTURE and UV start at the top-left, the read-back is top row first, 8 bits a channel", "[godot4]") {
    Godot4Job job;
    job.shader_code =
        "shader_type canvas_item;\nuniform float gain = 1.0;\n"
        "void fragment() { COLOR = vec4(texture(TEXTURE, UV).rgb * gain, 1.0); }\n";
    job.input = quadrants();
    job.filter = SamplerFilter::Nearest;
    job.width = 4;
    job.height = 4;
    job.params["gain"] = 0.5;
    auto image = shared_godot4_server().render(job);
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    const Image& out = image.value();
    REQUIRE(out.width == 4);
    REQUIRE(out.height == 4);
    // Top-left red, top-right green, bottom-left blue, at the gain the host set.
    CHECK(out.pixel(0, 0)[0] == Approx(0.5).margin(1.0 / 255));
    CHECK(out.pixel(3, 0)[1] == Approx(0.5).margin(1.0 / 255));
    CHECK(out.pixel(0, 3)[2] == Approx(0.5).margin(1.0 / 255));
    CHECK(out.pixel(3, 3)[0] == Approx(0.5).margin(1.0 / 255));
    // The viewport stores 8 bits: every value is a multiple of 1/255.
    for (float v : out.rgba) CHECK(std::fabs(v * 255.0f - std::round(v * 255.0f)) < 1e-3f);
}

TEST_CASE("godot4: a shader Godot 4 refuses but the shim accepts fails the godot4 consumer, with its line", "[godot4][errors]") {
    // A global without an initialiser (SPIRV-Cross's printing of OpUndef): GLSL, so the shim takes
    // it; Godot 4 has only global constants and says "Expected initialization of constant".
    OutputFile shader;
    shader.path = "addons/crtforge/refused.gdshader";
    shader.stage = ShaderStage::Fragment;
    shader.role = "shader";
    shader.data = "shader_type canvas_item;\n\nvec4 _1032;\n\nvoid fragment()\n{\n    COLOR = texture(TEXTURE, UV) + _1032 * 0.0;\n}\n";
    ConsumerEngines engines(EngineOptions{});
    REQUIRE(consumers::compile_through_shim(shader.data, 4, engines).ok());
    auto refused = godot4_consumer().compile(shader, engines);
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().kind == ErrorKind::Validation);
    CHECK_THAT(refused.error().message, Contains("Godot 4 rejected the shader") && Contains("initialization of constant"));
    CHECK(refused.error().line == 3);
    // The same shader with the global as a constant compiles.
    shader.data.replace(shader.data.find("vec4 _1032;"), 11, "const vec4 _1032 = vec4(0.0);");
    CHECK(godot4_consumer().compile(shader, engines).ok());
}

TEST_CASE("real Godot 4 accepts the Godot 4 shader of every snapshot construct", "[godot4]") {
    // One construct family per snapshot preset (loops, loop-carried values, int switches, the
    // optimiser's undefined lanes): each exported Godot 4 shader, node and screen mode, compiled
    // by the engine itself.
    const std::string dir = std::string(CRTFORGE_SOURCE_DIR) + "/tests/snapshots/expected/godot4/addons/crtforge";
    ConsumerEngines engines(EngineOptions{});
    size_t compiled = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".gdshader") continue;
        OutputFile shader;
        shader.path = entry.path().filename().string();
        shader.data = read_text_file(entry.path().string()).value();
        INFO(shader.path);
        auto result = godot4_consumer().compile(shader, engines);
        if (!result.ok()) UNSCOPED_INFO(result.error().str());
        CHECK(result.ok());
        ++compiled;
    }
    CHECK(compiled >= 16);
}

TEST_CASE("godot4: TIME is the game's scaled time modulo 3600 s, wrapped exactly (what the TIME fallback relies on)", "[godot4][time]") {
    // A shader used without crtforge_pipeline.gd reads TIME, and the exported shaders round the
    // angular speed to whole turns per 3600 s so that a phase stays continuous across TIME's wrap.
    // That holds only if TIME is an exact fmod(time, 3600). Measured here: the game runs at 12000x
    // (Engine.time_scale), so TIME wraps every 0.3 s of real time; the shader writes TIME in two
    // 8-bit channels (whole 256 s blocks and the seconds within one), the script the time it
    // summed from _process's delta.
    std::map<std::string, std::string> files;
    files["main.tscn"] = R"([gd_scene load_steps=3 format=3]

[ext_resource type="Script" path="res://main.gd" id="1"]

[sub_resource type="Shader" id="s"]
code = "shader_type canvas_item;
void fragment() {
	COLOR = vec4(fract(TIME / 256.0), floor(TIME / 256.0) / 255.0, 0.0, 1.0);
}"

[sub_resource type="ShaderMaterial" id="m"]
shader = SubResource("s")

[node name="Main" type="Control"]
offset_right = 4.0
offset_bottom = 4.0
script = ExtResource("1")

[node name="Rect" type="ColorRect" parent="."]
offset_right = 4.0
offset_bottom = 4.0
material = SubResource("m")
)";
    files["main.gd"] = R"(extends Control
var done := false
var summed := 0.0


func _ready() -> void:
	Engine.time_scale = 12000.0
	for i in range(100):
		await RenderingServer.frame_post_draw
		var c := get_viewport().get_texture().get_image().get_pixel(1, 1)
		print("T %f %f" % [summed, round(c.g * 255.0) * 256.0 + c.r * 256.0])
	Engine.time_scale = 1.0
	done = true


func _process(delta: float) -> void:
	summed += delta
)";
    auto log = shared_godot4_server().run_project(files, "res://main.tscn", 4, 4, 200);
    INFO((log.ok() ? log.value() : log.error().str()));
    REQUIRE(log.ok());
    std::vector<std::pair<double, double>> samples;  // (summed game time, the shader's TIME)
    std::istringstream in(log.value());
    for (std::string line; std::getline(in, line);) {
        double summed = 0, shader = 0;
        if (std::sscanf(line.c_str(), "T %lf %lf", &summed, &shader) == 2) samples.emplace_back(summed, shader);
    }
    REQUIRE(samples.size() == 100);
    // TIME = fmod(summed + offset, 3600), so from one frame to the next TIME advances by what
    // `summed` advanced, less 3600 where it wrapped. Checked a frame pair at a time, not against
    // one offset: under load the engine now and then draws a frame with a step other than the one
    // _process saw (the frame whose time_scale changed always does), which moves the offset for
    // good without saying anything about the wrap. Such pairs may be a few; the pairs that
    // straddle a wrap must agree to the 1 s the 8-bit channel resolves, all but one at most (a
    // hiccup may fall on a wrap): a wrap other than an exact fmod breaks every one of them.
    int agreeing = 0, wraps = 0, broken_wraps = 0, pairs = 0;
    for (size_t i = 2; i < samples.size(); ++i) {
        const double summed_step = samples[i].first - samples[i - 1].first;
        const double time_step = samples[i].second - samples[i - 1].second;
        const bool wrapped = time_step < 0;
        const double expected = std::fmod(summed_step, 3600.0) - (wrapped ? 3600.0 : 0.0);
        const bool agrees = std::fabs(time_step - expected) < 2.0;
        INFO("frames " << i - 1 << "-" << i << ": summed +" << summed_step << " s, TIME " << samples[i - 1].second
                       << " -> " << samples[i].second << " s");
        if (wrapped && !agrees) UNSCOPED_INFO("a wrap that does not agree: frames " << i - 1 << "-" << i);
        ++pairs;
        if (agrees) ++agreeing;
        if (wrapped) ++(agrees ? wraps : broken_wraps);
    }
    CHECK(agreeing >= pairs * 9 / 10);
    CHECK(wraps >= 2);
    CHECK(broken_wraps <= 1);
}

TEST_CASE("godot4: a server that goes leaves no folder of its driver or Chromium behind", "[godot4]") {
    std::string scratch;
    {
        Godot4Server server;
        const std::string described = server.describe();
        INFO(described);
        scratch = server.driver_scratch();
        REQUIRE_FALSE(scratch.empty());
        CHECK(std::filesystem::is_directory(std::filesystem::path(scratch) / "profile"));  // Chromium's, written while it runs
    }
    // Chromium's renderer and GPU processes outliving the browser process wrote into the profile
    // after the driver had removed it, which brought the folder back: a leak per run.
    std::this_thread::sleep_for(std::chrono::seconds(3));
    CHECK_FALSE(std::filesystem::exists(scratch));
}

TEST_CASE("godot4: a job that brings a different script under a path already used runs the new script", "[godot4]") {
    // Godot keeps a GDScript it loaded for the life of the process; the engine starts a fresh one
    // when a job's script differs from the one mounted under the same path.
    const std::string scene = "[gd_scene load_steps=2 format=3]\n\n[ext_resource type=\"Script\" path=\"res://said.gd\" id=\"1\"]\n\n"
                              "[node name=\"Main\" type=\"Node\"]\nscript = ExtResource(\"1\")\n";
    auto say = [](const std::string& word) {
        return "extends Node\nvar done := false\nfunc _ready() -> void:\n\tprint(\"SAID " + word + "\")\n\tdone = true\n";
    };
    for (const std::string word : {"first", "second", "second"}) {
        auto log = shared_godot4_server().run_project({{"said.tscn", scene}, {"said.gd", say(word)}}, "res://said.tscn", 2, 2, 10);
        INFO((log.ok() ? log.value() : log.error().str()));
        REQUIRE(log.ok());
        CHECK(log.value() == "SAID " + word);
    }
}
