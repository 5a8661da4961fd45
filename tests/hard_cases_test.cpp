// Issue 12's numerical hard cases that a unit test proves directly (the image-level cases are
// golden/plan.toml entries judged by validate; docs/hard-cases.md lists both).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/uniforms.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
using json = nlohmann::json;

namespace {

// Frame 0 of a preset's scene over one picture, on a width x height display: the reference's.
Image reference_frame(const Preset& preset, const Image& input, int width, int height,
                      const std::map<std::string, Value>& overrides = {}) {
    ReferenceSceneJob job;
    job.library = &test::shipped_library();
    job.preset = &preset;
    job.overrides = overrides;
    job.source = [&](int) -> Result<Image> { return input; };
    job.width = width;
    job.height = height;
    job.frames = {0};
    auto images = render_reference_scene(job);
    INFO((images.ok() ? std::string() : images.error().str()));
    REQUIRE(images.ok());
    return images.value().front();
}

// The same through one target's consumer, from the target's emitted files.
Image target_frame(const Preset& preset, const std::vector<CompiledVariant>& passes, TargetId target, const Image& input,
                   int width, int height, const std::map<std::string, Value>& overrides = {}) {
    static TargetRenderer renderer;
    auto outputs = emit_scene(passes, target, Cache());
    REQUIRE(outputs.ok());
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &passes;
    r.target = target;
    r.outputs = &outputs.value();
    r.overrides = overrides;
    r.source = [&](int) -> Result<Image> { return input; };
    r.width = width;
    r.height = height;
    r.frames = {0};
    auto images = renderer.render_scene(r);
    INFO((images.ok() ? std::string() : images.error().str()));
    REQUIRE(images.ok());
    return images.value().front();
}

size_t non_finite_values(const Image& image) {
    size_t count = 0;
    for (float v : image.rgba) count += !std::isfinite(v);
    return count;
}

}  // namespace

TEST_CASE("hosts hand the shader time reduced exactly, so the phase is right at any hour", "[hard][time]") {
    const TemplateLibrary& lib = test::shipped_library();
    const CompiledVariant c = test::compile_or_fail(lib, "crt-pulse");
    REQUIRE(c.variant.angular_speed() != nullptr);
    CHECK(c.variant.angular_speed()->spec->name == "pulseSpeed");
    constexpr long double kTau = 6.283185307179586476925286766559L;
    for (double speed : {20.0, 1.0, 37.5, -3.0}) {
        const auto values = effective_values(c.variant, {{"pulseSpeed", speed}});
        for (double seconds : {0.0, 0.5, 1000.0, 3599.5, 3600.5, 1e5, 1e7, 1e9}) {
            INFO("speed " << speed << ", " << seconds << " s");
            const float t = static_cast<float>(shader_time(c.variant, values, seconds));
            CHECK(t >= 0.0f);
            CHECK(t <= 2 * M_PI / std::fabs(speed) * (1 + 1e-6));
            // The phase the shader computes in float32 against the exact one, modulo a turn.
            long double error = std::fmod(static_cast<long double>(t) * speed - static_cast<long double>(seconds) * speed, kTau);
            if (error > kTau / 2) error -= kTau;
            if (error < -kTau / 2) error += kTau;
            CHECK(std::fabs(static_cast<double>(error)) < 2e-6);
        }
    }
    // A speed of zero (or a pass without one) leaves the seconds alone.
    CHECK(shader_time(c.variant, effective_values(c.variant, {{"pulseSpeed", 0.0}}), 12.5) == 12.5);
    const CompiledVariant classic = test::compile_or_fail(lib, "classic");
    CHECK(classic.variant.angular_speed() == nullptr);
    CHECK(shader_time(classic.variant, effective_values(classic.variant), 1e7) == 1e7);
}

