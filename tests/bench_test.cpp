// crtforge bench's speed-against-error data (issue 11): the structure of a timing and the error of
// the timed frame against the point-sampled and the supersampled reference. No timing is asserted
// here (speed lives in the bench command); only that each figure is there and the errors mean what
// they say.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "crtforge/files.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/spirv_compiler.hpp"

#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/bench.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/cache.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

Image reference_frame(const Preset& preset, int width, int height, int supersample, const std::string& input = "pixel_art") {
    const test::SceneShot shot{[input](int frame) { return make_test_input(input, 320, 240, frame); }, width, height, {0}};
    return test::reference_scene_or_fail(test::shipped_library(), preset, shot, supersample).front();
}

// A small, quick measurement: 160x120, one draw per timing, 4x4 supersampled reference.
BenchOptions small_bench() {
    BenchOptions options;
    options.width = 160;
    options.height = 120;
    options.draws = 1;
    options.repeats = 1;
    options.supersample = 4;
    return options;
}

}  // namespace

TEST_CASE("the supersampled reference box-filters each pixel's footprint", "[bench][reference]") {
    const Preset& classic = *test::shipped_library().find_preset("classic");
    const Image point = reference_frame(classic, 160, 120, 1);
    const Image four = reference_frame(classic, 160, 120, 4);
    // Supersampling changes where the picture has detail below the pixel (scanlines, mask, the
    // bezel edge), and only a little on average.
    auto diff = compare_images(four, point);
    REQUIRE(diff.ok());
    CHECK(diff.value().rmse > 0.005);
    CHECK(diff.value().rmse < 0.2);
    // The bezel's edge is anti-aliased: some pixel on the top-left curve lies strictly between the
    // bezel's black and the picture.
    bool partial = false;
    for (int x = 0; x < 40 && !partial; ++x)
        for (int y = 0; y < 40 && !partial; ++y) {
            const float a = four.at(x, y)[3];
            partial = a > 0.05f && a < 0.95f && point.at(x, y)[3] != a;
        }
    // (classic's bezel is opaque black: its alpha is 1 everywhere; the colour shows the blend.)
    if (!partial)
        for (int x = 0; x < 40 && !partial; ++x)
            for (int y = 0; y < 40 && !partial; ++y) {
                const float g = four.at(x, y)[1], p = point.at(x, y)[1];
                partial = (p == 0.0f) != (g == 0.0f) || (g > 0.0f && g < p * 0.9f);
            }
    CHECK(partial);
    // The passthrough preset of a linear ramp (grey_ramp's top half) is the same either way: the box
    // filter of a linear function is its value at the centre.
    const Preset& passthrough = *test::shipped_library().find_preset("passthrough");
    const Image ramp4 = reference_frame(passthrough, 320, 240, 4, "grey_ramp"), ramp1 = reference_frame(passthrough, 320, 240, 1, "grey_ramp");
    double worst = 0;
    for (int y = 0; y < 118; ++y)
        for (int x = 1; x < 319; ++x) worst = std::max(worst, static_cast<double>(std::abs(ramp4.at(x, y)[0] - ramp1.at(x, y)[0])));
    CHECK(worst < 1e-3);  // the sampler models Vulkan's 8-bit sub-texel weights
}

namespace {

// Frame 2 of `preset` on pixel art at 200x150 (super-win's screen rectangle inside it).
ReferenceSceneJob small_scene_job(const Preset& preset) {
    ReferenceSceneJob job;
    job.library = &test::shipped_library();
    job.preset = &preset;
    job.source = [](int frame) { return make_test_input("pixel_art", 256, 224, frame); };
    job.width = 200;
    job.height = 150;
    job.frames = {2};
    return job;
}

}  // namespace

TEST_CASE("a reference of some display rows equals the whole picture on those rows", "[bench][reference]") {
    // super-win: six passes with feedback, its last pass drawn into the screen's rectangle.
    for (const char* name : {"classic", "super-win"}) {
        const Preset& preset = *test::shipped_library().find_preset(name);
        ReferenceSceneJob job = small_scene_job(preset);
        job.supersample = 2;
        auto whole = render_reference_scene(job);
        REQUIRE(whole.ok());
        job.display_rows = {{0, 3}, {40, 52}, {140, 150}};
        auto banded = render_reference_scene(job);
        REQUIRE(banded.ok());
        const Image& w = whole.value().front();
        const Image& b = banded.value().front();
        int inside = 0, outside_black = 0, outside = 0;
        for (int y = 0; y < job.height; ++y) {
            const bool in = y < 3 || (y >= 40 && y < 52) || y >= 140;
            for (int x = 0; x < job.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    if (in) inside += b.at(x, y)[c] == w.at(x, y)[c];
                    else outside += 1, outside_black += b.at(x, y)[c] == 0.0f;
                }
        }
        INFO(name);
        CHECK(inside == 25 * job.width * 3);  // bit for bit where rendered
        CHECK(outside_black == outside);      // and nothing shaded elsewhere
    }
}

namespace {

bool same_pixels(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height && a.rgba == b.rgba; }

}  // namespace

