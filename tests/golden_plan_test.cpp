// The scene matrix as data (golden/plan.toml): configurations, draws, stage-isolation presets,
// expected failures, the errors a bad plan gets; and the reference's unstable-pixel maps.
#include <filesystem>
#include <set>

#include <catch2/catch.hpp>

#include "crtforge/files.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/validate/validation.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

using test::golden_dir;

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
    for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

// The plan of `text`, or its error.
Result<std::vector<GoldenEntry>> plan_of(const std::string& text) {
    static test::TempDir dir;
    REQUIRE(write_file_atomic(dir / "plan.toml", text).ok());
    return golden_plan(test::validation_library(), dir.path());
}

}  // namespace

std::string testing_columns(const std::set<int>& columns) {
    std::string out;
    for (int x : columns) out += std::to_string(x) + " ";
    return out;
}

TEST_CASE("the shipped plan is a matrix: sizes, configurations, stage isolation, both sets", "[golden][matrix]") {
    const auto plan = test::golden_plan_or_fail(test::validation_library(), golden_dir());
    std::set<std::string> configs, hosts;
    size_t full = 0, portrait = 0, odd = 0, k4 = 0, stages = 0, past_2_24 = 0;
    for (const GoldenEntry& e : plan) {
        configs.insert(e.config);
        if (!e.host.empty()) hosts.insert(e.host);
        full += e.full_matrix;
        portrait += e.height > e.width;
        odd += e.width % 2 == 1 && e.height % 2 == 1;
        k4 += e.width == 3840;
        stages += e.preset.rfind("stage-", 0) == 0 && e.frame == 0;
        past_2_24 += e.frame > (1 << 24);
    }
    for (const char* c : {"bezel", "draw1", "draw3", "uniforms-all", "uniforms-none", "medium", "mediump", "t1", "t1000", "t3599",
                          "t3601", "t100000", "t1e7", "mediump-t100000", "row8k", "col8k", "px1", "line", "odd", "portrait", "tiny", "colour",
                          "godot-defaults", "godot-material", "godot-screen", "web-three", "web-pixi", "web-babylon",
                          "web-app-three", "web-app-babylon"})
        CHECK(configs.count(c));
    // A `web = [...]` rule is a rule per framework adapter, each judged on the WGSL target alone.
    for (const GoldenEntry& e : plan)
        if (e.config.rfind("web-", 0) == 0) {
            CHECK(e.targets == std::vector<std::string>{"wgsl"});
            CHECK(e.config.size() > e.host.size());
            CHECK(e.config.compare(e.config.size() - e.host.size(), e.host.size(), e.host) == 0);
        }
    CHECK(hosts == std::set<std::string>{"defaults", "material", "screen", "three", "pixi", "babylon"});
    CHECK(full > 0);
    CHECK(full < plan.size());
    CHECK(portrait > 0);
    CHECK(odd > 0);
    CHECK(k4 > 0);
    // Every stage-isolation preset on flat grey, the ramp and the colour bars, the downsampling blur
    // once more on a picture four times its output's size, and the supersampled palette at 1.5
    // pixels a texel.
    size_t isolation_presets = 0;
    for (const Preset& p : test::validation_library().presets()) isolation_presets += p.test_only && p.name.rfind("stage-", 0) == 0;
    CHECK(isolation_presets >= 20);
    CHECK(stages == 3 * isolation_presets + 2);
    // Frame counters past 2^24, on the stage that reads frameCount.
    CHECK(past_2_24 == 2);
    // The pass-graph test: the original's history three frames deep, judged on a moving sprite
    // after the history has filled.
    const Preset* graph = test::validation_library().find_preset("graph-history");
    REQUIRE(graph);
    CHECK(graph->test_only);
    CHECK(graph->history_depth() == 3);
    std::set<int> graph_frames;
    for (const GoldenEntry& e : plan)
        if (e.preset == graph->name && e.input == "moving_sprite") graph_frames.insert(e.frame);
    CHECK(graph_frames == std::set<int>{12, 23});
}