TEST_CASE("the manifest and every host know how time is reduced", "[hard][time][manifest]") {
    const TemplateLibrary& lib = test::shipped_library();
    for (const char* uniforms : {"default", "none"}) {
        INFO("--uniforms " << uniforms);
        ExportRequest request;
        request.presets = {"crt-pulse"};
        request.options.uniforms = UniformSelection::parse(uniforms).value();
        auto result = run_export(lib, request, Cache());
        REQUIRE(result.ok());
        const auto& files = result.value().files;
        const json m = json::parse(files.at("manifest.json"));
        const json& block = m["presets"]["crt-pulse"]["passes"][0]["uniformBlock"];
        bool found = false;
        for (const json& member : block["members"])
            if (member["name"] == "time") {
                found = true;
                // The uniform's name when the speed is a uniform, the baked number otherwise.
                if (std::string(uniforms) == "default") CHECK(member["reduceBy"] == "pulseSpeed");
                else CHECK(member["reduceBy"] == 20.0);
            }
        CHECK(found);
        // Godot: the shader takes hostTime from the exported scene's script and falls back to TIME.
        for (const char* version : {"godot3", "godot4"}) {
            const std::string dir = std::string(version) + "/addons/crtforge/";
            const std::string& shader = files.at(dir + (std::string(version) == "godot3" ? "crt-pulse.shader" : "crt-pulse.gdshader"));
            CHECK_THAT(shader, Catch::Contains("uniform float hostTime = -1.0;"));
            CHECK_THAT(shader, Catch::Contains("max(hostTime, 0.0) + (1.0 - step(0.0, hostTime))"));
            CHECK_THAT(files.at(dir + "crt-pulse.tscn"), Catch::Contains("time_speed"));
            CHECK_THAT(files.at(dir + "crtforge_pipeline.gd"), Catch::Contains("\"hostTime\", _reduced_time("));
        }
    }
    // A preset without time has no reduction and no hostTime.
    const CompiledVariant classic = test::compile_or_fail(lib, "classic");
    auto godot = emit_target(classic, TargetId::Godot4, Cache());
    REQUIRE(godot.ok());
    CHECK_THAT(test::file_with_role(godot.value(), "shader").data, !Catch::Contains("hostTime"));
}

TEST_CASE("a pass with two angular speeds is refused at the spec line", "[hard][time]") {
    test::ScratchTemplates scratch;
    std::string spec = scratch.read("stages/glow.toml");
    spec += R"(
[[param]]
name = "pulseSpeed2"
type = "float"
range = [1.0, 40.0]
default = 5.0
doc = "A second speed"
runtime = true
role = "angular_speed"
)";
    spec.replace(spec.find(R"(params = ["pulseIntensity", "pulseWidth", "pulseSpeed"])"),
                 std::string(R"(params = ["pulseIntensity", "pulseWidth", "pulseSpeed"])").size(),
                 R"(params = ["pulseIntensity", "pulseWidth", "pulseSpeed", "pulseSpeed2"])");
    scratch.write("stages/glow.toml", spec);
    std::string glsl = scratch.read("stages/glow.glsl");
    glsl.replace(glsl.find("time * pulseSpeed)"), std::string("time * pulseSpeed)").size(), "time * pulseSpeed + time * pulseSpeed2)");
    scratch.write("stages/glow.glsl", glsl);
    auto lib = scratch.load();
    REQUIRE(lib.ok());
    auto c = compile_variant(*lib.value(), *lib.value()->find_preset("crt-pulse"), {}, Cache());
    REQUIRE_FALSE(c.ok());
    CHECK_THAT(c.error().message, Catch::Contains("two angular_speed params (pulseSpeed, pulseSpeed2)"));
    CHECK_THAT(c.error().file, Catch::EndsWith("glow.toml"));
    CHECK(c.error().line > 30);
    CHECK(c.error().field == "pulseSpeed2.role");
}

namespace {

// An input whose every texel has its own colour: (x, y) in r, g (exact in half floats), b = 1.
Image coordinate_image(int width, int height) {
    Image image = Image::make(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* p = image.at(x, y);
            p[0] = static_cast<float>(x) / 1024.0f;
            p[1] = static_cast<float>(y) / 1024.0f;
            p[2] = 1.0f;
            p[3] = 1.0f;
        }
    return image;
}

// Shadow-mask cells (the mask's own, in screen pixels, odd columns staggered by half a cell) that
// show more than one source texel among their on-screen pixels, over the cells with any.
std::pair<int, int> cells_with_several_samples(const Image& out, double mask_size) {
    std::map<std::pair<long, long>, std::set<std::pair<float, float>>> samples;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const float* p = out.at(x, y);
            if (p[2] < 0.5f) continue;  // the bezel
            const double cx = (x + 0.5) / mask_size, cy = (y + 0.5) / mask_size;
            const double stagger = std::floor(cx) * 0.5 - std::floor(std::floor(cx) * 0.5);
            samples[{static_cast<long>(std::floor(cx)), static_cast<long>(std::floor(cy + stagger))}].insert({p[0], p[1]});
        }
    int several = 0;
    for (const auto& [cell, set] : samples) several += set.size() > 1;
    return {several, static_cast<int>(samples.size())};
}

}  // namespace

