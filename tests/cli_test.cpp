// The crtforge executable: exit codes (0 ok, 1 validation failure, 2 bad usage or input), one-line
// errors naming file, line and field, and no partial output on failure.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "crtforge/validate/golden.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
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
    CHECK(targets.out == "spirv\nglsl450\nglsl330\nglsles300\nwebgl2\nhlsl50\nhlsl60\ngodot4\ngodot3\nwgsl\n");
    auto all = test::run_crtforge("list");
    CHECK(all.exit_code == 0);
    CHECK_THAT(all.out, Catch::Contains("scanlinePeriodPx"));
    CHECK_THAT(all.out, Catch::Contains("[runtime]"));
}

TEST_CASE("help on every command exits 0", "[cli]") {
    for (const char* cmd : {"--help", "list --help", "generate --help", "export --help", "assemble --help", "validate --help",
                            "render --help", "golden update --help", "report merge --help", "devices --help"}) {
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

TEST_CASE("the same code exports the same SPIR-V whatever its folder and comment lines", "[cli][determinism]") {
    // A comment moves every line of a stage (the debug info that carries the template's local
    // names records lines and files, and takes ids of its own): the optimised module must not show it.
    test::ScratchTemplates moved;
    moved.write("stages/scanlines.glsl", "// one\n// two\n// three\n" + moved.read("stages/scanlines.glsl"));
    test::TempDir tmp;
    const std::string as_shipped = "--no-cache export --preset classic --target spirv --out '" + (tmp / "a") + "'";
    const std::string as_moved = "--no-cache --templates '" + moved.dir() + "' export --preset classic --target spirv --out '" + (tmp / "b") + "'";
    REQUIRE(test::run_crtforge(as_shipped).exit_code == 0);
    REQUIRE(test::run_crtforge(as_moved).exit_code == 0);
    for (const char* file : {"spirv/classic.frag.spv", "spirv/classic.vert.spv"}) {
        INFO(file);
        const std::string a = test::slurp(tmp / ("a/" + std::string(file))), b = test::slurp(tmp / ("b/" + std::string(file)));
        CHECK(!a.empty());
        CHECK(a == b);
    }
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

TEST_CASE("render puts a preset on a user's image through a target's consumer", "[cli][render]") {
    test::TempDir tmp;
    // A user's screenshot: any format OpenImageIO reads; here a PNG written by crtforge itself.
    auto made = test::run_crtforge("render --preset passthrough --input color_bars --size 64x48 --output '" + (tmp / "shot.png") + "'");
    REQUIRE(made.exit_code == 0);
    for (const char* target : {"spirv", "glsl330", "glsles300", "hlsl60"}) {
        INFO(target);
        auto r = test::run_crtforge(std::string("--no-cache render --preset quiet-frame --target ") + target + " --input '" +
                                    (tmp / "shot.png") + "' --size 96x72 --output '" + (tmp / (std::string(target) + ".png")) + "'");
        CHECK(r.exit_code == 0);
        auto image = read_image(tmp / (std::string(target) + ".png"));
        REQUIRE(image.ok());
        CHECK(image.value().width == 96);
        CHECK(image.value().height == 72);
    }
    auto hdr = test::run_crtforge("render --preset webgpu-post --input hdr --reference --output '" + (tmp / "hdr.exr") + "'");
    CHECK(hdr.exit_code == 0);
    CHECK(fs::exists(tmp / "hdr.exr"));

    // The display's format: float keeps what the last pass drew; an 8-bit display (RetroArch's)
    // clamps it to 0..1 in 1/255 steps.
    auto max_value = [](const Image& image) { return *std::max_element(image.rgba.begin(), image.rgba.end()); };
    for (const char* display : {"rgba16f", "rgba8"}) {
        INFO(display);
        const std::string out = tmp / (std::string("hdr-") + display + ".exr");
        auto r = test::run_crtforge(std::string("render --preset passthrough --input hdr --size 64x48 --display ") + display +
                                    " --output '" + out + "'");
        REQUIRE(r.exit_code == 0);
        auto image = read_image(out);
        REQUIRE(image.ok());
        if (std::string(display) == "rgba8") {
            CHECK(max_value(image.value()) <= 1.0f);
            const float v = image.value().rgba[0] * 255.0f;
            CHECK(v == Approx(std::round(v)).margin(1e-3));
        } else {
            CHECK(max_value(image.value()) > 1.0f);
        }
    }
}

TEST_CASE("render rejects bad sizes, inputs and outputs with exit 2 and no file", "[cli][render][errors]") {
    test::TempDir tmp;
    const std::string out = tmp / "out.png";
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --size 0x10 --output '" + out + "'"), "--size");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --size 64by48 --output '" + out + "'"), "--size");
    check_usage_error(test::run_crtforge("render --preset classic --input nosuchfile.png --output '" + out + "'"), "--input");
    std::ofstream(tmp / "broken.png") << "not a png";
    check_usage_error(test::run_crtforge("render --preset classic --input '" + (tmp / "broken.png") + "' --output '" + out + "'"), "broken.png");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --output '" + (tmp / "out.bmp") + "'"), "--output");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --frame -3 --output '" + out + "'"), "--frame");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --display rgba10 --output '" + out + "'"), "--display");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --reference --display rgba8 --output '" + out + "'"),
                      "--display");
    CHECK_FALSE(fs::exists(out));
}

