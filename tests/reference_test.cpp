// The CPU reference renderer against the Vulkan renders of every preset: independent oracles
// that must agree within the golden tolerance; plus the reference's own sampling rules.
#include <catch2/catch.hpp>

#include "crtforge/validate/golden.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

TEST_CASE("reference sampling follows Vulkan: texel centres, clamp, nearest and bilinear", "[reference]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto variant = make_variant(lib, *lib.find_preset("passthrough"), {});
    REQUIRE(variant.ok());
    Image two = Image::make(2, 1);
    two.set_pixel(0, 0, {0, 0, 0, 1});
    two.set_pixel(1, 0, {1, 1, 1, 1});
    ReferenceJob job;
    job.variant = &variant.value();
    job.input = two;
    job.width = 4;
    job.height = 1;
    auto out = render_reference(job);
    REQUIRE(out.ok());
    // Output pixel centres at u = 1/8, 3/8, 5/8, 7/8 -> texel space 0.25..1.75: clamp, 0.25, 0.75, clamp.
    CHECK(out.value().at(0, 0)[0] == Approx(0.0));
    CHECK(out.value().at(1, 0)[0] == Approx(0.25));
    CHECK(out.value().at(2, 0)[0] == Approx(0.75));
    CHECK(out.value().at(3, 0)[0] == Approx(1.0));
    job.filter = SamplerFilter::Nearest;
    out = render_reference(job);
    CHECK(out.value().at(1, 0)[0] == 0.0f);
    CHECK(out.value().at(2, 0)[0] == 1.0f);
}

TEST_CASE("every preset: Vulkan render agrees with the fp64 reference within tolerance", "[reference]") {
    const TemplateLibrary& lib = test::shipped_library();
    TargetRenderer renderer(EngineOptions{"", true});  // validation layers on: any message fails
    for (const Preset& preset : lib.presets()) {
        for (const char* input_name : {"color_bars", "mandelbrot", "hdr"}) {
            INFO(preset.name << " on " << input_name);
            const GoldenEntry entry = make_golden_entry(preset.name, input_name, 160, 120, 160, 120, 7);
            auto reference = render_golden_reference(lib, entry);
            INFO((reference.ok() ? std::string() : reference.error().str()));
            REQUIRE(reference.ok());
            auto compiled = compile_scene(lib, preset, {}, Cache());
            REQUIRE(compiled.ok());
            SceneRenderRequest r;
            r.preset = &preset;
            r.passes = &compiled.value();
            r.source = [&entry](int frame) { return golden_input(entry, frame); };
            r.width = 160;
            r.height = 120;
            r.frames = {7};
            auto images = renderer.render_scene(r);
            INFO((images.ok() ? std::string() : images.error().str()));
            REQUIRE(images.ok());
            const Image image = images.value().front();
            auto verdict = judge(image, reference.value(), test::golden_plan_or_fail(lib, std::string(CRTFORGE_SOURCE_DIR) + "/golden").front().tolerance);
            REQUIRE(verdict.ok());
            INFO("rmse " << verdict.value().metrics.rmse << " ssim " << verdict.value().metrics.ssim << " outliers "
                         << verdict.value().outlier_fraction << ": " << verdict.value().reason);
            CHECK(verdict.value().passed);
            CHECK(verdict.value().metrics.rmse < 0.005);
        }
    }
}

TEST_CASE("the reference refuses stages it has no model of", "[reference][errors]") {
    test::ScratchTemplates t;
    t.write("stages/sepia.toml", "name = \"sepia\"\ndoc = \"Sepia tone\"\norder = 71\n[[form]]\nname = \"plain\"\ndoc = \"d\"\ncolor = \"sepia_plain\"\n");
    t.write("stages/sepia.glsl", "vec3 sepia_plain(vec3 color, CrtFrag frag) { return color; }\n");
    t.write("presets/sepia-only.toml", "name = \"sepia-only\"\ndoc = \"d\"\n[stages.sepia]\n");
    auto lib = t.load();
    REQUIRE(lib.ok());
    auto variant = make_variant(*lib.value(), *lib.value()->find_preset("sepia-only"), {});
    REQUIRE(variant.ok());
    ReferenceJob job;
    job.variant = &variant.value();
    job.input = Image::make(4, 4, {1, 1, 1, 1});
    job.width = 4;
    job.height = 4;
    auto out = render_reference(job);
    REQUIRE_FALSE(out.ok());
    CHECK_THAT(out.error().message, Catch::Contains("no model of stage 'sepia'"));
}