TEST_CASE("the shadow mask samples the source once per screen-space cell under curvature", "[hard][mask]") {
    const TemplateLibrary& lib = test::shipped_library();
    // Sizes where no pixel centre lies exactly on a cell edge (5.5 puts every 11th column on one:
    // which cell such a pixel falls in is the driver's rounding, not a second sample).
    for (double mask_size : {8.0, 6.4}) {
        const std::string text = fmt::format(R"(name = "one-sample"
doc = "Curvature and a quantised shadow mask with no tint: the picture shows which texel each pixel read"
[stages.curvature]
curvatureForm = "crt_effect"
curvature = 0.15
[stages.mask]
maskMode = "shadow"
maskSize = {}
maskIntensity = 0.0
maskQuantize = true
)", mask_size);
        auto preset = test::resolve_preset_texts({{"one-sample.toml", text}}, "one-sample");
        INFO((preset.ok() ? std::string() : preset.error().str()));
        REQUIRE(preset.ok());
        auto compiled = compile_variant(lib, preset.value(), {}, Cache());
        REQUIRE(compiled.ok());
        const Image input = coordinate_image(256, 224);
        for (auto [width, height] : {std::pair{333, 251}, std::pair{1280, 960}}) {
            INFO("maskSize " << mask_size << " at " << width << "x" << height);
            ReferenceJob job;
            job.variant = &compiled.value().variant;
            job.input = input;
            job.filter = SamplerFilter::Nearest;
            job.width = width;
            job.height = height;
            const Image reference = test::require_image(render_reference(job), width, height);
            const auto [ref_several, ref_cells] = cells_with_several_samples(reference, mask_size);
            CHECK(ref_cells > 1000 * 8 / mask_size / mask_size * (width * height) / (333 * 251) / 10);
            CHECK(ref_several == 0);

            static TargetRenderer renderer;
            for (TargetId target : {TargetId::Spirv, TargetId::Glsl330}) {
                INFO(target_info(target).name);
                auto emitted = emit_target(compiled.value(), target, Cache());
                REQUIRE(emitted.ok());
                TargetRenderRequest r;
                r.compiled = &compiled.value();
                r.target = target;
                r.output = &emitted.value();
                r.input = input;
                r.filter = SamplerFilter::Nearest;
                r.width = width;
                r.height = height;
                const Image rendered = test::require_image(renderer.render(r), width, height);
                const auto [several, cells] = cells_with_several_samples(rendered, mask_size);
                CHECK(cells == ref_cells);
                CHECK(several == 0);
            }
        }
    }
}