TEST_CASE("every declared tier is a validation preset of its own, with goldens", "[golden][matrix]") {
    const TemplateLibrary& lib = test::validation_library();
    const auto plan = test::golden_plan_or_fail(lib, golden_dir());
    size_t declared = 0;
    for (const Preset& p : lib.presets()) {
        if (p.test_only) continue;
        for (const DeclaredTier& tier : p.tiers) {
            ++declared;
            const Preset* t = lib.find_preset(p.name + "-tier-" + tier.name);
            REQUIRE(t);
            CHECK(t->test_only);
            CHECK(t->tier_of == p.name);
            CHECK(t->passes.size() == tier.preset->passes.size());
            size_t goldens = 0;
            for (const GoldenEntry& e : plan) goldens += e.preset == t->name;
            CHECK(goldens >= 2);
        }
    }
    CHECK(declared >= 6);
    // The tier's changes are what renders: atari-ntsc's ssaa tier supersamples its palette pass.
    const Preset* ssaa = lib.find_preset("atari-ntsc-tier-ssaa");
    REQUIRE(ssaa);
    CHECK(ssaa->passes.front().supersample == 2);
    CHECK(lib.find_preset("atari-ntsc")->passes.front().supersample == 1);
}

TEST_CASE("parameter draws are fixed by the seed, inside each range and on its step grid", "[golden][matrix]") {
    const std::string rule = R"([[golden]]
why = "draws"
tag = "d"
presets = ["crt-shadow-mask", "atari-16"]
draws = 4
seed = 7
inputs = ["pixel_art"]
size = [32, 24]
)";
    auto a = plan_of(rule);
    REQUIRE(a.ok());
    auto b = plan_of(rule);
    REQUIRE(b.ok());
    REQUIRE(a.value().size() == 8);
    std::set<std::string> distinct;
    for (size_t i = 0; i < a.value().size(); ++i) {
        const GoldenEntry& e = a.value()[i];
        CHECK(e.overrides == b.value()[i].overrides);
        REQUIRE_FALSE(e.overrides.empty());
        std::string text;
        for (const auto& [name, value] : e.overrides) {
            const ParamSpec* spec = test::validation_library().find_param(name);
            REQUIRE(spec);
            CHECK(spec->runtime);
            text += name + "=" + value_to_string(value) + " ";
            if (auto d = std::get_if<double>(&value)) {
                CHECK(*d >= *spec->min);
                CHECK(*d <= *spec->max);
                if (spec->step) CHECK(std::abs(std::remainder(*d - *spec->min, *spec->step)) < 1e-9);
            }
            if (auto n = std::get_if<int64_t>(&value)) {
                CHECK(*n >= *spec->min);
                CHECK(*n <= *spec->max);
            }
        }
        distinct.insert(text);
    }
    CHECK(distinct.size() == 8);
    auto other = plan_of(replace_all(rule, "seed = 7", "seed = 8"));
    REQUIRE(other.ok());
    CHECK(other.value().front().overrides != a.value().front().overrides);
}

