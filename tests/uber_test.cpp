// The all-stages uber-shader (--uniforms uber): one shader holding every stage a pass can feed,
// each behind its int switch uniform, every param a uniform. It must draw exactly what the
// specialised shader of the same preset draws, on every preset: only then is the cost bench
// measures for it the cost of branching, not of a different picture.
#include <algorithm>

#include <catch2/catch.hpp>

#include "crtforge/assembler.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/variant.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

VariantOptions uber_options() {
    VariantOptions o;
    o.uniforms = UniformSelection::parse("uber").value();
    return o;
}

const VariantParam* find_param(const Variant& v, const std::string& name) {
    for (const VariantParam& p : v.params)
        if (p.spec->name == name) return &p;
    return nullptr;
}

}  // namespace

TEST_CASE("the uber-shader holds every stage the pass can feed, each behind its switch", "[uber][variant]") {
    const TemplateLibrary& lib = test::shipped_library();
    const Preset* classic = lib.find_preset("classic");
    REQUIRE(classic);
    auto made = make_variant(lib, *classic, uber_options());
    REQUIRE(made.ok());
    const Variant& v = made.value();
    CHECK(v.uber());
    CHECK(UniformSelection::parse("uber").value().str() == "uber");

    // Every stage with a form that needs no texture classic's pass lacks; a form that samples a
    // texture the pass does not bind (palette's nearest: a palette LUT) is left out.
    for (const StageSpec& stage : lib.stages()) {
        INFO(stage.name);
        auto held = std::find_if(v.stages.begin(), v.stages.end(), [&](const VariantStage& s) { return s.stage == &stage; });
        const bool feedable = std::any_of(stage.forms.begin(), stage.forms.end(), [](const FormSpec& f) { return f.textures.empty(); });
        REQUIRE((held != v.stages.end()) == feedable);
        if (!feedable) continue;
        CHECK(held->switched);
        for (const FormSpec* form : held->forms) CHECK(form->textures.empty());
        // The switch: the preset's form, or 0 where the preset does not run the stage.
        const VariantParam* sw = find_param(v, stage.stage_switch.name);
        REQUIRE(sw);
        CHECK(sw->uniform);
        const ResolvedStage* running = classic->passes[0].find_stage(stage.name);
        const int64_t expected = running ? held->switch_value(running->form) : 0;
        CHECK(std::get<int64_t>(sw->value) == expected);
        if (running) CHECK(expected > 0);
        // Selectors are not in the shader: the switch does their work.
        if (!stage.selector.empty()) CHECK(find_param(v, stage.selector) == nullptr);
    }
    // Every param a uniform, runtime = true in its spec or not; classic's values where it sets them.
    for (const VariantParam& p : v.params) CHECK(p.uniform);
    const VariantParam* intensity = find_param(v, "scanlineIntensity");
    REQUIRE(intensity);
    CHECK(std::get<double>(intensity->value) == 0.5);
    CHECK(v.has_uniform_block());

    // In the source: each form's call under its switch value; forms sharing a function share its
    // call (curvature's point and edge anti-aliased forms warp alike).
    const std::string src = assemble(lib, v).fragment;
    const StageSpec* curvature = lib.find_stage("curvature");
    REQUIRE(curvature);
    for (size_t i = 0; i < curvature->forms.size(); ++i)
        CHECK_THAT(src, Catch::Contains("crtStage_curvature == " + std::to_string(i + 1)));
    CHECK_THAT(src, Catch::Contains("if (crtStage_curvature == 1 || crtStage_curvature == 4) frag.uv = curvature_atari(frag.uv);"));
    CHECK_THAT(src, Catch::Contains("int crtStage_scanlines;"));

    // A specialised variant has no switch and one form per stage.
    auto plain = make_variant(lib, *classic, {});
    REQUIRE(plain.ok());
    CHECK(plain.value().stages.size() == classic->passes[0].stages.size());
    for (const VariantStage& s : plain.value().stages) {
        CHECK_FALSE(s.switched);
        CHECK(s.forms.size() == 1);
    }
    CHECK(find_param(plain.value(), "crtStage_scanlines") == nullptr);
}