TEST_CASE("the document's alpha: transparent black outside the Atari screen, judged on every target that shows alpha", "[hard][alpha]") {
    const TemplateLibrary& lib = test::shipped_library();
    const CompiledVariant c = test::compile_or_fail(lib, "atari-crt");
    auto input = make_test_input("pixel_art", 320, 240);  // 1:1, as validate samples it
    REQUIRE(input.ok());
    ReferenceJob job;
    job.variant = &c.variant;
    job.input = input.value();
    job.filter = SamplerFilter::Nearest;
    job.width = 320;
    job.height = 240;
    const Image reference = test::require_image(render_reference(job), 320, 240);
    // crt.frag: fragColor = vec4(0.0) where the distorted uv leaves 0..1 (the corners at curvature 0.1).
    CHECK(reference.at(0, 0)[3] == 0.0f);
    CHECK(reference.at(0, 0)[0] == 0.0f);
    CHECK(reference.at(160, 120)[3] == 1.0f);

    static TargetRenderer renderer;
    for (TargetId target : {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50, TargetId::Wgsl}) {
        INFO(target_info(target).name);
        auto emitted = emit_target(c, target, Cache());
        REQUIRE(emitted.ok());
        TargetRenderRequest r;
        r.compiled = &c;
        r.target = target;
        r.output = &emitted.value();
        r.input = input.value();
        r.filter = SamplerFilter::Nearest;
        r.width = 320;
        r.height = 240;
        const Image rendered = test::require_image(renderer.render(r), 320, 240);
        CHECK(rendered.at(0, 0)[3] == 0.0f);
        CHECK(rendered.at(319, 239)[3] == 0.0f);
        CHECK(rendered.at(160, 120)[3] == 1.0f);
        auto verdict = judge(rendered, reference, default_tolerance());
        REQUIRE(verdict.ok());
        CHECK(verdict.value().alpha_outlier_fraction == 0.0);
        INFO(verdict.value().reason);
        CHECK(verdict.value().passed);
    }

    // The judge fails an opaque bezel where the golden is transparent; a display that composites
    // (an 8-bit window) sees the golden over black instead.
    Image opaque = reference;
    for (size_t p = 0; p < opaque.pixel_count(); ++p) opaque.rgba[p * 4 + 3] = 1.0f;
    auto wrong = judge(opaque, reference, default_tolerance());
    REQUIRE(wrong.ok());
    CHECK_FALSE(wrong.value().passed);
    CHECK_THAT(wrong.value().reason, Catch::Contains("alpha"));
    auto displayed = judge(opaque, reference, default_tolerance(), 1.0 / 255.0);
    REQUIRE(displayed.ok());
    CHECK(displayed.value().passed);

    // Godot's screen-mode shader replaces the screen, so it composites its alpha over black itself.
    auto godot = emit_target(c, TargetId::Godot4, Cache());
    REQUIRE(godot.ok());
    CHECK_THAT(test::file_with_role(godot.value(), "screenShader").data, Catch::Contains("COLOR = vec4(COLOR.rgb * COLOR.a, 1.0);"));
    CHECK_THAT(test::file_with_role(godot.value(), "shader").data, !Catch::Contains("COLOR.rgb * COLOR.a"));
}

TEST_CASE("a legacy Glitch preset loads through the migration, with a warning per key", "[hard][migration]") {
    test::ScratchTemplates scratch;
    scratch.write("presets/old-crt.toml", R"(name = "old-crt"
doc = "A Glitch preset from before the CRT effect existed"

[glitch]
crtEnabled = true
curvature = 0.08
vignetteEnabled = true
overlayMode = "scanlines"
overlayIntensity = 0.25
overlaySpacing = 3.0
datamoshEnabled = true
)");
    auto lib = scratch.load();
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    const auto& warnings = lib.value()->warnings();
    REQUIRE(warnings.size() == 7);
    CHECK_THAT(warnings[0], Catch::Contains("old-crt.toml:5: warning: field 'glitch.crtEnabled': Glitch (format 1) key migrated to stages.curvature on"));
    CHECK_THAT(warnings[1], Catch::Contains("old-crt.toml:6: warning: field 'glitch.curvature'") && Catch::Contains("stages.curvature.curvature"));
    CHECK_THAT(warnings[4], Catch::Contains(":9: warning: field 'glitch.overlayIntensity'") && Catch::Contains("scanlineIntensity"));
    CHECK_THAT(warnings[6], Catch::Contains(":11: warning: field 'glitch.datamoshEnabled'") && Catch::Contains("stays with Glitch"));

    // The migrated preset is the CRT effect with Glitch's values and nothing Glitch did not have.
    const Preset* p = lib.value()->find_preset("old-crt");
    REQUIRE(p != nullptr);
    std::map<std::string, std::map<std::string, Value>> stages;
    for (const ResolvedStage& rs : p->passes.front().stages) stages[rs.stage->name] = rs.values;
    CHECK(stages.count("mask") == 0);
    CHECK(stages.count("glow") == 0);
    REQUIRE(stages.count("curvature") == 1);
    CHECK(std::get<double>(stages["curvature"]["curvature"]) == 0.08);
    CHECK(std::get<std::string>(stages["curvature"]["curvatureForm"]) == "crt_effect");
    REQUIRE(stages.count("scanlines") == 1);
    CHECK(std::get<double>(stages["scanlines"]["scanlineIntensity"]) == 0.25);
    CHECK(std::get<double>(stages["scanlines"]["scanlineSpacing"]) == 3.0);
    REQUIRE(stages.count("vignette") == 1);
    CHECK(std::get<double>(stages["vignette"]["vignetteExponent"]) == 0.4);
    // It compiles like any preset.
    test::compile_or_fail(*lib.value(), "old-crt");

    // What a legacy file gets wrong is still a one-line error at its line and field.
    struct Case {
        const char* body;
        int line;
        const char* field;
        const char* says;
    };
    for (const Case& c : std::vector<Case>{
             {"[glitch]\ncrtEnabled = true\ncurvature = 0.9\n", 5, "glitch.curvature", "range"},
             {"[glitch]\ncrtEnabeld = true\n", 4, "glitch.crtEnabeld", "not a Glitch key"},
             {"format = 3\n[glitch]\ncrtEnabled = true\n", 3, "format", "not one this crtforge reads"},
             {"format = 2\n[glitch]\ncrtEnabled = true\n", 4, "glitch", "format-1"},
             {"[glitch]\ncrtEnabled = true\n[stages.mask]\nmaskSize = 4.0\n", 5, "stages", "format-1"},
         }) {
        INFO(c.body);
        test::ScratchTemplates bad;
        bad.write("presets/old-crt.toml", std::string("name = \"old-crt\"\ndoc = \"d\"\n") + c.body);
        auto broken = bad.load();
        REQUIRE_FALSE(broken.ok());
        CHECK(broken.error().line == c.line);
        CHECK(broken.error().field == c.field);
        CHECK_THAT(broken.error().message, Catch::Contains(c.says));
        CHECK_THAT(broken.error().file, Catch::EndsWith("old-crt.toml"));
    }
}