TEST_CASE("a bad plan names its line and field", "[golden][matrix]") {
    const std::string head = "[[golden]]\nwhy = \"x\"\npresets = \"all\"\ninputs = [\"pixel_art\"]\nsize = [8, 8]\n";
    struct Case {
        std::string extra, field, words;
    };
    const Case cases[] = {
        {"draws = 3\nseed = 1\n", "golden.draws", "tag"},
        {"tag = \"d\"\ndraws = 3\n", "golden.seed", "seed"},
        {"tag = \"A B\"\n", "golden.tag", "a-z"},
        {"tag = \"p\"\nparams = { noSuchParam = 1.0 }\n", "golden.params.noSuchParam", "no stage"},
        {"tag = \"p\"\nparams = { curvature = 2.0 }\n", "golden.params.curvature", "range"},
        {"tag = \"p\"\nparams = { curvature = nan }\n", "golden.params.curvature", "finite"},
        {"tag = \"p\"\nparams = { curvature = -inf }\n", "golden.params.curvature", "finite"},
        {"tag = \"u\"\nuniforms = \"some\"\n", "golden.uniforms", "default"},
        {"tag = \"t\"\ntime = -1.0\n", "golden.time", "seconds"},
        {"tag = \"g\"\ngodot = \"screen\"\n", "golden.godot", "godot3"},
        {"tag = \"w\"\nweb = \"three\"\n", "golden.web", "wgsl"},
        {"tag = \"w\"\ntargets = [\"wgsl\"]\nweb = \"unity\"\n", "golden.web", "three"},
        {"tag = \"w\"\ntargets = [\"wgsl\"]\nweb = [\"pixi\", \"pixi\"]\n", "golden.web", "twice"},
        {"tag = \"w\"\ntargets = [\"wgsl\"]\nweb = []\n", "golden.web", "three"},
        {"tag = \"w\"\ntargets = [\"wgsl\"]\nweb = \"three\"\ngodot = \"screen\"\n", "golden.web", "one host"},
        {"web = \"three\"\ntargets = [\"wgsl\"]\n", "golden.web", "tag"},
        {"matrix = \"huge\"\n", "golden.matrix", "full"},
        {"tolerance = { rmse = 0.1 }\n", "golden.tolerance.why", "why"},
        {"expect_fail = { targets = [\"nope\"], why = \"x\", bound = { rmse = 0.01 } }\n", "golden.expect_fail.targets", "nope"},
        {"expect_fail = { targets = [\"spirv\"], why = \"x\" }\n", "golden.expect_fail", "bound"},
        {"except = [\"nope\"]\n", "golden.except", "nope"},
    };
    for (const Case& c : cases) {
        INFO(c.extra);
        auto plan = plan_of(head + c.extra);
        REQUIRE_FALSE(plan.ok());
        CHECK(plan.error().field == c.field);
        CHECK(plan.error().line > 0);
        CHECK_THAT(plan.error().message, Catch::Contains(c.words));
    }
    // Two rules that make one id.
    auto twice = plan_of(head + head);
    REQUIRE_FALSE(twice.ok());
    CHECK_THAT(twice.error().message, Catch::Contains("give one of them a tag"));
}

TEST_CASE("stage-isolation presets are validation-only: not exported, not in 'all'", "[golden][matrix]") {
    const TemplateLibrary& lib = test::validation_library();
    const Preset* grille = lib.find_preset("stage-mask-grille");
    REQUIRE(grille);
    CHECK(grille->test_only);
    REQUIRE(grille->passes.size() == 1);
    REQUIRE(grille->passes.front().stages.size() == 1);
    CHECK(grille->passes.front().stages.front().form->name == "grille");
    ExportRequest request;
    request.targets = {TargetId::Spirv};
    auto exported = run_export(lib, request, Cache());
    REQUIRE(exported.ok());
    for (const auto& [path, data] : exported.value().files) {
        CHECK(path.find("stage-") == std::string::npos);
        CHECK(path.find("graph-") == std::string::npos);
        CHECK(path.find("-tier-") == std::string::npos);
    }
    CHECK(exported.value().files.size() > 10);
    auto plan = plan_of("[[golden]]\nwhy = \"x\"\npresets = \"all\"\ninputs = [\"flat_grey\"]\nsize = [8, 8]\n");
    REQUIRE(plan.ok());
    for (const GoldenEntry& e : plan.value()) CHECK(e.preset.rfind("stage-", 0) != 0);
}

