// Presets: inheritance, overrides, disabling, and every validation error with file:line:field.
#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

Result<Preset> resolve_texts(const std::vector<std::pair<std::string, std::string>>& files, const std::string& name) {
    return test::resolve_preset_texts(files, name);
}

double number(const Preset& p, const std::string& stage, const std::string& param) {
    return std::get<double>(p.find_stage(stage)->values.at(param));
}

}  // namespace

TEST_CASE("every shipped preset resolves and names its source document", "[preset]") {
    const TemplateLibrary& lib = test::shipped_library();
    std::vector<std::string> names;
    for (const auto& p : lib.presets()) names.push_back(p.name);
    CHECK(names == std::vector<std::string>{"arcade", "atari-128", "atari-16", "atari-256", "atari-64", "atari-chain",
                                            "atari-crt", "atari-ntsc", "classic", "crt-aperture-grille", "crt-pulse",
                                            "crt-shadow-mask", "heavy", "passthrough", "quiet-frame", "subtle", "super-win",
                                            "webgpu-post"});
    const Preset* pulse = lib.find_preset("crt-pulse");
    REQUIRE(pulse->find_stage("glow"));
    CHECK(number(*pulse, "glow", "pulseIntensity") == 0.03);
    CHECK(number(*pulse, "glow", "pulseWidth") == 60.0);
    CHECK(number(*pulse, "glow", "pulseSpeed") == 20.0);
    CHECK_THAT(lib.find_preset("quiet-frame")->doc, Catch::Contains("Quiet Frame"));
    CHECK_THAT(lib.find_preset("webgpu-post")->doc, Catch::Contains("crt.ts"));
    CHECK_THAT(lib.find_preset("classic")->doc, Catch::Contains("Retro CRT Effects"));
    CHECK_THAT(lib.find_preset("crt-shadow-mask")->doc, Catch::Contains("CRT effect"));
    CHECK(lib.find_preset("passthrough")->passes.front().stages.empty());
}

TEST_CASE("the Atari article's preset table is reproduced", "[preset]") {
    const TemplateLibrary& lib = test::shipped_library();
    struct Row { const char* name; double scan, curv, vig; };
    for (const Row& r : {Row{"subtle", 0.2, 0.05, 0.2}, Row{"classic", 0.5, 0.1, 0.4},
                         Row{"heavy", 0.8, 0.2, 0.6}, Row{"arcade", 0.6, 0.15, 0.3}}) {
        INFO(r.name);
        const Preset* p = lib.find_preset(r.name);
        REQUIRE(p);
        CHECK(number(*p, "scanlines", "scanlineIntensity") == r.scan);
        CHECK(number(*p, "curvature", "curvature") == r.curv);
        CHECK(number(*p, "vignette", "vignetteStrength") == r.vig);
        CHECK(p->lineage == std::vector<std::string>{r.name, "atari-crt"});
        // Inherited from atari-crt, untouched by the table.
        CHECK(p->find_stage("mask")->form->name == "atari_grille");
        CHECK(number(*p, "aberration", "rgbOffset") == 0.002);
    }
}

TEST_CASE("the documents' systems keep their defaults", "[preset]") {
    const TemplateLibrary& lib = test::shipped_library();
    const Preset* web = lib.find_preset("webgpu-post");
    CHECK(web->find_stage("scanlines")->form->name == "period");
    CHECK(number(*web, "scanlines", "scanlinePeriodPx") == 4.0);
    CHECK(number(*web, "scanlines", "scanlineStrength") == 0.3);
    CHECK(number(*web, "aberration", "aberration") == 1.0);
    CHECK(web->find_stage("tonemap") != nullptr);
    CHECK(web->find_stage("curvature") == nullptr);

    const Preset* shadow = lib.find_preset("crt-shadow-mask");
    CHECK(shadow->find_stage("mask")->form->name == "shadow");
    CHECK(number(*shadow, "mask", "maskSize") == 8.0);
    CHECK(number(*shadow, "mask", "maskIntensity") == 0.7);
    CHECK(number(*shadow, "mask", "maskBorder") == 0.8);
    CHECK(number(*shadow, "curvature", "curvature") == 0.06);
    CHECK(number(*shadow, "vignette", "vignetteExponent") == 0.4);
    CHECK(shadow->find_stage("glow") == nullptr);  // pulseEnabled defaults to false
    CHECK(lib.find_preset("crt-aperture-grille")->find_stage("mask")->form->name == "grille");

    const Preset* qf = lib.find_preset("quiet-frame");
    CHECK(number(*qf, "curvature", "curvature") == 0.10);
    CHECK(number(*qf, "bloom", "bloomStrength") == 1.4);
    CHECK(number(*qf, "mask", "maskDim") == 0.7);
    CHECK(number(*qf, "scanlines", "scanlineIntensity") == 0.5);
    CHECK(number(*qf, "vignette", "vignetteScale") == 1.0);
}