TEST_CASE("the display pass drawn again from its kept inputs is the scene's last pass", "[bench][reference]") {
    for (const char* name : {"classic", "atari-16", "super-win"}) {
        INFO(name);
        const Preset& preset = *test::shipped_library().find_preset(name);
        ReferenceSceneJob job = small_scene_job(preset);
        ReferenceDisplayPass kept;
        auto whole = render_reference_scene(job, &kept);
        REQUIRE(whole.ok());
        CHECK(kept.display_width == 200);
        CHECK(kept.variant.pass == &preset.passes.back());
        auto again = render_display_pass(kept, job);
        REQUIRE(again.ok());
        CHECK(same_pixels(again.value(), whole.value().front()));
        // Display rows as the scene takes them; supersampling too where the pass is the scene (in a
        // scene of several, every pass is supersampled, and the kept inputs are point-sampled).
        job.display_rows = {{0, 3}, {40, 52}};
        job.supersample = preset.passes.size() == 1 ? 2 : 1;
        auto banded = render_reference_scene(job);
        auto banded_again = render_display_pass(kept, job);
        REQUIRE(banded.ok());
        REQUIRE(banded_again.ok());
        CHECK(same_pixels(banded_again.value(), banded.value().front()));
        // A single-pass scene reads the original only: perturbed, the pass alone is the scene
        // perturbed (the input gain included).
        if (preset.passes.size() == 1) {
            job.display_rows.clear();
            job.supersample = 1;
            for (const auto& [sign, sign_y] : {std::pair{1.0, 1.0}, {-1.0, 1.0}}) {
                auto moved = render_reference_scene(jittered(job, sign, sign_y));
                auto moved_again = render_display_pass(kept, jittered(job, sign, sign_y));
                REQUIRE(moved.ok());
                REQUIRE(moved_again.ok());
                CHECK(same_pixels(moved_again.value(), moved.value().front()));
                if (preset.name == "classic") CHECK_FALSE(same_pixels(moved_again.value(), whole.value().front()));  // (a palette's output may not move)
            }
        }
    }
}

TEST_CASE("bench reports every pass and the frame's error against both references", "[bench]") {
    const BenchOptions options = small_bench();
    for (const char* name : {"crt-shadow-mask", "atari-chain", "super-win"}) {
        INFO(name);
        const Preset& preset = *test::shipped_library().find_preset(name);
        auto timing = bench_scene(test::shipped_library(), preset, options);
        REQUIRE(timing.ok());
        CHECK(timing.value().passes.size() == preset.passes.size());
        for (const PassTiming& p : timing.value().passes) {
            CHECK(p.ns > 0);
            CHECK(p.blit_ns > 0);
        }
        REQUIRE(timing.value().vs_point);
        REQUIRE(timing.value().vs_supersampled);
        // The shader matches the point reference to float precision; against the supersampled one
        // it also shows what point sampling aliases (the shadow mask's cells, the bezel's edge).
        CHECK(timing.value().vs_point->rmse < 0.002);
        // (every pass is supersampled: atari-chain's CRT pass under its palette, super-win's screen
        // pass with its texel mask alias too)
        CHECK(timing.value().vs_supersampled->rmse > 2 * timing.value().vs_point->rmse);
        const std::string table = format_scene_timing(timing.value());
        CHECK_THAT(table, Catch::Contains("error vs point-sampled fp64") && Catch::Contains("4x4 supersampled fp64"));
    }
}

TEST_CASE("a point sample exactly on a texel edge is a tie judged against the jittered reference", "[bench][reference]") {
    // 540 rows over a 240-row source: 2.25 px a texel, so every ninth row's sample falls on a texel
    // edge of the nearest-filtered palette pass, where fp32 and fp64 may each take either texel.
    BenchOptions options = small_bench();
    options.supersample = 2;
    const Preset& preset = *test::shipped_library().find_preset("atari-16");
    options.width = 720;
    options.height = 540;
    auto tied = bench_scene(test::shipped_library(), preset, options);
    REQUIRE(tied.ok());
    REQUIRE(tied.value().vs_point);
    CHECK(tied.value().vs_point->rmse < 0.002);
    // At most the rows on texel edges, and never the whole frame.
    CHECK(tied.value().point_ties <= 720 * (540 / 9 + 1));
    CHECK_THAT(format_scene_timing(tied.value()), Catch::Contains(std::to_string(tied.value().point_ties) + " pixels sample a discontinuity") ||
                                                       Catch::Contains("RMSE 0.0000"));
    // At a whole number of pixels a texel no sample is on an edge: nothing to judge as a tie.
    options.width = 640;
    options.height = 480;
    auto whole = bench_scene(test::shipped_library(), preset, options);
    REQUIRE(whole.ok());
    CHECK(whole.value().point_ties == 0);
    CHECK(whole.value().vs_point->rmse < 0.002);
}

TEST_CASE("bench --stage-costs times each pass once per stage turned off", "[bench][stages]") {
    BenchOptions options = small_bench();
    options.supersample = 0;
    options.stage_costs = true;
    // super-win: stages that read textures of their own (the LUT, the previous frame) in six passes.
    for (const char* name : {"classic", "super-win"}) {
        INFO(name);
        const Preset& preset = *test::shipped_library().find_preset(name);
        auto timing = bench_scene(test::shipped_library(), preset, options);
        REQUIRE(timing.ok());
        std::vector<std::string> expected, got;
        for (const Pass& pass : preset.passes)
            for (const ResolvedStage& rs : pass.stages) expected.push_back(pass.alias + ":" + rs.stage->name + ":" + rs.form->name);
        for (const StageCost& c : timing.value().stage_costs) {
            got.push_back(c.pass + ":" + c.stage + ":" + c.form);
            CHECK(c.blit_ns > 0);
            CHECK(std::isfinite(c.ns));
        }
        CHECK(got == expected);
        const std::string table = format_scene_timing(timing.value());
        for (const StageCost& c : timing.value().stage_costs) CHECK_THAT(table, Catch::Contains("+ " + c.stage));
        auto json = nlohmann::json::parse(bench_json({timing.value()}));
        CHECK(json[0]["stageCosts"].size() == expected.size());
        CHECK_THAT(bench_markdown({timing.value()}), Catch::Contains("| stage (form) | adds (us per draw) |"));
    }
    // Without the option: none.
    options.stage_costs = false;
    auto plain = bench_scene(test::shipped_library(), *test::shipped_library().find_preset("classic"), options);
    REQUIRE(plain.ok());
    CHECK(plain.value().stage_costs.empty());
}