TEST_CASE("a stage param may not take an uber-shader switch's name", "[uber][spec][errors]") {
    const std::string text = "name = \"probe\"\ndoc = \"d\"\norder = 5\n[[param]]\nname = \"crtStage_probe\"\ntype = \"float\"\n"
                             "range = [0.0, 1.0]\ndefault = 0.5\ndoc = \"d\"\n[[form]]\nname = \"only\"\ndoc = \"d\"\n"
                             "params = [\"crtStage_probe\"]\ncolor = \"probe_color\"\n";
    auto spec = parse_stage_spec(text, "probe.toml");
    REQUIRE_FALSE(spec.ok());
    CHECK(spec.error().file == "probe.toml");
    CHECK(spec.error().line == 5);  // the name
    CHECK(spec.error().field == "param.crtStage_probe");
    CHECK_THAT(spec.error().message, Catch::Contains("switches"));
}

// Every shipped preset, every pass: the uber-shader's frame against the specialised shader's, on
// Vulkan (lavapipe), with every param a uniform in both (so both see the same float values).
TEST_CASE("the uber-shader draws what the specialised shader draws, on every preset", "[uber][vulkan]") {
    const TemplateLibrary& lib = test::shipped_library();
    VariantOptions all;
    all.uniforms = UniformSelection::parse("all").value();
    TargetRenderer renderer;
    const test::SceneShot shot{[](int frame) { return make_test_input("pixel_art", 80, 60, frame); }, 96, 72, {2}};
    int presets = 0;
    for (const Preset& preset : lib.presets()) {
        if (preset.test_only) continue;
        INFO(preset.name);
        std::vector<Image> frames;
        for (const VariantOptions& options : {all, uber_options()}) {
            auto compiled = compile_scene(lib, preset, options, Cache());
            INFO((compiled.ok() ? std::string() : compiled.error().str()));
            REQUIRE(compiled.ok());
            frames.push_back(test::render_scene_or_fail(renderer, preset, compiled.value(), shot).front());
        }
        auto metrics = compare_images(frames[1], frames[0]);
        REQUIRE(metrics.ok());
        // The same arithmetic in the same order; only the optimiser's scheduling around the branches
        // may differ (a fused multiply-add here or there).
        CHECK(metrics.value().max_abs < 1e-3);
        CHECK(metrics.value().rmse < 1e-4);
        ++presets;
    }
    CHECK(presets >= 17);
}

// The uber-shader on every target, through the consumer that proves it (a real Godot 3, Dawn,
// Mesa GL, WebGL 2's plain uniforms set by name...), against the specialised shader on Vulkan.
TEST_CASE("the uber-shader renders on every target like the specialised shader", "[uber][targets]") {
    const TemplateLibrary& lib = test::shipped_library();
    const Preset* classic = lib.find_preset("classic");
    REQUIRE(classic);
    TargetRenderer renderer;
    const test::SceneShot shot{[](int frame) { return make_test_input("pixel_art", 80, 60, frame); }, 96, 72, {1}};
    auto specialised = compile_scene(lib, *classic, {}, Cache());
    REQUIRE(specialised.ok());
    const Image expected = test::render_scene_or_fail(renderer, *classic, specialised.value(), shot).front();
    auto uber = compile_scene(lib, *classic, uber_options(), Cache());
    REQUIRE(uber.ok());
    for (const TargetInfo& target : all_targets()) {
        INFO(target.name);
        std::vector<TargetOutput> outputs;
        auto out = emit_target(uber.value().front(), target.id, Cache());
        INFO((out.ok() ? std::string() : out.error().str()));
        REQUIRE(out.ok());
        for (const OutputFile& file : out.value().files) {
            INFO(file.suffix);
            auto compiled = renderer.compile(target.id, file);
            INFO((compiled.ok() ? std::string() : compiled.error().str()));
            CHECK(compiled.ok());
        }
        outputs.push_back(std::move(out.value()));
        const Image image = test::render_scene_or_fail(renderer, *classic, uber.value(), shot, target.id, &outputs).front();
        auto metrics = compare_images(image, expected);
        REQUIRE(metrics.ok());
        const double quantum = renderer.output_quantum(target.id);  // Godot 3's 8-bit display
        INFO("RMSE " << metrics.value().rmse << " max " << metrics.value().max_abs);
        CHECK(metrics.value().rmse < 0.0005 + quantum);
        CHECK(metrics.value().max_abs < 0.005 + 2 * quantum);
    }
}