// A render whose consumer is missing from the machine (hidden through `env`): exit 2, the message
// names what to install, and no output file.
static void check_missing_consumer(const std::string& target, const std::string& env, const std::string& install) {
    test::TempDir tmp;
    auto r = test::run_crtforge("render --preset classic --target " + target + " --input color_bars --output '" +
                                    (tmp / "x.png") + "'", env);
    check_usage_error(r, install);
    CHECK_FALSE(fs::exists(tmp / "x.png"));
}

TEST_CASE("without a Vulkan driver, render says which package is missing", "[cli][render][errors]") {
    check_missing_consumer("spirv", "VK_ICD_FILENAMES=/nonexistent.json", "mesa-vulkan-drivers");
}

TEST_CASE("without Node.js, a WGSL render says which packages to install", "[cli][render][errors][wgsl]") {
    check_missing_consumer("wgsl", "PATH=/nonexistent", "nodejs and npm");
}

TEST_CASE("devices lists lavapipe, and golden update writes only when asked", "[cli][golden]") {
    auto devices = test::run_crtforge("devices");
    CHECK(devices.exit_code == 0);
    CHECK_THAT(devices.out, Catch::Contains("llvmpipe"));

    test::TempDir dir;
    auto no_plan = test::run_crtforge("golden update --dir '" + dir.path() + "'");
    CHECK(no_plan.exit_code == 2);
    CHECK_THAT(no_plan.err, Catch::Contains("plan.toml"));
    fs::copy_file(std::string(CRTFORGE_SOURCE_DIR) + "/golden/plan.toml", dir / "plan.toml");
    auto update = test::run_crtforge("golden update --dir '" + dir.path() + "' --filter webgpu-post.color_bars");
    CHECK(update.exit_code == 0);
    CHECK(fs::exists(dir / "webgpu-post.color_bars.320x240.f0.png"));
    CHECK_FALSE(fs::exists(dir / "classic.color_bars.320x240.f0.png"));
    auto manifest = load_golden_manifest(dir.path());
    REQUIRE(manifest.ok());
    // The CLI's library: the shipped presets and their declared tiers (no golden/stages/ here).
    TemplateLibrary with_tiers = test::shipped_library();
    REQUIRE(with_tiers.add_tier_presets().ok());
    CHECK(manifest.value().size() == test::golden_plan_or_fail(with_tiers, dir.path()).size());
}