TEST_CASE("a session divides every scene by the fastest blit it measured of that shape", "[bench]") {
    BenchOptions options = small_bench();
    options.supersample = 0;
    options.stage_costs = true;
    BenchSession session(test::shipped_library());
    std::vector<SceneTiming> timings;
    for (const char* name : {"classic", "subtle", "crt-pulse"}) {  // one shape: 320x240 onto 160x120
        auto timing = session.scene(*test::shipped_library().find_preset(name), options);
        REQUIRE(timing.ok());
        timings.push_back(timing.value());
    }
    double fastest = timings.front().passes.front().blit_ns;
    for (const SceneTiming& t : timings) fastest = std::min(fastest, t.passes.front().blit_ns);
    CHECK(timings.back().passes.front().blit_ns == fastest);  // the last scene already knows the fastest
    for (SceneTiming& t : timings) {
        const double before = t.passes.front().blit_ns;
        session.rebase(t);
        CHECK(t.passes.front().blit_ns == fastest);
        CHECK(t.passes.front().blit_ns <= before);
        CHECK(t.display_blit_ns == fastest);  // a single pass onto the display is the display's shape
        for (const StageCost& c : t.stage_costs) CHECK(c.blit_ns == fastest);
        CHECK(t.passes.front().own_blit_ns >= fastest);
    }
    // A scene whose blits ran well above the session's fastest was timed in a slow spell.
    SceneTiming slow = timings.front();
    slow.passes.front().own_blit_ns = 1.1 * fastest;
    CHECK(session.quiet(slow));
    slow.passes.front().own_blit_ns = 1.8 * fastest;
    CHECK_FALSE(session.quiet(slow));
}

TEST_CASE("bench --quick writes its table, JSON and plot with the Pareto front", "[bench][cli]") {
    test::TempDir out;
    auto run = test::run_crtforge("bench --quick --preset crt-shadow-mask,classic,passthrough,super-win --out " + out.path());
    REQUIRE(run.exit_code == 0);
    auto json = nlohmann::json::parse(read_text_file(out / "bench.json").value());
    // crt-shadow-mask's five quality tiers, classic's two, passthrough as written and super-win's four
    // (its declared quarter-bloom tier point-sampled and filtered, then point and filtered)
    REQUIRE(json.size() == 12);
    size_t on_front = 0;
    for (const auto& preset : json) {
        CHECK(preset["ratio"].get<double>() > 0);
        CHECK(preset["errorVsPoint"]["rmse"].get<double>() < 0.002);
        CHECK(preset["errorVsSupersampled"].is_object());
        on_front += preset["pareto"].get<bool>();
        // The front is each preset's own: a preset timed once has no alternative to beat.
        if (preset["preset"] == "passthrough") CHECK_FALSE(preset["pareto"].get<bool>());
    }
    CHECK(on_front >= 2);  // crt-shadow-mask's cheapest tier and classic's, at least
    const std::string md = read_text_file(out / "bench.md").value();
    CHECK_THAT(md, Catch::Contains("| crt-shadow-mask@point | 320x240 | 1 |") && Catch::Contains("| crt-shadow-mask@filtered | 320x240 | 1 |") &&
                       Catch::Contains("| classic@filtered | 320x240 | 1 |") && Catch::Contains("| passthrough | 320x240 | 1 |") && Catch::Contains("| crt-shadow-mask@filtered:mask | 320x240 | 1 |") && Catch::Contains("| crt-shadow-mask | filtered") &&
                       Catch::Contains("| super-win@quarter-bloom | 320x240 | 6 |") && Catch::Contains("| super-win@quarter-bloom+filtered | 320x240 | 6 |"));
    const std::string svg = read_text_file(out / "bench.svg").value();
    CHECK_THAT(svg, Catch::StartsWith("<svg") && Catch::Contains("Pareto front") && Catch::Contains(">passthrough</text>"));
}