TEST_CASE("NaN, infinities and negative values in the input give finite output on every target", "[hard][hdr]") {
    const TemplateLibrary& lib = test::shipped_library();
    // Columns of hostile values across a normal ramp: NaN, +Inf, -Inf, -1, 1e30 (Inf in half floats), 70000.
    const float hostile[] = {std::nanf(""), INFINITY, -INFINITY, -1.0f, 1e30f, 70000.0f};
    constexpr int kW = 48, kH = 36;
    Image input = Image::make(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* p = input.at(x, y);
            const float ramp = static_cast<float>(x) / kW;
            for (int c = 0; c < 3; ++c) p[c] = (x / 4 + c) % 3 == 0 ? hostile[(x / 4 + y / 6) % 6] : ramp;
            p[3] = 1.0f;
        }
    for (const Preset& preset : lib.presets()) {
        auto passes = compile_scene(lib, preset, {}, Cache());
        REQUIRE(passes.ok());
        // The reference applies the same rule (it is what the goldens hold).
        INFO(preset.name << " reference");
        CHECK(non_finite_values(reference_frame(preset, input, kW, kH)) == 0);
        for (TargetId target : {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50, TargetId::Wgsl}) {
            INFO(preset.name << " on " << target_info(target).name);
            CHECK(non_finite_values(target_frame(preset, passes.value(), target, input, kW, kH)) == 0);
        }
    }
}

TEST_CASE("the generator rejects undefined constructs in a stage snippet at its file and line", "[hard][lint]") {
    struct Case {
        std::string code;  // appended to vignette.glsl as line N+2
        std::string says;
    };
    for (const Case& c : std::vector<Case>{
             {"float lint_a(float x) { return smoothstep(0.85, 0.4, x); }", "edges reversed or equal"},
             {"float lint_b(float x) { return smoothstep(0.5, 0.5, x); }", "edges reversed or equal"},
             {"float lint_c(float x) { return pow(-2.0, x); }", "negative constant base"},
             {"float lint_d(float x) { return x / 0.0; }", "literal zero"},
             {"float lint_e(float x) { return x / vignetteStrength; }", "divides by vignetteStrength, whose range includes 0"},
             {"float lint_f(float x) { return smoothstep(vignetteStrength, 0.5, x); }", "ranges let the edges meet or cross"},
         }) {
        INFO(c.code);
        test::ScratchTemplates scratch;
        std::string glsl = scratch.read("stages/vignette.glsl");
        const int line = static_cast<int>(std::count(glsl.begin(), glsl.end(), '\n')) + 2;
        scratch.write("stages/vignette.glsl", glsl + "\n" + c.code + "\n");
        auto lib = scratch.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("vignette.glsl"));
        CHECK(lib.error().line == line);
        CHECK(lib.error().field == "glsl");
        CHECK_THAT(lib.error().message, Catch::Contains(c.says));
    }
    // In comments, guarded, or safe by range: accepted.
    test::ScratchTemplates scratch;
    scratch.write("stages/vignette.glsl", scratch.read("stages/vignette.glsl") +
                                              "\n// return smoothstep(0.85, 0.4, x); x / 0.0\n"
                                              "float lint_g(float x) { return vignetteStrength > 0.0 ? x / vignetteStrength : x; }  // guarded: > 0\n"
                                              "float lint_h(float x) { return x / 0.5 + smoothstep(0.4, 0.85, x); }\n");
    auto lib = scratch.load();
    INFO((lib.ok() ? std::string() : lib.error().str()));
    CHECK(lib.ok());
}