TEST_CASE("validate exits 1 on a failing comparison and 2 on bad arguments", "[cli][validate]") {
    test::TempDir golden;
    // A golden set where one image is wrong: validate must fail it, with a report.
    fs::copy_file(std::string(CRTFORGE_SOURCE_DIR) + "/golden/plan.toml", golden / "plan.toml");
    REQUIRE(test::run_crtforge("golden update --dir '" + golden.path() + "' --filter webgpu-post.color_bars").exit_code == 0);
    Image wrong = Image::make(320, 240, {1.0f, 0.0f, 1.0f, 1.0f});
    REQUIRE(write_png(golden / "webgpu-post.color_bars.320x240.f0.png", wrong, 16).ok());
    test::TempDir report;
    auto r = test::run_crtforge("validate --golden-dir '" + golden.path() + "' --preset webgpu-post --target spirv --input color_bars --report '" +
                                report.path() + "'");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.out, Catch::Contains("FAIL webgpu-post spirv render:webgpu-post.color_bars.320x240.f0"));
    CHECK(fs::exists(report / "report.html"));
    CHECK(fs::exists(report / "images/webgpu-post.color_bars.320x240.f0/spirv.diff.png"));
    // The HTML report: the failure index first, the failing golden before the folded passing ones,
    // pictures at 1:1.
    std::ifstream html_in(report / "report.html");
    const std::string html((std::istreambuf_iterator<char>(html_in)), {});
    const size_t index = html.find("1 cause</h2>"), failing = html.find("id=\"g-webgpu-post.color_bars.320x240.f0\""),
                 folded = html.find("<details>");
    CHECK(index != std::string::npos);
    CHECK(index < failing);
    CHECK((folded == std::string::npos || failing < folded));
    CHECK_THAT(html, Catch::Contains("spirv.png\" alt=\"spirv\" width=\"320\" height=\"240\""));
    check_usage_error(test::run_crtforge("validate --shard 3/2"), "--shard");
    check_usage_error(test::run_crtforge("validate --input nothing --preset classic"), "--input");
}

TEST_CASE("render --frames writes one file per frame, an input sequence feeds them, bad patterns are errors",
          "[cli][render][scene]") {
    test::TempDir tmp;
    const std::string out = tmp / "f_%02d.png";
    auto r = test::run_crtforge("render --preset super-win --target spirv --input moving_sprite --size 320x240 --frames 2:4 --output '" +
                                out + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    for (int f : {2, 3, 4}) CHECK(fs::exists(tmp / ("f_0" + std::to_string(f) + ".png")));
    CHECK_FALSE(fs::exists(tmp / "f_01.png"));
    CHECK_FALSE(fs::exists(tmp / "f_05.png"));
    // The frames differ: the sprite moves and leaves a trail.
    auto a = read_image(tmp / "f_02.png"), b = read_image(tmp / "f_04.png");
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    auto metrics = compare_images(a.value(), b.value());
    REQUIRE(metrics.ok());
    CHECK(metrics.value().max_abs > 0.1);

    // Those files as an input sequence (frame N reads f_0N.png) through a stateless preset.
    const std::string again = tmp / "g_%d.png";
    r = test::run_crtforge("render --preset passthrough --target spirv --input '" + out + "' --frames 2:4 --output '" + again + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    auto copy = read_image(tmp / "g_4.png");
    REQUIRE(copy.ok());
    auto same = compare_images(copy.value(), b.value());
    REQUIRE(same.ok());
    CHECK(same.value().max_abs < 1.0 / 255 + 1e-6);

    // A long run shows its progress (a line per 10 % when not on a terminal); a short one does not.
    r = test::run_crtforge("render --preset super-win --target spirv --input moving_sprite --size 64x56 --frame 39 --output '" +
                           (tmp / "long.png") + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("render: frame 4/40"));
    CHECK_THAT(r.out, Catch::Contains("render: frame 40/40"));
    CHECK(r.out.find("render: frame 2/") == std::string::npos);

    // A sequence that runs out, an output without %d, --frame with --frames: usage errors, no files.
    check_usage_error(test::run_crtforge("render --preset passthrough --target spirv --input '" + out + "' --frames 2:5 --output '" +
                                         (tmp / "h_%d.png") + "'"),
                      "no frame 5");
    CHECK_FALSE(fs::exists(tmp / "h_2.png"));
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --frames 0:2 --output '" + (tmp / "x.png") + "'"),
                      "--output");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --frames 0:2 --frame 1 --output '" + out + "'"),
                      "--frame");
    check_usage_error(test::run_crtforge("render --preset classic --input color_bars --frames 3:1 --output '" + out + "'"), "--frames");
}