TEST_CASE("inheritance: override, disable, change form, filter", "[preset]") {
    auto base = std::make_pair(std::string("base.toml"), std::string(R"(name = "base"
doc = "Base"
filter = "nearest"
[stages.scanlines]
scanlineForm = "crt_effect"
scanlineIntensity = 0.4
scanlineSpacing = 3.0
[stages.vignette]
vignetteForm = "crt_effect"
)"));
    SECTION("override one value, inherit the rest") {
        auto p = resolve_texts({base, {"child.toml", "name = \"child\"\ndoc = \"C\"\nbase = \"base\"\n[stages.scanlines]\nscanlineIntensity = 0.9\n"}}, "child");
        REQUIRE(p.ok());
        CHECK(number(p.value(), "scanlines", "scanlineIntensity") == 0.9);
        CHECK(number(p.value(), "scanlines", "scanlineSpacing") == 3.0);
        CHECK(number(p.value(), "scanlines", "scanlineSharpness") == 1.5);  // spec default
        CHECK(p.value().filter == Filter::Nearest);
        CHECK(p.value().find_stage("vignette") != nullptr);
    }
    SECTION("disable an inherited stage") {
        auto p = resolve_texts({base, {"child.toml", "name = \"child\"\ndoc = \"C\"\nbase = \"base\"\n[stages.vignette]\nenabled = false\n"}}, "child");
        REQUIRE(p.ok());
        CHECK(p.value().find_stage("vignette") == nullptr);
        CHECK(p.value().find_stage("scanlines") != nullptr);
    }
    SECTION("switch form: inherited values the new form does not read are dropped") {
        auto p = resolve_texts({base, {"child.toml", "name = \"child\"\ndoc = \"C\"\nbase = \"base\"\n[stages.scanlines]\nscanlineForm = \"period\"\n"}}, "child");
        REQUIRE(p.ok());
        CHECK(p.value().find_stage("scanlines")->values.count("scanlineSpacing") == 0);
        CHECK(number(p.value(), "scanlines", "scanlinePeriodPx") == 4.0);
    }
    SECTION("stages come out in pass order whatever the file order") {
        auto p = resolve_texts({{"o.toml", "name = \"o\"\ndoc = \"O\"\n[stages.vignette]\n[stages.curvature]\n[stages.mask]\n"}}, "o");
        REQUIRE(p.ok());
        REQUIRE(p.value().passes.front().stages.size() == 3);
        CHECK(p.value().passes.front().stages[0].stage->name == "curvature");
        CHECK(p.value().passes.front().stages[1].stage->name == "mask");
        CHECK(p.value().passes.front().stages[2].stage->name == "vignette");
    }
}

TEST_CASE("invalid presets name file, line and field", "[preset][errors]") {
    struct Case { const char* what; std::string text; int line; const char* field; const char* message; };
    const Case cases[] = {
        {"unknown stage", "name = \"p\"\ndoc = \"d\"\n[stages.scanline]\n", 3, "stages.scanline", "unknown stage"},
        {"unknown param", "name = \"p\"\ndoc = \"d\"\n[stages.scanlines]\nscanlineIntensty = 0.5\n", 4, "stages.scanlines.scanlineIntensty", "unknown param"},
        {"out of range", "name = \"p\"\ndoc = \"d\"\n[stages.scanlines]\n\nscanlineIntensity = 1.5\n", 5, "stages.scanlines.scanlineIntensity", "outside the range"},
        {"wrong type", "name = \"p\"\ndoc = \"d\"\n[stages.mask]\nmaskQuantize = \"yes\"\n", 4, "stages.mask.maskQuantize", "true or false"},
        {"bad enum", "name = \"p\"\ndoc = \"d\"\n[stages.mask]\nmaskMode = \"trinitron\"\n", 4, "stages.mask.maskMode", "not one of"},
        {"missing doc", "name = \"p\"\n", 1, "doc", "missing"},
        {"bad name", "name = \"My Preset\"\ndoc = \"d\"\n", 1, "name", "lower-case"},
        {"bad filter", "name = \"p\"\ndoc = \"d\"\nfilter = \"cubic\"\n", 3, "filter", "linear"},
        {"unknown key", "name = \"p\"\ndoc = \"d\"\ninherit = \"x\"\n", 3, "inherit", "unknown key"},
        {"disabled with values", "name = \"p\"\ndoc = \"d\"\n[stages.mask]\nenabled = false\nmaskDim = 0.5\n", 3, "stages.mask", "disabled"},
        {"syntax", "name = \"p\"\ndoc = \"d\n", 2, "", ""},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        auto f = parse_preset_file(c.text, "presets/p.toml", &test::shipped_library());
        REQUIRE_FALSE(f.ok());
        CHECK(f.error().file == "presets/p.toml");
        CHECK(f.error().line == c.line);
        CHECK(f.error().field == c.field);
        CHECK_THAT(f.error().message, Catch::Contains(c.message));
    }
}

TEST_CASE("resolution errors: unused value, missing base, cycles", "[preset][errors]") {
    SECTION("a value the chosen form never reads") {
        auto p = resolve_texts({{"p.toml", "name = \"p\"\ndoc = \"d\"\n[stages.scanlines]\nscanlineForm = \"period\"\nscanlineSpacing = 2.0\n"}}, "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().line == 5);
        CHECK(p.error().field == "stages.scanlines.scanlineSpacing");
        CHECK_THAT(p.error().message, Catch::Contains("not read by form 'period'"));
    }
    SECTION("missing base") {
        auto p = resolve_texts({{"p.toml", "name = \"p\"\ndoc = \"d\"\nbase = \"nope\"\n"}}, "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().field == "base");
        CHECK(p.error().file == "p.toml");
    }
    SECTION("inheritance cycle") {
        auto p = resolve_texts({{"a.toml", "name = \"a\"\ndoc = \"d\"\nbase = \"b\"\n"},
                                {"b.toml", "name = \"b\"\ndoc = \"d\"\nbase = \"a\"\n"}}, "a");
        REQUIRE_FALSE(p.ok());
        CHECK_THAT(p.error().message, Catch::Contains("cycle"));
    }
    SECTION("a preset whose file name differs from its name") {
        test::ScratchTemplates t;
        t.write("presets/mine.toml", "name = \"other\"\ndoc = \"d\"\n");
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("presets/mine.toml"));
        CHECK(lib.error().field == "name");
    }
}