TEST_CASE("bench at several sizes reports each size on its own", "[bench][cli]") {
    test::TempDir out;
    auto run = test::run_crtforge("bench --preset crt-shadow-mask --size 160x120,240x180 --draws 2 --repeats 1 --supersample 2 --out " + out.path());
    REQUIRE(run.exit_code == 0);
    auto json = nlohmann::json::parse(read_text_file(out / "bench.json").value());
    REQUIRE(json.size() == 10);  // five quality tiers at each size, the first size first
    std::map<int, int> on_front;  // per display width
    for (size_t i = 0; i < json.size(); ++i) {
        CHECK(json[i]["display"][0].get<int>() == (i < 5 ? 160 : 240));
        CHECK(json[i]["drawsPerTiming"].get<int>() == 2);
        on_front[json[i]["display"][0].get<int>()] += json[i]["pareto"].get<bool>();
    }
    CHECK(on_front[160] >= 1);  // each size has its own front
    CHECK(on_front[240] >= 1);
    const std::string md = read_text_file(out / "bench.md").value();
    CHECK_THAT(md, Catch::Contains("### 160x120") && Catch::Contains("### 240x180") && Catch::Contains("tier to pick at 160x120") &&
                       Catch::Contains("tier to pick at 240x180"));
    CHECK(md.find("### 160x120") < md.find("### 240x180"));
    const std::string svg = read_text_file(out / "bench.svg").value();
    CHECK_THAT(svg, Catch::Contains("(160x120, ") && Catch::Contains("(240x180, "));  // one plot per size

    // Without --draws, a timing draws as many pixels at every size.
    auto scaled = test::run_crtforge("bench --preset passthrough --no-tiers --size 320x240,640x480 --repeats 1 --supersample 0 --out " + out.path());
    REQUIRE(scaled.exit_code == 0);
    json = nlohmann::json::parse(read_text_file(out / "bench.json").value());
    REQUIRE(json.size() == 2);
    CHECK(json[0]["drawsPerTiming"].get<int>() == 4 * json[1]["drawsPerTiming"].get<int>());

    auto bad = test::run_crtforge("bench --preset passthrough --size 160x120,0x5");
    CHECK(bad.exit_code != 0);
    CHECK_THAT(bad.err, Catch::Contains("--size") && Catch::Contains("0x5"));
}

TEST_CASE("a preset's quality tiers swap each stage between its point-sampled and filtered forms", "[bench][tiers]") {
    const TemplateLibrary& lib = test::shipped_library();
    const Preset& shadow = *lib.find_preset("crt-shadow-mask");
    const std::vector<PresetTier> tiers = preset_tiers(shadow);
    // Three stages have filtered forms: point, each alone (pass order), all.
    REQUIRE(tiers.size() == 5);
    CHECK(tiers[0].tier == QualityTier::Point);
    CHECK(tiers[0].name == "point");
    CHECK(tiers[0].changes.empty());  // written with the point-sampled forms
    CHECK(tiers[1].name == "filtered:curvature");
    CHECK(tiers[1].changes == std::vector<std::string>{"pass main: curvature crt_effect -> crt_effect_filtered"});
    CHECK(tiers[2].name == "filtered:scanlines");
    CHECK(tiers[2].changes == std::vector<std::string>{"pass main: scanlines crt_effect -> crt_effect_filtered"});
    CHECK(tiers[3].name == "filtered:mask");
    CHECK(tiers[3].changes == std::vector<std::string>{"pass main: mask shadow -> shadow_filtered"});
    CHECK(tiers[4].tier == QualityTier::Filtered);
    CHECK(tiers[4].name == "filtered");
    REQUIRE(tiers[4].changes == std::vector<std::string>{"pass main: curvature crt_effect -> crt_effect_filtered",
                                                         "pass main: scanlines crt_effect -> crt_effect_filtered",
                                                         "pass main: mask shadow -> shadow_filtered"});
    const ResolvedStage* mask = tiers[4].preset.passes.front().find_stage("mask");
    REQUIRE(mask);
    CHECK(mask->form->name == "shadow_filtered");
    CHECK(std::get<std::string>(mask->values.at("maskMode")) == "shadow_filtered");
    CHECK(mask->values.at("maskSize") == shadow.passes.front().find_stage("mask")->values.at("maskSize"));
    CHECK(tiers[2].preset.passes.front().find_stage("mask")->form->name == "shadow");  // the other stages stay point-sampled
    CHECK(tiers[2].preset.passes.front().find_stage("curvature")->form->name == "crt_effect");
    // A preset written with the filtered forms offers the point ones first, as the cheaper tier.
    const std::vector<PresetTier> back = preset_tiers(tiers[4].preset);
    REQUIRE(back.size() == 5);
    CHECK(back[0].changes == std::vector<std::string>{"pass main: curvature crt_effect_filtered -> crt_effect",
                                                      "pass main: scanlines crt_effect_filtered -> crt_effect",
                                                      "pass main: mask shadow_filtered -> shadow"});
    CHECK(back[3].changes == std::vector<std::string>{"pass main: curvature crt_effect_filtered -> crt_effect",
                                                      "pass main: scanlines crt_effect_filtered -> crt_effect"});
    CHECK(back[4].changes.empty());
    // No stage with a filtered form and no declared tier: one tier, as written.
    const std::vector<PresetTier> one = preset_tiers(*lib.find_preset("passthrough"));
    REQUIRE(one.size() == 1);
    CHECK(one[0].changes.empty());
    // A declared tier that supersamples a pass does more work than point: it comes after.
    const std::vector<PresetTier> atari = preset_tiers(*lib.find_preset("atari-16"));
    REQUIRE(atari.size() == 2);
    CHECK(atari[0].name == "point");
    CHECK(atari[1].name == "ssaa");
    CHECK(atari[1].changes == std::vector<std::string>{"pass main: supersample 1 -> 2"});
    CHECK(atari[1].preset.passes.front().supersample == 2);
}