TEST_CASE("the reference finds its own flips: a mask cell edge on a pixel centre is unstable, and only there", "[golden][judge]") {
    // maskSize 6.5 puts every other shadow-mask cell edge exactly on a pixel centre (x + 0.5 = 6.5 k).
    auto plan = plan_of(R"([[golden]]
why = "ties"
tag = "tie"
presets = ["crt-shadow-mask"]
params = { maskSize = 6.5, curvature = 0.0 }
inputs = ["flat_grey"]
size = [64, 48]
)");
    REQUIRE(plan.ok());
    REQUIRE(plan.value().size() == 1);
    const GoldenEntry& e = plan.value().front();
    auto reference = render_golden_references(test::validation_library(), {&e});
    REQUIRE(reference.ok());
    auto unstable = render_golden_unstable(test::validation_library(), {&e}, reference.value());
    REQUIRE(unstable.ok());
    std::set<int> columns;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            if (unstable.value().front().at(x, y)[0] > 0) columns.insert(x);
    REQUIRE_FALSE(columns.empty());
    // Only columns at cell edges: x + 0.5 = 6.5 k (k odd) -> x = 6, 19, 32, 45, 58.
    INFO("unstable columns: " << ::testing_columns(columns));
    for (int x : columns) CHECK((x == 6 || x == 19 || x == 32 || x == 45 || x == 58));
    // A flip there is allowed; the same change elsewhere is not.
    Image flipped = reference.value().front();
    const int at = *columns.begin();
    Image moved = flipped;
    for (int y = 0; y < 48; ++y)
        for (int c = 0; c < 3; ++c) moved.at(at, y)[c] = moved.at(at, y)[c] + unstable.value().front().at(at, y)[0] * 0.9f;
    const Tolerance tolerance = e.tolerance;
    auto allowed = judge(moved, flipped, tolerance, 0, &unstable.value().front());
    REQUIRE(allowed.ok());
    CHECK(allowed.value().passed);
}

TEST_CASE("expect_fail: a tracked defect fails as expected within its bound, and worse or a pass fails", "[golden][matrix]") {
    // A golden whose judge must fail (its tolerance is impossible) and one that passes, each
    // expected to fail on spirv.
    test::TempDir goldens;
    REQUIRE(write_file_atomic(goldens / "plan.toml", R"([[golden]]
why = "fails"
tag = "impossible"
presets = ["classic"]
inputs = ["pixel_art"]
size = [32, 24]
tolerance = { rmse = 0.0, pixel = 0.0, tile = 0.0, ssim = 1.0, outliers = 0.0, why = "impossible bounds, for the test" }
expect_fail = { targets = ["spirv"], why = "issue 0: a test", bound = { rmse = 0.01 } }

[[golden]]
why = "fails, and by more than its defect's bound"
tag = "worse"
presets = ["classic"]
inputs = ["pixel_art"]
size = [32, 24]
tolerance = { rmse = 0.0, pixel = 0.0, tile = 0.0, ssim = 1.0, outliers = 0.0, why = "impossible bounds, for the test" }
expect_fail = { targets = ["spirv"], why = "issue 0: a test", bound = { rmse = 0.0, pixel = 0.0, outliers = 0.0 } }

[[golden]]
why = "passes"
tag = "fine"
presets = ["classic"]
inputs = ["pixel_art"]
size = [32, 24]
expect_fail = { targets = ["spirv"], why = "issue 0: a test", bound = { rmse = 0.01 } }
)")
                .ok());
    REQUIRE(update_goldens(test::validation_library(), goldens.path(), "").ok());
    ValidateRequest request;
    request.golden_dir = goldens.path();
    request.presets = {"classic"};
    request.targets = {TargetId::Spirv};
    auto report = run_validation(test::validation_library(), request, Cache());
    REQUIRE(report.ok());
    for (const CheckResult& c : report.value().checks) {
        if (c.check.find("impossible") != std::string::npos) {
            CHECK(c.passed);
            CHECK_THAT(c.message, Catch::StartsWith("expected failure (issue 0: a test)"));
        }
        if (c.check.find("worse") != std::string::npos) {
            CHECK_FALSE(c.passed);
            CHECK_THAT(c.message, Catch::StartsWith("worse than the tracked defect (issue 0: a test) allows"));
        }
        if (c.check.find("fine") != std::string::npos) {
            CHECK_FALSE(c.passed);
            CHECK_THAT(c.message, Catch::Contains("remove the target from expect_fail"));
        }
    }
}
