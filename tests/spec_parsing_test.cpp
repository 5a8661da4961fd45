// Stage-spec parsing: a valid spec reads back every field; each invalid spec gets a one-line error
// naming file, line and field.
#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

const char* kValidSpec = R"(name = "demo"
doc = "A demo stage"
order = 5
selector = "demoForm"
common = ["gain"]

[[param]]
name = "demoForm"
type = "enum"
values = ["one", "two"]
default = "two"
doc = "Which formula"

[[param]]
name = "gain"
type = "float"
range = [0.0, 2.0]
step = 0.1
default = 1.0
unit = "x"
doc = "Overall gain"
runtime = true

[[param]]
name = "taps"
type = "int"
range = [1, 8]
default = 3
doc = "Number of taps"

[[param]]
name = "flip"
type = "bool"
default = false
doc = "Flip it"

[[param]]
name = "tint"
type = "color"
default = [1.0, 0.5, 0.0]
doc = "Tint colour"
runtime = true

[[form]]
name = "one"
doc = "First formula"
params = ["taps", "flip"]
color = "demo_one"

[[form]]
name = "two"
doc = "Second formula"
params = ["tint"]
builtins = ["time"]
fetch = "demo_two"
)";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
    for (size_t pos = s.find(from); pos != std::string::npos; pos = s.find(from, pos + to.size()))
        s.replace(pos, from.size(), to);
    return s;
}

// Replaces the first occurrence of `from` in the valid spec.
std::string mutate(const std::string& from, const std::string& to) {
    std::string s = kValidSpec;
    auto pos = s.find(from);
    REQUIRE(pos != std::string::npos);
    return s.replace(pos, from.size(), to);
}

}  // namespace

TEST_CASE("a valid stage spec reads back every field", "[spec]") {
    auto parsed = parse_stage_spec(kValidSpec, "demo.toml");
    REQUIRE(parsed.ok());
    const StageSpec& s = parsed.value();
    CHECK(s.name == "demo");
    CHECK(s.order == 5);
    CHECK(s.selector == "demoForm");
    REQUIRE(s.params.size() == 5);
    const ParamSpec* gain = s.find_param("gain");
    REQUIRE(gain);
    CHECK(gain->type == ParamType::Float);
    CHECK(*gain->min == 0.0);
    CHECK(*gain->max == 2.0);
    CHECK(*gain->step == Approx(0.1));
    CHECK(std::get<double>(gain->default_value) == 1.0);
    CHECK(gain->unit == "x");
    CHECK(gain->runtime);
    CHECK(gain->where.line == 14);  // the [[param]] header
    CHECK(std::get<int64_t>(s.find_param("taps")->default_value) == 3);
    CHECK(std::get<bool>(s.find_param("flip")->default_value) == false);
    CHECK(std::get<Color>(s.find_param("tint")->default_value) == Color{1.0, 0.5, 0.0});
    CHECK(std::get<std::string>(s.find_param("demoForm")->default_value) == "two");
    REQUIRE(s.forms.size() == 2);
    CHECK(s.find_form("one")->functions[static_cast<int>(Hook::Color)] == "demo_one");
    CHECK(s.find_form("two")->functions[static_cast<int>(Hook::Fetch)] == "demo_two");
    CHECK(s.find_form("two")->builtins == std::vector<Builtin>{Builtin::Time});
}

TEST_CASE("colours are accepted as #rrggbb too", "[spec]") {
    auto parsed = parse_stage_spec(mutate("default = [1.0, 0.5, 0.0]", "default = \"#ff8000\""), "demo.toml");
    REQUIRE(parsed.ok());
    const Color c = std::get<Color>(parsed.value().find_param("tint")->default_value);
    CHECK(c[0] == 1.0);
    CHECK(c[1] == Approx(128.0 / 255.0));
    CHECK(c[2] == 0.0);
}