TEST_CASE("a supersampled pass draws its own reference and aliases less than point", "[bench][tiers][reference]") {
    // 1.5 display pixels a texel: nearest-filtered texel edges cross pixels, which point sampling
    // aliases and atari-16's ssaa tier (2 x 2 points a pixel) box-filters.
    BenchOptions options = small_bench();
    options.width = 480;
    options.height = 360;
    options.supersample = 4;
    const std::vector<PresetTier> tiers = preset_tiers(*test::shipped_library().find_preset("atari-16"));
    REQUIRE(tiers.size() == 2);
    BenchSession session(test::shipped_library());
    auto point = session.tier(tiers, 0, options);
    auto ssaa = session.tier(tiers, 1, options);
    REQUIRE(point.ok());
    REQUIRE(ssaa.ok());
    CHECK(ssaa.value().tier == "ssaa");
    CHECK(ssaa.value().vs_point->rmse < 0.002);  // the GPU's four points are the reference's
    CHECK(ssaa.value().vs_supersampled->rmse < 0.5 * point.value().vs_supersampled->rmse);
    CHECK(ssaa.value().cost().samples == 4 * point.value().cost().samples);
}

TEST_CASE("each filtered form is its point form averaged over each pixel", "[bench][tiers][reference]") {
    // On flat grey the filtered tier's reference equals the point tier's reference supersampled
    // finely (the box filter the filtered form computes exactly), and it is far from the point one.
    const TemplateLibrary& lib = test::validation_library();
    for (const char* name : {"stage-mask-shadow-filtered", "stage-mask-grille-filtered", "stage-scanlines-quiet-frame-filtered",
                             "stage-scanlines-crt-effect-filtered", "stage-curvature-atari-filtered",
                             "stage-curvature-crt-effect-filtered", "stage-curvature-quiet-frame-filtered",
                             "stage-texel-mask-pincushion-filtered", "stage-scanlines-period-filtered"}) {
        INFO(name);
        const std::vector<PresetTier> tiers = preset_tiers(*lib.find_preset(name));
        REQUIRE(tiers.size() == 2);
        const Image filtered = reference_frame(tiers[1].preset, 96, 64, 1, "flat_grey");
        const Image point = reference_frame(tiers[0].preset, 96, 64, 1, "flat_grey");
        const Image box = reference_frame(tiers[0].preset, 96, 64, 16, "flat_grey");
        auto vs_box = compare_images(filtered, box), point_vs_box = compare_images(point, box);
        REQUIRE(vs_box.ok());
        REQUIRE(point_vs_box.ok());
        CHECK(vs_box.value().rmse < 0.01);
        CHECK(point_vs_box.value().rmse > 5 * vs_box.value().rmse);
    }
}

TEST_CASE("the downsampling blur averages its 13 taps over each output pixel as the supersampled reference does", "[bench][reference]") {
    // A 320x240 picture shrunk to 80x60: poisson_filtered's 4 x 4 points per output pixel are the
    // 4 x 4 supersampled reference's, so the two agree to double precision; read once per pixel the
    // blur aliases the picture's detail.
    const TemplateLibrary& lib = test::validation_library();
    const Preset& filtered = *lib.find_preset("stage-poisson-blur-filtered");
    const Preset& point = *lib.find_preset("stage-poisson-blur");
    const Image mean = reference_frame(filtered, 80, 60, 1);
    const Image box = reference_frame(point, 80, 60, 4);
    const Image once = reference_frame(point, 80, 60, 1);
    auto exact = compare_images(mean, box), aliased = compare_images(once, box);
    REQUIRE(exact.ok());
    REQUIRE(aliased.ok());
    CHECK(exact.value().max_abs < 1e-6);
    CHECK(aliased.value().rmse > 1e-3);
    // Not shrinking (the upsample of a bloom), it is the point form.
    auto same = compare_images(reference_frame(filtered, 640, 480, 1), reference_frame(point, 640, 480, 1));
    REQUIRE(same.ok());
    CHECK(same.value().max_abs == 0.0);
}

// The edge anti-aliased bezel spreads the screen's edge over a pixel or two, exactly where the golden
// judge allows a render the golden's own 3x3 variation (a sub-pixel shift at a discontinuity), so a
// wrong edge profile could pass validation: here the Vulkan render must match the reference of the
// same form pixel for pixel, with no such allowance.
TEST_CASE("the edge anti-aliased bezel renders its reference's edge profile", "[bench][tiers][vulkan]") {
    const TemplateLibrary& lib = test::validation_library();
    TargetRenderer renderer;
    const test::SceneShot shot{[](int frame) { return make_test_input("grey_ramp", 320, 240, frame); }, 96, 64, {0}};
    for (const char* name : {"stage-curvature-atari-filtered", "stage-curvature-crt-effect-filtered", "stage-curvature-quiet-frame-filtered"}) {
        INFO(name);
        const Preset& preset = *lib.find_preset(name);
        auto compiled = compile_scene(lib, preset, {}, Cache());
        REQUIRE(compiled.ok());
        auto m = compare_images(test::render_scene_or_fail(renderer, preset, compiled.value(), shot).front(),
                                test::reference_scene_or_fail(lib, preset, shot).front());
        REQUIRE(m.ok());
        CHECK(m.value().max_abs < 0.004);
    }
}