TEST_CASE("every runtime param at either end of its range renders finite and like the reference", "[hard][params]") {
    const TemplateLibrary& lib = test::shipped_library();
    int checked = 0;
    for (const Preset& preset : lib.presets()) {
        auto passes = compile_scene(lib, preset, {}, Cache());
        REQUIRE(passes.ok());
        const int iw = preset.scene.source_width ? preset.scene.source_width : 64;
        const int ih = preset.scene.source_width ? preset.scene.source_height : 48;
        auto input = make_test_input("pixel_art", iw, ih);
        REQUIRE(input.ok());
        std::map<std::string, const ParamSpec*> params;  // every numeric uniform of every pass
        for (const CompiledVariant& pass : passes.value())
            for (const VariantParam* p : pass.variant.uniforms())
                if ((p->spec->type == ParamType::Float || p->spec->type == ParamType::Int) && p->spec->min) params[p->spec->name] = p->spec;
        for (const auto& [name, spec] : params)
            for (double end : {*spec->min, *spec->max}) {
                std::map<std::string, Value> set;
                if (spec->type == ParamType::Int)
                    set[name] = static_cast<int64_t>(end);
                else
                    set[name] = end;
                INFO(preset.name << ": " << name << " = " << end);
                const Image reference = reference_frame(preset, input.value(), 64, 48, set);
                CHECK(non_finite_values(reference) == 0);
                const Image rendered = target_frame(preset, passes.value(), TargetId::Spirv, input.value(), 64, 48, set);
                CHECK(non_finite_values(rendered) == 0);
                auto m = compare_images(rendered, reference);
                REQUIRE(m.ok());
                // Agreement is the goldens' job (exact bounds, jitter maps); here: no blow-up at the ends.
                CHECK(m.value().rmse < 0.01);
                ++checked;
            }
    }
    CHECK(checked > 60);
}

TEST_CASE("text that reaches generated code is one plain line: control characters and line terminators are refused", "[hard][text]") {
    struct Case {
        std::string rel, from, to, field, says;
    };
    const std::string unit_line = "unit = \"px\"";
    for (const Case& c : std::vector<Case>{
             {"stages/glow.toml", "doc = \"Amplitude of the brightness ripple\"", "doc = \"Amplitude\\rvec4 injected;\"", "doc", "U+000D"},
             {"stages/glow.toml", unit_line, "unit = \"px\\nuniform float injected;\"", "unit", "U+000A"},
             {"stages/glow.toml", unit_line, "unit = \"px\xE2\x80\xA8x\"", "unit", "U+2028"},
             {"stages/glow.toml", unit_line, "unit = \"px\xC2\x85x\"", "unit", "U+0085"},
             {"stages/glow.toml", unit_line, "unit = \"px\\\\\"", "unit", "trailing backslash"},
             {"presets/crt-pulse.toml", "doc = \"", "doc = \"\\u000b", "doc", "U+000B"},
         }) {
        INFO(c.rel << ": " << c.to);
        test::ScratchTemplates scratch;
        std::string text = scratch.read(c.rel);
        const size_t at = text.find(c.from);
        REQUIRE(at != std::string::npos);
        text.replace(at, c.from.size(), c.to);
        scratch.write(c.rel, text);
        auto lib = scratch.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith(c.rel.substr(c.rel.find('/') + 1)));
        CHECK(lib.error().line > 0);
        CHECK_THAT(lib.error().field, Catch::EndsWith(c.field));
        CHECK_THAT(lib.error().message, Catch::Contains(c.says));
    }
}