TEST_CASE("under GitHub Actions, validate annotates failures and writes the step summary", "[cli][validate][ci]") {
    test::TempDir golden, work;
    fs::copy_file(std::string(CRTFORGE_SOURCE_DIR) + "/golden/plan.toml", golden / "plan.toml");
    REQUIRE(test::run_crtforge("golden update --dir '" + golden.path() + "' --filter webgpu-post.color_bars").exit_code == 0);
    REQUIRE(write_png(golden / "webgpu-post.color_bars.320x240.f0.png", Image::make(320, 240, {1.0f, 0.0f, 1.0f, 1.0f}), 16).ok());
    const std::string args = "validate --golden-dir '" + golden.path() + "' --preset webgpu-post --target spirv --input color_bars --second-device none";
    auto r = test::run_crtforge(args, "GITHUB_ACTIONS=true GITHUB_STEP_SUMMARY='" + (work / "summary.md") + "'");
    CHECK(r.exit_code == 1);
    // One ::error per failed check, at the preset's file, titled by the check.
    CHECK_THAT(r.out, Catch::Contains("::error file=") && Catch::Contains("templates/presets/webgpu-post.toml,line=1,title=webgpu-post spirv render%3Awebgpu-post.color_bars"));
    std::ifstream in(work / "summary.md");
    const std::string summary((std::istreambuf_iterator<char>(in)), {});
    CHECK_THAT(summary, Catch::Contains("| spirv | 2 | 1 | 0 |"));
    CHECK_THAT(summary, Catch::Contains("| webgpu-post | spirv | render:webgpu-post.color_bars.320x240.f0 |"));
    // Outside GitHub Actions: no workflow commands.
    auto plain = test::run_crtforge(args);
    CHECK_THAT(plain.out, !Catch::Contains("::error"));
}

TEST_CASE("the CI kit's crtforge command lines use only options crtforge has", "[cli][ci]") {
    const std::string help = test::run_crtforge("--help").out + test::run_crtforge("validate --help").out +
                             test::run_crtforge("report merge --help").out;
    size_t options = 0;
    for (const char* kit : {"docs/ci/github-actions.yml", "docs/ci/gitlab-ci.yml"}) {
        std::ifstream in(std::string(CRTFORGE_SOURCE_DIR) + "/" + kit);
        REQUIRE(in);
        const std::string text((std::istreambuf_iterator<char>(in)), {});
        // Every --option on the lines that run crtforge (and their continuation lines).
        bool in_command = false;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            if (line.find("build/crtforge") != std::string::npos) in_command = true;
            else if (line.find("--") == std::string::npos || line.find('#') < line.find("--")) in_command = false;
            if (!in_command) continue;
            for (size_t at = line.find(" --"); at != std::string::npos; at = line.find(" --", at + 1)) {
                const std::string option = line.substr(at + 1, line.find_first_of(" =\"\\", at + 1) - at - 1);
                INFO(kit << ": " << option);
                CHECK_THAT(help, Catch::Contains(option + " ") || Catch::Contains(option + ","));
                ++options;
            }
        }
    }
    CHECK(options >= 12);
}