TEST_CASE("bench measures every tier against the point tier's supersampled picture", "[bench][tiers]") {
    BenchOptions options = small_bench();
    const std::vector<PresetTier> tiers = preset_tiers(*test::shipped_library().find_preset("crt-shadow-mask"));
    BenchSession session(test::shipped_library());
    std::vector<double> errors;
    for (size_t i = 0; i < tiers.size(); ++i) {
        auto timing = session.tier(tiers, i, options);
        REQUIRE(timing.ok());
        CHECK(timing.value().tier == tiers[i].name);
        CHECK(timing.value().tier_changes == tiers[i].changes);
        REQUIRE(timing.value().vs_point);
        REQUIRE(timing.value().vs_supersampled);
        CHECK(timing.value().vs_point->rmse < 0.002);  // each tier renders its own formula exactly
        errors.push_back(timing.value().vs_supersampled->rmse);
    }
    // crt-shadow-mask's 2.67 px stripes alias when point-sampled; the filtered tiers with the mask
    // in them remove most of it, the scanlines alone little, the bezel's edge (only the corners
    // fall off the screen in the CRT-effect barrel) less still.
    REQUIRE(errors.size() == 5);
    CHECK(errors[4] < 0.5 * errors[0]);
    CHECK(errors[3] < 0.5 * errors[0]);
    CHECK(errors[2] > 0.8 * errors[0]);
    CHECK(errors[1] > 0.8 * errors[0]);
    CHECK(errors[1] == Approx(errors[0]).epsilon(0.05));  // a 2x2 reference is too coarse to rank the edge
    // Each tier's point reference, and the point tier's supersampled one once for all tiers; a
    // --uniforms variant of a tier draws the same pictures and renders none again.
    CHECK(session.reference_renders() == 6);
    options.variant.uniforms = UniformSelection::parse("none").value();
    options.uniforms_label = "none";
    auto baked = session.tier(tiers, 4, options);
    REQUIRE(baked.ok());
    CHECK(baked.value().label() == "crt-shadow-mask@filtered uniforms=none");
    CHECK(baked.value().vs_supersampled->rmse == Approx(errors[4]).margin(1e-4));
    CHECK(session.reference_renders() == 6);
    // The uber-shader runs the same forms behind its switches: the same picture, at its own cost.
    options.variant.uniforms = UniformSelection::parse("uber").value();
    options.uniforms_label = "uber";
    auto uber = session.tier(tiers, 4, options);
    REQUIRE(uber.ok());
    CHECK(uber.value().label() == "crt-shadow-mask@filtered uniforms=uber");
    CHECK(uber.value().vs_supersampled->rmse == Approx(errors[4]).margin(1e-4));
    CHECK(uber.value().vs_point->rmse == Approx(baked.value().vs_point->rmse).margin(1e-4));
    CHECK(uber.value().cost().instructions > 2 * baked.value().cost().instructions);
    CHECK(uber.value().cost().samples > baked.value().cost().samples);
    CHECK(session.reference_renders() == 6);
}

TEST_CASE("generate and render take a tier by name and refuse one the preset lacks", "[bench][tiers][cli]") {
    test::TempDir out;
    auto written = test::run_crtforge("generate --preset super-win --target glsl450 --out " + (out / "written"));
    auto cheap = test::run_crtforge("generate --preset super-win --target glsl450 --tier quarter-bloom --out " + (out / "cheap"));
    REQUIRE(written.exit_code == 0);
    REQUIRE(cheap.exit_code == 0);
    // The tier's downsample is the filtered blur: another bloom_down shader, the other passes alike.
    const auto down = [&](const char* dir) { return read_text_file(out / (std::string(dir) + "/super-win.bloom_down.frag")).value(); };
    const auto screen = [&](const char* dir) { return read_text_file(out / (std::string(dir) + "/super-win.screen.frag")).value(); };
    CHECK(down("written") != down("cheap"));
    CHECK(screen("written") == screen("cheap"));

    auto unknown = test::run_crtforge("generate --preset super-win --target glsl450 --tier nope --out " + (out / "nope"));
    CHECK(unknown.exit_code != 0);
    CHECK_THAT(unknown.err, Catch::Contains("--tier") && Catch::Contains("no tier 'nope'") && Catch::Contains("quarter-bloom+filtered"));
    CHECK_FALSE(std::filesystem::exists(out / "nope"));
    auto both = test::run_crtforge("generate --preset super-win --target glsl450 --tier point --resolution 64x48 --max-cost 100");
    CHECK(both.exit_code != 0);
    CHECK_THAT(both.err, Catch::Contains("not both"));

    auto rendered = test::run_crtforge("render --preset super-win --tier quarter-bloom+filtered --input pixel_art --size 128x96 --output " +
                                       (out / "tier.png"));
    INFO(rendered.err);
    CHECK(rendered.exit_code == 0);
    CHECK(std::filesystem::exists(out / "tier.png"));
}

