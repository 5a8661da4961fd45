// The crtforge executable: exit codes (0 ok, 1 validation failure, 2 bad usage or input), one-line
// errors naming file, line and field, and no partial output on failure.
#include <filesystem>

#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

size_t line_count(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

void check_usage_error(const test::CommandResult& r, const std::string& needle) {
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_THAT(r.err, Catch::StartsWith("crtforge: "));
    CHECK_THAT(r.err, Catch::Contains(needle));
}

}  // namespace

TEST_CASE("list prints one name per line for scripts", "[cli]") {
    auto presets = test::run_crtforge("list presets");
    CHECK(presets.exit_code == 0);
    CHECK(line_count(presets.out) == test::shipped_library().presets().size());
    CHECK_THAT(presets.out, Catch::Contains("quiet-frame\n"));
    auto targets = test::run_crtforge("list targets");
    CHECK(targets.out == "spirv\nglsl450\nglsl330\nglsles300\nhlsl50\nhlsl60\n");
    auto all = test::run_crtforge("list");
    CHECK(all.exit_code == 0);
    CHECK_THAT(all.out, Catch::Contains("scanlinePeriodPx"));
    CHECK_THAT(all.out, Catch::Contains("[runtime]"));
}

TEST_CASE("help on every command exits 0", "[cli]") {
    for (const char* cmd : {"--help", "list --help", "generate --help", "export --help", "assemble --help"}) {
        INFO(cmd);
        auto r = test::run_crtforge(cmd);
        CHECK(r.exit_code == 0);
        CHECK_THAT(r.out, Catch::Contains("Usage"));
    }
}

TEST_CASE("bad usage gets exit 2 and a one-line message naming the argument", "[cli][errors]") {
    check_usage_error(test::run_crtforge(""), "subcommand");
    check_usage_error(test::run_crtforge("generate --preset nope --target glsl330"), "--preset");
    check_usage_error(test::run_crtforge("generate --preset classic --target metal"), "--target");
    check_usage_error(test::run_crtforge("generate --preset classic"), "--target");
    check_usage_error(test::run_crtforge("export"), "--out");
    check_usage_error(test::run_crtforge("export --out /tmp/x --precision low"), "--precision");
    check_usage_error(test::run_crtforge("export --out /tmp/x --uniforms maskBlend"), "--uniforms");
    check_usage_error(test::run_crtforge("list colours"), "what");
    check_usage_error(test::run_crtforge("--templates /nonexistent list"), "/nonexistent");
}

TEST_CASE("a broken preset file: exit 2, file:line and field, no output directory", "[cli][errors]") {
    test::ScratchTemplates t;
    t.write("presets/broken.toml", "name = \"broken\"\ndoc = \"d\"\n[stages.scanlines]\nscanlineIntensity = 7\n");
    test::TempDir tmp;
    const std::string out = tmp / "out";
    auto r = test::run_crtforge("--templates '" + t.dir() + "' export --out '" + out + "'");
    check_usage_error(r, "presets/broken.toml:4");
    CHECK_THAT(r.err, Catch::Contains("field 'stages.scanlines.scanlineIntensity'"));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("a broken template snippet: exit 2 at the snippet's line, no output", "[cli][errors]") {
    test::ScratchTemplates t;
    t.write("stages/tonemap.glsl", "// line 1\nvec3 tonemap_saturate(vec3 color, CrtFrag frag) {\n    return clamp(color, 0.0, oops);\n}\n");
    test::TempDir tmp;
    const std::string out = tmp / "out";
    auto r = test::run_crtforge("--no-cache --templates '" + t.dir() + "' export --out '" + out + "'");
    check_usage_error(r, "stages/tonemap.glsl:3");
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("generate and export write the promised files", "[cli]") {
    test::TempDir tmp;
    auto gen = test::run_crtforge("--no-cache generate --preset quiet-frame --target hlsl50 --out '" + tmp.path() + "/g'");
    CHECK(gen.exit_code == 0);
    CHECK(fs::exists(tmp / "g/quiet-frame.ps.hlsl"));
    CHECK(fs::exists(tmp / "g/quiet-frame.vs.hlsl"));

    auto printed = test::run_crtforge("--no-cache generate --preset webgpu-post --target glsles300");
    CHECK(printed.exit_code == 0);
    CHECK_THAT(printed.out, Catch::StartsWith("#version 300 es"));

    auto exp = test::run_crtforge("--cache-dir '" + tmp.path() + "/cache' export --out '" + tmp.path() +
                                  "/e' --preset classic,passthrough --target spirv --target glsl330");
    CHECK(exp.exit_code == 0);
    CHECK(fs::exists(tmp / "e/manifest.json"));
    CHECK(fs::exists(tmp / "e/spirv/classic.frag.spv"));
    CHECK(fs::exists(tmp / "e/glsl330/passthrough.vert"));
    CHECK_FALSE(fs::exists(tmp / "e/hlsl50"));

    // The same export again: everything comes from the content-hash cache, nothing recompiles.
    auto again = test::run_crtforge("--cache-dir '" + tmp.path() + "/cache' export --out '" + tmp.path() +
                                    "/e2' --preset classic,passthrough --target spirv --target glsl330");
    CHECK(again.exit_code == 0);
    CHECK_THAT(again.out, Catch::Contains(" 0 misses"));
}