TEST_CASE("invalid stage specs name file, line and field", "[spec][errors]") {
    struct Case {
        const char* what;
        std::string text;
        int line;
        const char* field;
        const char* message;
    };
    const Case cases[] = {
        {"TOML syntax", mutate("order = 5", "order = = 5"), 3, "", ""},
        {"missing name", mutate("name = \"demo\"\n", ""), 1, "name", "missing"},
        {"bad stage identifier", mutate("name = \"demo\"", "name = \"de mo\""), 1, "name", "identifier"},
        {"unknown top-level key", mutate("order = 5", "order = 5\ncolour = 1"), 4, "colour", "unknown key"},
        {"order not integer", mutate("order = 5", "order = \"5\""), 3, "order", "integer"},
        {"param name not identifier", mutate("name = \"gain\"", "name = \"2gain\""), 15, "param.name", "identifier"},
        {"unknown type", mutate("type = \"float\"", "type = \"double\""), 16, "param.gain.type", "not a type"},
        {"float without range", mutate("range = [0.0, 2.0]\n", ""), 14, "param.gain.range", "needs a range"},
        {"reversed range", mutate("range = [0.0, 2.0]", "range = [2.0, 0.0]"), 17, "param.gain.range", "below max"},
        {"default out of range", mutate("default = 1.0", "default = 3.0"), 19, "param.gain.default", "outside the range"},
        {"default of wrong type", mutate("default = 1.0", "default = \"high\""), 19, "param.gain.default", "must be a number"},
        {"int default not integer", mutate("default = 3", "default = 2.5"), 28, "param.taps.default", "integer"},
        {"bool default not bool", mutate("default = false", "default = 0"), 34, "param.flip.default", "true or false"},
        {"bad colour", mutate("default = [1.0, 0.5, 0.0]", "default = [1.0, 2.0, 0.0]"), 40, "param.tint.default", "colour"},
        {"enum default not a value", mutate("default = \"two\"", "default = \"three\""), 11, "param.demoForm.default", "not one of"},
        {"enum without values", mutate("values = [\"one\", \"two\"]\n", ""), 7, "param.demoForm.values", "non-empty"},
        {"missing doc", mutate("doc = \"Overall gain\"\n", ""), 14, "param.gain.doc", "missing"},
        {"runtime enum", mutate("doc = \"Which formula\"", "doc = \"Which formula\"\nruntime = true"), 13, "param.demoForm.runtime", "cannot be a runtime uniform"},
        {"runtime bool", mutate("doc = \"Flip it\"", "doc = \"Flip it\"\nruntime = true"), 36, "param.flip.runtime", "cannot be a runtime uniform"},
        {"duplicate param", mutate("name = \"taps\"", "name = \"gain\""), 24, "param.gain", "twice"},
        {"unknown param key", mutate("unit = \"x\"", "units = \"x\""), 20, "param.units", "unknown key"},
        {"form reads unknown param", mutate("params = [\"tint\"]", "params = [\"tnt\"]"), 53, "form.two.params", "not a param"},
        {"form without function", mutate("fetch = \"demo_two\"\n", ""), 50, "form.two", "at least one function"},
        {"unknown builtin", mutate("builtins = [\"time\"]", "builtins = [\"clock\"]"), 54, "form.two.builtins", "not a builtin"},
        {"selector values differ from forms", mutate("values = [\"one\", \"two\"]", "values = [\"two\", \"one\"]"), 4, "selector", "form names"},
        {"selector not enum", mutate("selector = \"demoForm\"", "selector = \"gain\""), 4, "selector", "enum param"},
        {"unused param", mutate("params = [\"taps\", \"flip\"]", "params = [\"taps\"]"), 31, "param.flip", "not read by any form"},
        {"unknown role", mutate("unit = \"x\"", "unit = \"x\"\nrole = \"speed\""), 21, "param.gain.role", "not a role"},
        {"angular_speed on an int", mutate("doc = \"Number of taps\"", "doc = \"Number of taps\"\nrole = \"angular_speed\""), 30,
         "param.taps.role", "must be a float"},
        {"angular_speed read without time", mutate("unit = \"x\"", "unit = \"x\"\nrole = \"angular_speed\""), 14,
         "param.gain.role", "without the time builtin"},
        {"quality tier of an unknown form", mutate("fetch = \"demo_two\"", "fetch = \"demo_two\"\nquality_of = \"three\""), 50,
         "form.two.quality_of", "not another form"},
        {"quality tier of itself", mutate("fetch = \"demo_two\"", "fetch = \"demo_two\"\nquality_of = \"two\""), 50,
         "form.two.quality_of", "not another form"},
        {"quality tier reading other params", mutate("fetch = \"demo_two\"", "fetch = \"demo_two\"\nquality_of = \"one\""), 50,
         "form.two.quality_of", "same params, builtins and textures"},
        {"no forms", std::string(kValidSpec).substr(0, std::string(kValidSpec).find("[[form]]")), 1, "form", "at least one"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        auto parsed = parse_stage_spec(c.text, "templates/stages/demo.toml");
        REQUIRE_FALSE(parsed.ok());
        const Diagnostic& d = parsed.error();
        CHECK(d.file == "templates/stages/demo.toml");
        CHECK(d.line == c.line);
        CHECK(d.field == c.field);
        CHECK_THAT(d.message, Catch::Contains(c.message));
        const std::string line = d.str();
        CHECK(line.find('\n') == std::string::npos);
        CHECK_THAT(line, Catch::StartsWith("templates/stages/demo.toml:" + std::to_string(c.line)));
    }
}

TEST_CASE("the shipped templates load and every stage has docs and forms", "[spec]") {
    const TemplateLibrary& lib = test::shipped_library();
    std::vector<std::string> names;
    for (const auto& s : lib.stages()) names.push_back(s.name);
    // The CRT-effect document's pass order, with the WebGPU pass's aberration -> tone-map -> scanlines,
    // Super Win the Game's NES-space stages before them and its screen, bloom and palette stages between.
    CHECK(names == std::vector<std::string>{"color_grade", "trails", "ringing", "ntsc_mask", "curvature", "crt_screen",
                                            "aberration", "bloom", "tonemap", "scanlines", "texel_mask", "mask", "glow",
                                            "vignette", "poisson_blur", "bloom_add", "palette"});
    for (const auto& s : lib.stages()) {
        CHECK_FALSE(s.doc.empty());
        CHECK_FALSE(s.forms.empty());
        for (const auto& p : s.params) CHECK_FALSE(p.doc.empty());
    }
}

TEST_CASE("library-level checks: global param names, pass order, file names", "[spec][errors]") {
    SECTION("a param name used by two stages") {
        test::ScratchTemplates t;
        // vignette.toml loads after mask.toml (files load in name order), so it is the one blamed.
        t.write("stages/vignette.toml", replace_all(t.read("stages/vignette.toml"), "vignetteScale", "maskSize"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/vignette.toml"));
        CHECK(lib.error().field == "param.maskSize");
        CHECK_THAT(lib.error().message, Catch::Contains("already declared at"));
    }
    SECTION("two stages with the same order") {
        test::ScratchTemplates t;
        t.write("stages/vignette.toml", replace_all(t.read("stages/vignette.toml"), "order = 60", "order = 40"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK(lib.error().field == "order");
        CHECK_THAT(lib.error().message, Catch::Contains("mask"));
    }
    SECTION("a form function missing from the snippet") {
        test::ScratchTemplates t;
        t.write("stages/glow.glsl", "// nothing here\n");
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK(lib.error().field == "form.pulse");
        CHECK_THAT(lib.error().message, Catch::Contains("glow_pulse"));
    }
    SECTION("a missing snippet file") {
        test::ScratchTemplates t;
        t.remove("stages/glow.glsl");
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/glow.glsl"));
    }
    SECTION("a param named like generated code") {
        test::ScratchTemplates t;
        t.write("stages/glow.toml", replace_all(t.read("stages/glow.toml"), "pulseWidth", "outputSize"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().message, Catch::Contains("reserved"));
    }
}