TEST_CASE("budget mode generates the cheapest tier within --max-error and says why", "[bench][tiers][cli]") {
    test::TempDir out;
    auto loose = test::run_crtforge("generate --preset crt-shadow-mask --target glsl330 --resolution 160x120 --max-error 0.5 --out " +
                                    (out / "loose"));
    REQUIRE(loose.exit_code == 0);
    CHECK_THAT(loose.err, Catch::Contains("chose tier 'point' (as written) at 160x120"));

    auto tight = test::run_crtforge("generate --preset crt-shadow-mask --target glsl330 --resolution 160x120 --max-error 0.012 --out " +
                                    (out / "tight"));
    REQUIRE(tight.exit_code == 0);
    CHECK_THAT(tight.err, Catch::Contains("tier 'point' (as written) at 160x120") && Catch::Contains("error over 0.012") &&
                              Catch::Contains("tier 'filtered:scanlines' (pass main: scanlines crt_effect -> crt_effect_filtered)") &&
                              Catch::Contains("chose tier 'filtered:mask' (pass main: mask shadow -> shadow_filtered)") &&
                              Catch::Contains("stripes are 2.67 px wide"));
    // The filtered tier's shader, not the preset as written.
    auto exported = test::run_crtforge("generate --preset crt-shadow-mask --target glsl330 --out " + (out / "written"));
    REQUIRE(exported.exit_code == 0);
    const std::string written = read_text_file(out / "written/crt-shadow-mask.frag").value();
    CHECK(read_text_file(out / "loose/crt-shadow-mask.frag").value() == written);
    CHECK(read_text_file(out / "tight/crt-shadow-mask.frag").value() != written);

    auto none = test::run_crtforge("generate --preset crt-shadow-mask --target glsl330 --resolution 160x120 --max-error 0.00001 --out " +
                                   (out / "none"));
    CHECK(none.exit_code == 1);
    CHECK_THAT(none.err, Catch::Contains("no quality tier of 'crt-shadow-mask' meets the budget at 160x120"));
    CHECK_FALSE(std::filesystem::exists(out / "none"));

    for (const char* args : {"--resolution 160x120", "--max-error 0.1", "--resolution 0x120 --max-cost 4", "--resolution 160x120 --max-error 2",
                             "--resolution 160x120 --max-error nan", "--resolution 160x120 --max-cost nan"}) {
        INFO(args);
        auto bad = test::run_crtforge(std::string("generate --preset crt-shadow-mask --target glsl330 ") + args);
        CHECK(bad.exit_code == 2);
    }
}

TEST_CASE("the static shader cost counts instructions, texture reads and transcendentals", "[bench]") {
    CompileOptions options;
    options.stage = ShaderStage::Fragment;
    options.source_name = "<cost>";
    auto spirv = compile_to_spirv(R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() {
    vec4 a = texture(source, vTexCoord);
    vec4 b = texelFetch(source, ivec2(vTexCoord * 8.0), 0);
    fragColor = a * sin(vTexCoord.x * 7.0) + b * pow(vTexCoord.y, 2.2) + sqrt(vTexCoord.xyxy);
})", options);
    REQUIRE(spirv.ok());
    const ShaderCost cost = spirv_cost(spirv.value());
    CHECK(cost.samples == 2);
    CHECK(cost.transcendentals == 2);  // sin and pow; sqrt is not one
    CHECK(cost.instructions > 10);
    CHECK(spirv_cost({}).instructions == 0);
    CHECK(spirv_cost({0x07230203u, 0, 0, 0, 0, 0xFFFF0000u}).instructions == 0);  // a malformed word count stops the count

    // Baking params folds code away: classic with every param a constant is smaller than with its
    // live ones, and bench reports both variants.
    test::TempDir out;
    auto run = test::run_crtforge("bench --quick --no-tiers --preset classic --uniforms none,default,uber --supersample 0 --out " + out.path());
    REQUIRE(run.exit_code == 0);
    auto json = nlohmann::json::parse(read_text_file(out / "bench.json").value());
    REQUIRE(json.size() == 3);
    CHECK(json[0]["uniforms"] == "none");
    CHECK(json[1]["uniforms"] == "default");
    CHECK(json[2]["uniforms"] == "uber");
    CHECK(json[0]["shader"]["instructions"].get<int>() < json[1]["shader"]["instructions"].get<int>());
    CHECK(json[0]["shader"]["textureSamples"] == json[1]["shader"]["textureSamples"]);
    // The all-stages uber-shader holds every stage's code: many times the instructions and reads.
    CHECK(json[2]["shader"]["instructions"].get<int>() > 4 * json[1]["shader"]["instructions"].get<int>());
    CHECK(json[2]["shader"]["textureSamples"].get<int>() > json[1]["shader"]["textureSamples"].get<int>());
    CHECK_THAT(read_text_file(out / "bench.md").value(), Catch::Contains("| classic uniforms=none | 320x240 | 1 |") &&
                                                          Catch::Contains("| classic uniforms=uber | 320x240 | 1 |"));
    CHECK(test::run_crtforge("bench --quick --preset classic --uniforms some").exit_code == 2);
}

namespace {

// A RetroArch pass whose parameters decide its work: a loop bound and a branch. Baked (crtforge's
// export), the loop and the branch fold away; as uniforms (RetroArch's compile) they stay.
const std::string kParamHeavyPass = test::slang_program(
    {"float TAPS; float WARM; ",
     "#pragma parameter TAPS \"Taps\" 3.0 1.0 8.0 1.0\n#pragma parameter WARM \"Warm tint\" 0.0 0.0 1.0 1.0\n", "", "",
     "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
     "void main() {\n"
     "    vec3 sum = vec3(0.0);\n"
     "    for (int i = 0; i < int(params.TAPS); ++i)\n"
     "        sum += texture(Source, vTexCoord + vec2(float(i) * params.SourceSize.z, 0.0)).rgb;\n"
     "    sum /= params.TAPS;\n"
     "    if (params.WARM > 0.5) sum *= vec3(1.1, 1.0, 0.8);\n"
     "    FragColor = vec4(pow(sum, vec3(2.0)), 1.0);\n"
     "}\n"});

}  // namespace

TEST_CASE("bench --versus-retroarch times an imported preset as RetroArch compiles it and as crtforge exports it", "[bench][retroarch][cli]") {
    test::TempDir dir;
    {
        std::ofstream(dir / "taps.slang") << kParamHeavyPass;
        std::ofstream(dir / "taps.slangp") << "shaders = 1\nshader0 = taps.slang\nscale_type0 = viewport\n";
    }
    auto run = test::run_crtforge("bench --versus-retroarch --preset " + (dir / "taps.slangp") +
                                  " --size 96x64 --draws 1 --repeats 1 --out " + (dir / "out"));
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    auto json = nlohmann::json::parse(read_text_file(dir / "out/bench.json").value());
    REQUIRE(json.size() == 2);
    // RetroArch's compile first, untiered, every parameter a uniform and glslang's code as it is.
    CHECK(json[0]["uniforms"] == "retroarch");
    CHECK(json[0]["tier"] == "");
    CHECK(json[0]["speedupVsRetroarchCompile"].is_null());
    CHECK(json[1]["uniforms"] == "none");
    // The two compiles are told apart by what they hand the driver, not by a timing.
    CHECK(json[1]["shader"]["instructions"].get<int>() < json[0]["shader"]["instructions"].get<int>());
    CHECK(json[1]["shader"]["transcendentals"].get<int>() < json[0]["shader"]["transcendentals"].get<int>());  // pow(x, 2) reduced
    // Each timed in two rounds, the second in the opposite order (a slow spell favours neither).
    CHECK(json[0]["rounds"] == 2);
    CHECK(json[1]["rounds"] == 2);
    CHECK(json[1]["retroarchCompileNs"].get<double>() == Approx(json[0]["sceneNs"].get<double>()));
    CHECK(json[1]["speedupVsRetroarchCompile"].get<double>() ==
          Approx(json[0]["sceneNs"].get<double>() / json[1]["sceneNs"].get<double>()));
    CHECK(json[1]["frameVsRetroarchCompile"]["psnr"].get<double>() >= 50.0);  // the same picture
    CHECK(json[1]["errorVsPoint"].is_null());  // an imported pass has no double-precision model
    const std::string md = read_text_file(dir / "out/bench.md").value();
    CHECK_THAT(md, Catch::Contains("### Against RetroArch's compile") && Catch::Contains("| taps uniforms=none | 96x64 | 1 |") &&
                       Catch::Contains("Speed-up over 1 scenes: mean"));
    CHECK_THAT(run.out, Catch::Contains("x RetroArch's compile ("));

    // It chooses the variants itself: a --uniforms beside it is refused, not overridden.
    auto both = test::run_crtforge("bench --versus-retroarch --uniforms all --preset " + (dir / "taps.slangp") + " --out " + (dir / "out2"));
    CHECK(both.exit_code == 2);
    CHECK_THAT(both.err, Catch::Contains("--uniforms"));
    CHECK_FALSE(std::filesystem::exists(dir / "out2"));
}

TEST_CASE("bench --keep-going reports a preset that fails and times the others", "[bench][retroarch][cli]") {
    test::TempDir dir;
    {
        std::ofstream(dir / "taps.slang") << kParamHeavyPass;
        std::ofstream(dir / "taps.slangp") << "shaders = 1\nshader0 = taps.slang\n";
        // Imports (the file parses) but cannot compile: an undeclared name in the fragment stage.
        std::string broken = kParamHeavyPass;  // a copy
        broken.replace(broken.find("sum /= params.TAPS;"), 19, "sum /= undeclared;");
        std::ofstream(dir / "broken.slang") << broken;
        std::ofstream(dir / "broken.slangp") << "shaders = 1\nshader0 = broken.slang\n";
    }
    const std::string presets = (dir / "broken.slangp") + "," + (dir / "taps.slangp");
    auto stops = test::run_crtforge("bench --no-tiers --supersample 0 --size 32x32 --draws 1 --repeats 1 --preset " + presets);
    CHECK(stops.exit_code != 0);
    CHECK_THAT(stops.out, !Catch::Contains("taps at 32x32"));
    auto goes_on = test::run_crtforge("bench --keep-going --no-tiers --supersample 0 --size 32x32 --draws 1 --repeats 1 --preset " + presets);
    CHECK(goes_on.exit_code == 1);
    CHECK_THAT(goes_on.out, Catch::Contains("taps at 32x32"));
    CHECK_THAT(goes_on.err, Catch::Contains("undeclared") && Catch::Contains("bench: 1 of 2 preset timings failed"));
}

TEST_CASE("two renders compare as an 8-bit display shows them", "[bench][retroarch]") {
    Image a = Image::make(16, 16, {0.5f, 1.5f, std::nanf(""), 1.0f});
    Image b = Image::make(16, 16, {0.5f + 0.4f / 255.0f, 1.0f, 0.0f, 1.0f});
    auto same = compare_on_8bit_display(a, b);
    REQUIRE(same.ok());
    CHECK(same.value().psnr >= 100.0);  // a clamped value, a NaN shown as 0 and a sub-step difference
    b.rgba[0] = 0.5f + 1.0f / 255.0f;
    auto step = compare_on_8bit_display(a, b);
    REQUIRE(step.ok());
    CHECK(step.value().max_abs == Approx(1.0 / 255.0));
}
