// crtforge import: RetroArch presets as crtforge overlays, rendered through crtforge's targets.
// A preset of our own pins the mapping (semantics, aliases, feedback, LUTs, shared parameters,
// macro-built block access, a vertex input not named TexCoord); a curated slice of the corpus
// renders on Vulkan, GL and HLSL alike; bad input is one line and writes nothing.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <optional>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/slang_import.hpp"
#include "generator/spirv_spec_values.hpp"
#include "generator/spirv_source_key.hpp"
#include "tests/retroarch_test_support.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
using namespace crtforge::test::retroarch;

namespace {

const char* kFirstPass = R"(#version 450
layout(push_constant) uniform Push {
    vec4 SourceSize;
    float GAIN;
} params;
layout(std140, set = 0, binding = 0) uniform UBO {
    mat4 MVP;
    float SHARED;
} global;
#pragma parameter GAIN "Gain" 1.0 0.0 2.0 0.1
#pragma parameter SHARED "Shared by both passes" 0.5 0.0 1.0 0.05
#pragma name first
#define P(x) params.x
#pragma stage vertex
layout(location = 0) in vec4 Position;
layout(location = 1) in vec2 Coord;
layout(location = 0) out vec2 vTexCoord;
void main() {
    gl_Position = global.MVP * Position;
    vTexCoord = Coord;
}
#pragma stage fragment
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 FragColor;
layout(set = 0, binding = 2) uniform sampler2D Source;
void main() {
    vec2 texel = vec2(P(SourceSize).z, 0.0);
    vec3 c = (texture(Source, vTexCoord - texel).rgb + texture(Source, vTexCoord).rgb + texture(Source, vTexCoord + texel).rgb) / 3.0;
    float source = 0.5 + global.SHARED;  // a local named like crtforge's main input
    FragColor = vec4(c * P(GAIN) * source, 1.0);
}
)";

const char* kSecondPass = R"(#version 450
layout(push_constant) uniform Push {
    vec4 OriginalSize;
    vec4 OutputSize;
    vec4 tintSize;
    uint FrameCount;
    float SHARED;
    float UNKNOWN_MEMBER;
} params;
layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; } global;
#pragma parameter SHARED "Shared by both passes" 0.5 0.0 1.0 0.05
#pragma stage vertex
layout(location = 0) in vec4 Position;
layout(location = 1) in vec2 TexCoord;
layout(location = 0) out vec2 vTexCoord;
layout(location = 1) out float origWidth;
void main() {
    gl_Position = global.MVP * Position;
    vTexCoord = TexCoord;
    origWidth = params.OriginalSize.x;
}
#pragma stage fragment
layout(location = 0) in vec2 vTexCoord;
layout(location = 1) in float origWidth;
layout(location = 0) out vec4 FragColor;
layout(set = 0, binding = 2) uniform sampler2D first;
layout(set = 0, binding = 3) uniform sampler2D firstFeedback;
layout(set = 0, binding = 4) uniform sampler2D tint;
layout(set = 0, binding = 5) uniform sampler2D Original;
void main() {
    vec3 c = texture(first, vTexCoord).rgb * texture(tint, vec2(0.5)).rgb;
    // Wrong sizes or a garbage member light the pixel up.
    float wrong = float(origWidth != 64.0) + float(params.tintSize.x != 2.0) + float(params.OutputSize.x != 160.0) +
                  abs(params.UNKNOWN_MEMBER);
    vec3 previous = texture(firstFeedback, vTexCoord).rgb;
    FragColor = vec4(c + wrong + 0.0 * previous + 0.0 * texture(Original, vTexCoord).rgb + 0.0 * params.SHARED, 0.0);
}
)";

// The test preset in `dir`, with a 2x1 LUT.
std::string write_test_preset(const test::TempDir& dir) {
    test::write_file(dir / "shaders/first.slang", kFirstPass);
    test::write_file(dir / "shaders/second.slang", kSecondPass);
    Image lut = Image::make(2, 1, {1.0f, 0.5f, 0.25f, 1.0f});
    std::filesystem::create_directories(dir / "luts");
    REQUIRE(write_png(dir / "luts/tint.png", lut).ok());
    test::write_file(dir / "presets/test.slangp",
          "shaders = 2\n"
          "shader0 = ../shaders/first.slang\n"
          "filter_linear0 = false\n"
          "wrap_mode0 = clamp_to_edge\n"
          "shader1 = ../shaders/second.slang\n"
          "scale_type1 = viewport\n"
          "filter_linear1 = true\n"
          "textures = tint\n"
          "tint = ../luts/tint.png\n"
          "tint_linear = false\n"
          "SHARED = 0.25\n");
    return dir / "presets/test.slangp";
}

}  // namespace

TEST_CASE("an imported RetroArch preset maps its passes, textures, semantics and shared parameters onto a crtforge scene",
          "[retroarch][import]") {
    test::TempDir dir;
    const std::string slangp = write_test_preset(dir);
    auto lib = import_into(slangp, dir / "overlay", dir.path());
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    const Preset* preset = lib.value()->find_preset("test");
    REQUIRE(preset);
    REQUIRE(preset->passes.size() == 2);
    CHECK(preset->passes[0].alias == "first");
    CHECK(preset->passes[0].inputs.front().filter == Filter::Nearest);
    CHECK(preset->passes[0].inputs.front().wrap == Wrap::ClampToEdge);
    const Pass& second = preset->passes[1];
    CHECK(second.inputs.front().wrap == Wrap::ClampToBorder);  // RetroArch's default
    auto source_of = [&](const std::string& binding) {
        const PassInput* input = second.find_input(binding);
        return input ? input->from.str() : std::string("<unbound>");
    };
    CHECK(source_of("first") == "first");
    CHECK(source_of("firstFeedback") == "first@previous");
    CHECK(source_of("Original") == "original");
    CHECK(source_of("tint") == "lut:tint");
    // Readers of pass 0's output sample it as pass 1 declares (filter_linear1 = true).
    CHECK(second.find_input("first")->filter == Filter::Linear);
    CHECK(second.find_input("first")->wrap == Wrap::ClampToBorder);
    // Readers of its feedback sample the copy as pass 0 itself declares (RetroArch's
    // update_feedback_info): filter_linear0 = false, wrap_mode0 = clamp_to_edge.
    CHECK(second.find_input("firstFeedback")->filter == Filter::Nearest);
    CHECK(second.find_input("firstFeedback")->wrap == Wrap::ClampToEdge);
    CHECK(second.find_input("tint")->filter == Filter::Nearest);
    // One parameter namespace: SHARED is one value, the preset's 0.25, in both passes.
    CHECK(std::get<double>(preset->passes[0].stages.front().values.at("SHARED")) == 0.25);
    CHECK(std::get<double>(preset->passes[1].stages.front().values.at("SHARED")) == 0.25);
    CHECK(std::get<double>(preset->passes[0].stages.front().values.at("GAIN")) == 1.0);

    // Flat grey 0.4 through both passes: 0.4 * GAIN 1 * (0.5 + 0.25), stored as 8 bits, times the
    // LUT's (1, 0.5, 0.25); any wrong size or unset member adds 1.
    const Image input = Image::make(64, 48, {0.4f, 0.4f, 0.4f, 1.0f});
    TargetRenderer renderer;
    const float first = std::round(0.3f * 255.0f) / 255.0f;
    for (TargetId target : {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50}) {
        INFO(target_info(target).name);
        const std::vector<Image> images = render_imported_or_fail(renderer, *lib.value(), *preset, target, input, 160, 120, {0, 2});
        for (const Image& image : images) {
            const float* p = image.rgba.data() + (60 * 160 + 80) * 4;
            CHECK(p[0] == Approx(first).margin(1.5 / 255));
            CHECK(p[1] == Approx(first * 0.5f).margin(1.5 / 255));
            CHECK(p[2] == Approx(first * 0.25f).margin(1.5 / 255));
            CHECK(p[3] == 1.0f);  // RetroArch's display ignores the last pass's alpha
        }
    }
}

// The vertex stage that passes the quad through, and the fragment stage's interface up to main().
const std::string kPassThroughStages = R"(#pragma stage vertex
layout(location = 0) in vec4 Position;
layout(location = 1) in vec2 TexCoord;
layout(location = 0) out vec2 vTexCoord;
void main() {
    gl_Position = global.MVP * Position;
    vTexCoord = TexCoord;
}
#pragma stage fragment
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 FragColor;
layout(set = 0, binding = 2) uniform sampler2D Source;
)";

// A pass two presets share, which reads one of the parameters its include declares.
const std::string kSharedPass = std::string(R"(#version 450
layout(push_constant) uniform Push {
    vec4 SourceSize;
    vec4 OriginalSize;
    float READ;
    float UNREAD;
    float SET;
} params;
layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; float UNREAD_TOO; } global;
#pragma parameter READ "Read by the pass" 0.5 0.0 1.0 0.05
#pragma parameter UNREAD "Declared, never read" 0.5 0.0 1.0 0.05
#pragma parameter UNREAD_TOO "Declared, never read" 0.5 0.0 1.0 0.05
#pragma parameter SET "0: none, 1..2: a row of the table" 0.0 0.0 2.0 1.0
)") + kPassThroughStages + R"(const vec3 kTable[2] = vec3[2](vec3(0.5), vec3(0.25));
void main() {
    vec2 textureSize = params.OriginalSize.xy;  // a local named like the builtin the size is read with (yee64)
    // An index valid only while SET is no constant expression (crt-sony-megatron's pattern).
    const uint set = uint(params.SET);
    const vec3 tint = set == 0u ? vec3(1.0) : kTable[set - 1u];
    FragColor = vec4(texture(Source, vTexCoord).rgb * params.READ * tint + (params.SourceSize.z + textureSize.x) * 0.0, 1.0);
}
)";

// The same reads, with a local that takes the instance's name: the struct stays, shadowed there.
const std::string kShadowingPass = std::string(R"(#version 450
layout(push_constant) uniform Push { float READ; } params;
layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; } global;
#pragma parameter READ "Read by the pass" 0.5 0.0 1.0 0.05
)") + kPassThroughStages + R"(float halve(float params) { return params * 0.5; }
void main() {
    FragColor = vec4(texture(Source, vTexCoord).rgb * halve(params.READ * 2.0), 1.0);
}
)";

TEST_CASE("an imported pass reads its block members in place and holds only the constants it names: shared passes compile alike",
          "[retroarch][import]") {
    test::TempDir dir;
    test::write_file(dir / "shaders/shared.slang", kSharedPass);
    test::write_file(dir / "shaders/shadowing.slang", kShadowingPass);
    auto preset_text = [](const std::string& shader, double read, double unread) {
        return fmt::format("shaders = 1\nshader0 = ../shaders/{}\nREAD = {}\nUNREAD = {}\nUNREAD_TOO = {}\n", shader, read, unread, unread);
    };
    test::write_file(dir / "presets/a.slangp", preset_text("shared.slang", 0.75, 0.25));
    test::write_file(dir / "presets/b.slangp", preset_text("shared.slang", 0.75, 0.5));
    test::write_file(dir / "presets/c.slangp", preset_text("shared.slang", 0.5, 0.25));
    test::write_file(dir / "presets/shadow.slangp", preset_text("shadowing.slang", 0.75, 0.25));
    VariantOptions baked;
    baked.uniforms = UniformSelection::parse("none").value();
    auto compile = [&](const std::string& name) -> std::pair<std::shared_ptr<TemplateLibrary>, CompiledVariant> {
        auto lib = import_into(dir / ("presets/" + name + ".slangp"), dir / ("overlay-" + name), dir.path());
        INFO((lib.ok() ? std::string() : lib.error().str()));
        REQUIRE(lib.ok());
        const Preset* preset = lib.value()->find_preset(name);
        REQUIRE(preset);
        auto compiled = compile_variant(*lib.value(), *preset, baked, Cache());
        INFO((compiled.ok() ? std::string() : compiled.error().str()));
        REQUIRE(compiled.ok());
        return {lib.value(), std::move(compiled.value())};
    };
    const auto a = compile("a"), b = compile("b"), c = compile("c"), shadow = compile("shadow");

    // The reads are in place, with no struct; the unread parameters are not in the pass at all.
    CHECK(a.second.fragment_glsl.find("struct CrtRetroArch_") == std::string::npos);
    CHECK(a.second.fragment_glsl.find("UNREAD") == std::string::npos);
    // Presets that differ only in what the pass does not read share its module; a value it
    // reads makes another one.
    CHECK(a.second.fragment == b.second.fragment);
    CHECK(a.second.fragment != c.second.fragment);
    // The table read compiles, with the baked params variables the pass never writes (as
    // constants, `SET - 1` is an index out of range).
    CHECK(a.second.fragment_glsl.find("\nfloat SET = 0.0;") != std::string::npos);
    CHECK(a.second.fragment_glsl.find("\nfloat READ = 0.75;") != std::string::npos);
    // A local named like the instance keeps the struct (the local shadows it where declared); its
    // baked params are variables there too.
    CHECK(shadow.second.fragment_glsl.find("struct CrtRetroArch_params") != std::string::npos);
    CHECK(shadow.second.fragment_glsl.find("\nfloat READ = 0.75;") != std::string::npos);

    // And each draws what its values say: READ 0.75 of a flat 0.8 (the shadowing pass halves twice READ).
    const Image input = Image::make(16, 16, {0.8f, 0.8f, 0.8f, 1.0f});
    TargetRenderer renderer;
    for (const auto* one : {&a, &c, &shadow}) {
        const Preset* preset = one->first->find_preset(one == &a ? "a" : one == &c ? "c" : "shadow");
        const std::vector<Image> images = render_imported_or_fail(renderer, *one->first, *preset, TargetId::Spirv, input, 16, 16, {0});
        const double expected = 0.8 * (one == &c ? 0.5 : 0.75);
        CHECK(images.front().rgba[0] == Approx(expected).margin(1.0 / 255));
    }
}

TEST_CASE("a pass imported into another folder is the same compile cache entry", "[retroarch][import][cache]") {
    // `corpus` imports each preset into a new temporary folder: the #line file names differ from
    // run to run, and the compile cache must not key on them.
    test::TempDir dir;
    std::string shader = kSharedPass;
    const std::string unique = "0.5 0.0 1.0 0.05\n#pragma parameter UNREAD";  // a value no other test compiles
    shader.replace(shader.find(unique), unique.size(), "0.3125 0.0 1.0 0.05\n#pragma parameter UNREAD");
    test::write_file(dir / "shaders/shared.slang", shader);
    test::write_file(dir / "presets/only.slangp", "shaders = 1\nshader0 = ../shaders/shared.slang\n");
    const Cache cache(dir / "cache");
    auto entries = [&]() {
        size_t n = 0;
        std::error_code ec;
        for (auto it = std::filesystem::directory_iterator(dir / "cache/spirv", ec); !ec && it != std::filesystem::directory_iterator(); ++it) ++n;
        return n;
    };
    for (const char* folder : {"overlay-1", "elsewhere/overlay-2"}) {
        auto lib = import_into(dir / "presets/only.slangp", dir / folder, dir.path());
        REQUIRE(lib.ok());
        auto compiled = compile_variant(*lib.value(), *lib.value()->find_preset("only"), {}, cache);
        INFO((compiled.ok() ? std::string() : compiled.error().str()));
        REQUIRE(compiled.ok());
        CHECK(compiled.value().fragment_glsl.find(std::string(folder) + "/stages/") != std::string::npos);  // the names are there
        CHECK(entries() == 2);  // the pass's two stages, once
    }
}

TEST_CASE("crtforge import writes an overlay the CLI uses, and refuses bad presets in one line with nothing written",
          "[retroarch][import][cli]") {
    test::TempDir dir;
    const std::string slangp = write_test_preset(dir);
    auto ok = test::run_crtforge("import '" + slangp + "' --out '" + (dir / "out") + "' --root '" + dir.path() + "' --name mine");
    INFO(ok.err);
    REQUIRE(ok.exit_code == 0);
    auto listed = test::run_crtforge("--templates '" + (dir / "out") + "' list");
    CHECK(listed.out.find("mine") != std::string::npos);

    // A .slangp path goes where a preset name goes: imported on the way, beside shipped presets.
    auto rendered = test::run_crtforge("render --preset '" + slangp + "' --input pixel_art --size 64x48 --output '" +
                                       (dir / "direct.png") + "'");
    INFO(rendered.err);
    CHECK(rendered.exit_code == 0);
    CHECK(std::filesystem::exists(dir / "direct.png"));
    auto exported = test::run_crtforge("export --preset '" + slangp + "',classic --target glsl330 --out '" + (dir / "direct-export") + "'");
    INFO(exported.err);
    CHECK(exported.exit_code == 0);
    CHECK(std::filesystem::exists(dir / "direct-export/glsl330/test.first.frag"));
    CHECK(std::filesystem::exists(dir / "direct-export/glsl330/classic.frag"));
    auto both = test::run_crtforge("--templates '" + (dir / "out") + "' render --preset '" + slangp +
                                   "' --input pixel_art --output '" + (dir / "never.png") + "'");
    CHECK(both.exit_code == 2);
    CHECK(both.err.find("--templates") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "never.png"));

    struct Bad {
        const char* what;
        std::string text;
        const char* expect;
    };
    const std::vector<Bad> cases = {
        {"a missing shader", "shaders = 1\nshader0 = ../shaders/none.slang\n", "none.slang"},
        {"a malformed line", "shaders = 1\n/* a note\nshader0 = ../shaders/first.slang\n*/\n", "bad.slangp:3"},
        {"a path escaping the root", "shaders = 1\nshader0 = ../../../../../../etc/hostname\n", "shader0"},
        {"a parameter declared again with other values", "shaders = 2\nshader0 = ../shaders/first.slang\nshader1 = ../shaders/clash.slang\n",
         "SHARED"},
        {"a sampler naming no texture", "shaders = 1\nshader0 = ../shaders/stray.slang\n", "sampler 'nowhere'"},
        // Integer framebuffers (test/format.slangp's R32_UINT pass and its reader) are refused by name.
        {"an integer texture", "shaders = 1\nshader0 = ../shaders/usampler.slang\n", "sampler 'Source' is a usampler2D: integer textures"},
        {"an integer output", "shaders = 1\nshader0 = ../shaders/uint-out.slang\n", "writes a uint at location 0: integer framebuffers"},
        // A pass's name becomes an identifier and part of file names: a long one is refused where it is given.
        {"an alias too long", "shaders = 1\nshader0 = ../shaders/first.slang\nalias0 = " + std::string(100, 'A') + "\n",
         "bad.slangp:3: error: field 'alias0': 'AAAAAAAAAAAAAAAAAAAAAAAA...' is 100 characters long"},
        {"a #pragma name too long", "shaders = 1\nshader0 = ../shaders/long-name.slang\n", "error: field 'pragma name': 'BBBBBBBBBBBBBBBBBBBBBBBB...' is 5000"},
        // RetroArch's strtod reads these; a shader parameter that is not finite is refused at its line.
        {"a parameter set to inf", "shaders = 1\nshader0 = ../shaders/first.slang\nparameters = GAIN\nGAIN = inf\n",
         "bad.slangp:4: error: field 'GAIN'"},
        {"a parameter set to nan", "shaders = 1\nshader0 = ../shaders/first.slang\nGAIN = nan\n", "bad.slangp:3: error: field 'GAIN'"},
        {"a parameter past a double's range", "shaders = 1\nshader0 = ../shaders/first.slang\nGAIN = -1e999\n", "not a finite number"},
        // A scale crtforge cannot render is refused at the .slangp's line, not in the preset it would write.
        {"an absolute scale of 0", "shaders = 1\nshader0 = ../shaders/first.slang\nscale_type0 = absolute\nscale_x0 = 0.3\nscale_y0 = 4\n",
         "bad.slangp:4: error: field 'scale_x0'"},
        {"a negative source scale", "shaders = 1\nshader0 = ../shaders/first.slang\nscale_type0 = source\nscale0 = -2\n",
         "bad.slangp:4: error: field 'scale0'"},
        {"an absolute size past the limit", "shaders = 1\nshader0 = ../shaders/first.slang\nscale_type_y0 = absolute\nscale_y0 = 1e9\n",
         "bad.slangp:4: error: field 'scale_y0'"},
    };
    // shaders/<file>: `pass` with its first `from` replaced by `to`.
    auto write_changed = [&](const std::string& file, std::string pass, const std::string& from, const std::string& to) {
        pass.replace(pass.find(from), from.size(), to);
        test::write_file(dir / ("shaders/" + file), pass);
        return pass;
    };
    write_changed("clash.slang", kSecondPass, "0.5 0.0 1.0 0.05", "0.5 0.0 2.0 0.05");
    const std::string stray = write_changed("stray.slang", kFirstPass, "uniform sampler2D Source;",
                                            "uniform sampler2D Source;\nlayout(set = 0, binding = 3) uniform sampler2D nowhere;");
    write_changed("usampler.slang", kFirstPass, "uniform sampler2D Source;", "uniform usampler2D Source;");
    write_changed("uint-out.slang", kFirstPass, "out vec4 FragColor;", "out uint FragColor;");
    write_changed("long-name.slang", kFirstPass, "#pragma name first", "#pragma name " + std::string(5000, 'B'));
    for (const Bad& bad : cases) {
        INFO(bad.what);
        test::write_file(dir / "presets/bad.slangp", bad.text);
        const std::string out = dir / "bad-out";
        auto r = test::run_crtforge("import '" + (dir / "presets/bad.slangp") + "' --out '" + out + "' --root '" + dir.path() + "'");
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(bad.expect) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK_FALSE(std::filesystem::exists(out));
    }

    // The error names the line that declares the stray sampler, in the .slang itself.
    const int stray_line = 1 + static_cast<int>(std::count(stray.begin(), stray.begin() + stray.find("nowhere"), '\n'));
    test::write_file(dir / "presets/bad.slangp", "shaders = 1\nshader0 = ../shaders/stray.slang\n");
    auto located = test::run_crtforge("import '" + (dir / "presets/bad.slangp") + "' --out '" + (dir / "bad-out") + "'");
    CHECK(located.err.find("stray.slang:" + std::to_string(stray_line) + ": error: field 'sampler nowhere'") != std::string::npos);

    // A FIFO where a preset should be is refused, not read until someone writes to it.
    REQUIRE(test::run_command("mkfifo '" + (dir / "presets/fifo.slangp") + "'").exit_code == 0);
    auto fifo = test::run_command("timeout 20 '" CRTFORGE_BINARY "' import '" + (dir / "presets/fifo.slangp") + "' --out '" +
                                  (dir / "fifo-out") + "'");
    CHECK(fifo.exit_code == 2);
    CHECK(fifo.err.find("not a regular file") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "fifo-out"));
}

// A curated slice of the corpus (the whole library is `tools/retroarch-runner/agreement.sh` and,
// later, `crtforge corpus`): each preset imports and renders alike on Vulkan, GL and HLSL.
TEST_CASE("a curated slice of RetroArch's CRT presets renders alike through Vulkan, GL and HLSL", "[retroarch][import][corpus]") {
    const std::string corpus = std::string(CRTFORGE_SOURCE_DIR) + "/../shared/slang-shaders";
    if (!std::filesystem::is_directory(corpus + "/crt")) {
        WARN("no RetroArch corpus at " << corpus << ": skipped");
        return;
    }
    auto input = make_test_input("pixel_art", 256, 224);
    REQUIRE(input.ok());
    TargetRenderer renderer;
    for (const char* file : {"crt/zfast-crt.slangp", "crt/crt-easymode.slangp", "crt/crt-lottes.slangp", "crt/crt-pi.slangp"}) {
        INFO(file);
        test::TempDir dir;
        auto lib = import_into(corpus + "/" + file, dir / "overlay", corpus, "imported");
        INFO((lib.ok() ? std::string() : lib.error().str()));
        REQUIRE(lib.ok());
        const Preset* preset = lib.value()->find_preset("imported");
        REQUIRE(preset);
        const std::vector<Image> vulkan = render_imported_or_fail(renderer, *lib.value(), *preset, TargetId::Spirv, input.value(), 512, 448, {1});
        for (TargetId target : {TargetId::Glsl330, TargetId::Hlsl50}) {
            INFO(target_info(target).name);
            const std::vector<Image> other = render_imported_or_fail(renderer, *lib.value(), *preset, target, input.value(), 512, 448, {1});
            auto m = compare_images(other.front(), vulkan.front());
            REQUIRE(m.ok());
            CHECK(m.value().psnr >= 40.0);
        }
    }
}

TEST_CASE("Godot 3's screen shader of an imported pass flips texelFetch of the screen, keeps textureSize and reads a biased read's level 0", "[retroarch][import][godot]") {
    test::TempDir dir;
    test::write_file(dir / "shaders/fetch.slang",
          test::slang_program({"", "", "", "",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "void main() {\n"
                               "    ivec2 size = textureSize(Source, 0);\n"
                               "    ivec2 p = clamp(ivec2(gl_FragCoord.xy) / 2, ivec2(0), size - 1);\n"
                               "    FragColor = vec4(texelFetch(Source, p, 0).rg, texture(Source, vTexCoord, min(-16.0, float(size.x))).b, 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "fetch.slangp", "shaders = 1\nshader0 = shaders/fetch.slang\n");
    auto lib = import_into(dir / "fetch.slangp", dir / "overlay", dir.path(), "fetch");
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    auto compiled = compile_scene(*lib.value(), *lib.value()->find_preset("fetch"), {}, Cache());
    REQUIRE(compiled.ok());
    auto out = emit_target(compiled.value().front(), TargetId::Godot3, Cache());
    INFO((out.ok() ? std::string() : out.error().str()));
    REQUIRE(out.ok());
    std::string screen;
    for (const auto& f : out.value().files)
        if (f.role == "screenShader") screen = f.data;
    INFO(screen);
    // Rows count from the bottom in Godot 3's screen texture: row y of the effect is size.y - 1 - y.
    CHECK_THAT(screen, Catch::Contains("texelFetch(SCREEN_TEXTURE, ivec2((") && Catch::Contains(").x, textureSize(SCREEN_TEXTURE, 0).y - 1 - ("));
    CHECK_THAT(screen, Catch::Contains("textureSize(SCREEN_TEXTURE, 0)"));
    CHECK(screen.find("crt_flip_y(SCREEN_UV)") != std::string::npos);  // its gl_FragCoord, counted from the top
    // crt-lottes-fast's texture(Source, uv, -16.0): the screen has one level to read, so the bias
    // goes with its whole argument and the read is of level 0, as every screen read here.
    CHECK(screen.find("-16.0") == std::string::npos);
    CHECK_THAT(screen, Catch::Contains("textureLod(SCREEN_TEXTURE, crt_flip_y(") && Catch::Contains("), 0.0)"));
}

TEST_CASE("the Vulkan-only sweep bakes a program's params as specialization constants: one optimisation for presets that share "
          "the pass, the same picture as constants",
          "[retroarch][import][specialize]") {
    test::TempDir dir;
    const std::string params = "#pragma parameter GAIN \"Gain\" 0.5 0.0 2.0 0.05\n#pragma parameter SWAP \"Swap\" 0.0 0.0 1.0 1.0\n";
    test::write_file(dir / "shaders/gain.slang",
          test::slang_program({"float GAIN; float SWAP; ", params, "", "",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "void main() {\n"
                               "    vec3 c = texture(Source, vTexCoord).rgb * params.GAIN;\n"
                               "    if (params.SWAP > 0.5) c = c.bgr;\n"
                               "    FragColor = vec4(c, 1.0);\n"
                               "}\n"}));
    // A global constant made from a param: no specialization constant can be one (SPIR-V folds no
    // float arithmetic of them), so this pass falls back to constants.
    test::write_file(dir / "shaders/global.slang",
          test::slang_program({"float GAIN; ", "#pragma parameter GAIN \"Gain\" 0.5 0.0 2.0 0.05\n", "", "",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "const float kHalfGain = params.GAIN * 0.5;\n"
                               "void main() { FragColor = vec4(texture(Source, vTexCoord).rgb * kHalfGain, 1.0); }\n"}));
    test::write_file(dir / "a.slangp", "shaders = 2\nshader0 = shaders/gain.slang\nscale_type0 = source\nshader1 = shaders/global.slang\n"
                            "GAIN = 1.5\nSWAP = 1.0\n");
    test::write_file(dir / "b.slangp", "shaders = 2\nshader0 = shaders/gain.slang\nscale_type0 = source\nshader1 = shaders/global.slang\n"
                            "GAIN = 0.75\n");
    auto baked = UniformSelection::parse("none");
    REQUIRE(baked.ok());
    VariantOptions constants;
    constants.uniforms = baked.value();
    constants.local_names = false;
    VariantOptions specialized = constants;
    specialized.specialize_baked = true;

    TargetRenderer renderer;
    test::SceneShot shot{[](int) -> Result<Image> { return make_test_input("pixel_art", 16, 12, 0); }, 16, 12, {0}};
    std::vector<SpirvBinary> cleared;
    std::vector<Image> pictures;
    for (const std::string name : {"a", "b"}) {
        auto lib = import_into(dir / (name + ".slangp"), dir / ("overlay_" + name), dir.path(), name);
        INFO((lib.ok() ? std::string() : lib.error().str()));
        REQUIRE(lib.ok());
        const Preset& preset = *lib.value()->find_preset(name);
        auto as_constants = compile_scene(*lib.value(), preset, constants, Cache());
        auto as_spec = compile_scene(*lib.value(), preset, specialized, Cache());
        INFO((as_spec.ok() ? std::string() : as_spec.error().str()));
        REQUIRE(as_constants.ok());
        REQUIRE(as_spec.ok());
        // The first pass's params are specialization constants holding the preset's values ...
        auto values = spec_constant_values(as_spec.value()[0].fragment);
        std::set<float> held;
        for (const auto& [id, value] : values) {
            REQUIRE(value.words.size() == 1);
            held.insert(std::bit_cast<float>(value.words[0]));
        }
        CHECK(held == (name == "a" ? std::set<float>{1.5f, 1.0f} : std::set<float>{0.75f, 0.0f}));
        CHECK(spec_constant_values(as_constants.value()[0].fragment).empty());
        // ... the second pass could not have them and has its constant.
        CHECK(spec_constant_values(as_spec.value()[1].fragment).empty());
        SpirvBinary module = as_spec.value()[0].fragment;
        REQUIRE(clear_spec_constant_values(module));
        cleared.push_back(std::move(module));

        const Image by_constants = test::render_scene_or_fail(renderer, preset, as_constants.value(), shot).front();
        const Image by_spec = test::render_scene_or_fail(renderer, preset, as_spec.value(), shot).front();
        auto same = compare_images(by_spec, by_constants);
        REQUIRE(same.ok());
        CHECK(same.value().psnr >= 80.0);
        pictures.push_back(by_spec);
    }
    // Both presets' first pass is one module but for its values (one optimisation), and the
    // values took effect: the two pictures differ.
    CHECK(cleared[0] == cleared[1]);
    auto apart = compare_images(pictures[0], pictures[1]);
    REQUIRE(apart.ok());
    CHECK(apart.value().psnr < 20.0);
}

// A pass's stock vertex stage and the head of its fragment stage, which reads Source.
const std::string kStockHead = R"(#version 450
layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; } global;
#pragma stage vertex
layout(location = 0) in vec4 Position;
layout(location = 1) in vec2 TexCoord;
layout(location = 0) out vec2 vTexCoord;
void main() { gl_Position = global.MVP * Position; vTexCoord = TexCoord; }
#pragma stage fragment
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 FragColor;
layout(set = 0, binding = 2) uniform sampler2D Source;
)";

// A one-pixel checkerboard shown eight times smaller: through a mip chain every output pixel is
// the board's mean (levels 1.. average it to 0.5 exactly); read at level 0 with a nearest filter
// it stays black or white. The first pass copies the original (whose mip chain RetroArch never
// makes, whatever mipmap_input0 says); the second reads that copy with mipmap_input1, the
// original at level 0, and a LUT with board_mipmap.
TEST_CASE("mipmap_input and NAME_mipmap sample through a mip chain on Vulkan, GL, the shipped WebGPU driver and Godot's LUTs",
          "[retroarch][import][mipmap]") {
    test::TempDir dir;
    // Both passes: the stock vertex stage, then a fragment stage reading Source (and more).
    const std::string head = kStockHead;
    test::write_file(dir / "shaders/copy.slang", head + "void main() { FragColor = texture(Source, vTexCoord); }\n");
    test::write_file(dir / "shaders/minify.slang", head + R"(layout(set = 0, binding = 3) uniform sampler2D Original;
layout(set = 0, binding = 4) uniform sampler2D board;
void main() { FragColor = vec4(texture(Source, vTexCoord).r, texture(Original, vTexCoord).r, texture(board, vTexCoord).r, 1.0); }
)");
    Image checker = Image::make(256, 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (int c = 0; c < 4; ++c) checker.rgba[(static_cast<size_t>(y) * 256 + x) * 4 + c] = c == 3 || (x + y) % 2 ? 1.0f : 0.0f;
    std::filesystem::create_directories(dir / "luts");
    REQUIRE(write_png(dir / "luts/board.png", checker).ok());
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "mip",
          "shaders = 2\n"
          "shader0 = ../shaders/copy.slang\n"
          "filter_linear0 = false\n"
          "mipmap_input0 = true\n"
          "scale_type0 = source\n"
          "shader1 = ../shaders/minify.slang\n"
          "filter_linear1 = true\n"
          "mipmap_input1 = true\n"
          "scale_type1 = viewport\n"
          "textures = board\n"
          "board = ../luts/board.png\n"
          "board_linear = true\n"
          "board_mipmap = true\n", 2);
    const Preset* preset = lib->find_preset("mip");
    CHECK_FALSE(preset->passes[0].inputs.front().mipmap);  // mipmap_input0: RetroArch's original has no chain
    const PassInput& source = preset->passes[1].inputs.front();
    CHECK(source.mipmap);
    CHECK(source.filter == Filter::Linear);
    CHECK(source.mip_filter == Filter::Nearest);  // no pass after it has a chain: RetroArch reads the nearest level
    const PassInput* board = preset->passes[1].find_input("board");
    REQUIRE(board);
    CHECK(board->mipmap);
    CHECK(board->mip_filter == Filter::Linear);  // a linear mipmapped LUT blends its levels
    const PassInput* original = preset->passes[1].find_input("Original");
    REQUIRE(original);
    CHECK_FALSE(original->mipmap);
    // 30 x 30: no level's texel centres line up with the display's. The original's nearest
    // read lands on texel edges at some columns, where drivers may pick either neighbour: each
    // target is judged on its own, and the chains' channels against Vulkan's. Vulkan runs under
    // its validation layer: any message about the chain's barriers or blits fails the render.
    TargetRenderer renderer(EngineOptions{"", /*validation*/ true});
    std::optional<Image> vulkan;
    // Godot's viewports have no mip chains: there only the LUT's channel is judged.
    for (TargetId target : {TargetId::Spirv, TargetId::Glsl330, TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3}) {
        INFO(target_info(target).name);
        const std::vector<Image> images = render_imported_or_fail(renderer, *lib, *preset, target, checker, 30, 30, {1});
        const Image& v = images.front();
        const bool godot = target == TargetId::Godot4 || target == TargetId::Godot3;
        double worst_mip = 0, extreme = 0, worst_vs_vulkan = 0;
        for (size_t i = 0; i < v.pixel_count(); ++i) {
            worst_mip = std::max({worst_mip, godot ? 0.0 : std::abs(v.rgba[i * 4] - 0.5), std::abs(v.rgba[i * 4 + 2] - 0.5)});
            extreme += std::min(v.rgba[i * 4 + 1], 1.0f - v.rgba[i * 4 + 1]);  // 0 for black or white
            if (vulkan)
                for (int c : {godot ? 2 : 0, 2}) worst_vs_vulkan = std::max<double>(worst_vs_vulkan, std::abs(v.rgba[i * 4 + c] - vulkan->rgba[i * 4 + c]));
        }
        CHECK(worst_mip < 0.02);                  // the pass output's and the LUT's chains: grey
        CHECK(extreme / v.pixel_count() < 0.01);  // the original at level 0, nearest: black or white
        CHECK(worst_vs_vulkan < 0.02);
        if (!vulkan) vulkan = v;
    }
}

// RetroArch keeps an R8G8B8A8_UNORM framebuffer's mip chain in 8 bits (each level a blit into the
// same format), and clamp_to_border at an explicit level reads transparent black one *level*
// texel outside. A 64x32 picture of 0, 128 and 255 whose 2x2 averages fall between bytes: level
// 3 read at a texel centre must be on the byte grid (a float chain gives e.g. 95.75 / 255), and
// level 5 (2 x 1) read at (0.3, 0.3) is 0.8 of its texel on every host: WGSL, which emulates the
// border in the shader, must measure the footprint in that level's texels, not level 0's
// (raster_bloom's average brightness read 18 % too bright in WebGPU before).
TEST_CASE("an 8-bit pass output's mip chain is 8-bit, and clamp_to_border at an explicit level is measured in that level's texels",
          "[retroarch][import][mipmap]") {
    test::TempDir dir;
    const std::string head = kStockHead;
    test::write_file(dir / "shaders/copy.slang", head + "void main() { FragColor = texture(Source, vTexCoord); }\n");
    // Level 3 is 8 x 4: (2.5 / 8, 1.5 / 4) is a texel centre.
    test::write_file(dir / "shaders/levels.slang", head + R"(void main() {
    float level3 = textureLod(Source, vec2(2.5 / 8.0, 1.5 / 4.0), 3.0).r;
    // How far level 3's texel is from the byte grid, measured here: the display is half floats.
    FragColor = vec4(textureLod(Source, vec2(0.3, 0.3), 5.0).r, abs(fract(level3 * 255.0 + 0.5) - 0.5), level3, 1.0);
}
)");
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "levels",
          "shaders = 2\n"
          "shader0 = ../shaders/copy.slang\n"
          "filter_linear0 = false\n"
          "scale_type0 = source\n"
          "shader1 = ../shaders/levels.slang\n"
          "filter_linear1 = true\n"
          "mipmap_input1 = true\n"
          "scale_type1 = viewport\n", 2);
    const Preset* preset = lib->find_preset("levels");
    CHECK(preset->passes[1].inputs.front().wrap == Wrap::ClampToBorder);
    Image picture = Image::make(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 4; ++c)
                picture.rgba[(static_cast<size_t>(y) * 64 + x) * 4 + c] = c == 3 ? 1.0f : static_cast<float>(((x * 7 + y * 3) % 3) * 127.5 / 255.0);
    for (float& v : picture.rgba) v = std::round(v * 255.0f) / 255.0f;
    TargetRenderer renderer;
    std::optional<std::array<float, 2>> vulkan;
    for (TargetId target : {TargetId::Spirv, TargetId::Glsl330, TargetId::Wgsl}) {
        INFO(target_info(target).name);
        const std::vector<Image> images = render_imported_or_fail(renderer, *lib, *preset, target, picture, 8, 8, {0});
        const float* p = images.front().rgba.data() + (4 * 8 + 4) * 4;
        INFO("level 3 texel " << p[2] * 255.0f << " / 255 (" << p[1] << " off the byte grid), level 5 at the border "
                                  << p[0] * 255.0f << " / 255");
        CHECK(p[1] < 0.01f);  // on the byte grid: an 8-bit chain
        CHECK(p[0] > 0.05f);
        if (vulkan) {
            CHECK(std::abs(p[0] - (*vulkan)[0]) < 1.5f / 255.0f);
            CHECK(std::abs(p[2] - (*vulkan)[1]) < 1.5f / 255.0f);
        } else {
            vulkan = std::array<float, 2>{p[0], p[2]};
        }
    }
}

// RetroArch's framebuffer formats beyond 8-bit and half float: five passes write the same texel
// into an R32G32B32A32_SFLOAT, R16G16B16A16_SFLOAT, A2B10G10R10_UNORM_PACK32, R16_SFLOAT and
// R16G16_SFLOAT framebuffer; the last shows what each holds, one column each (top row: red's
// 32-bit detail, green past 1 (/ 1.5), blue's offset from a 10-bit step (+ 0.5); bottom row: alpha). What a
// format lacks reads 0 (colour) and 1 (alpha); 10 bits clamp and round to steps of 1/1023 (alpha
// 1/3). Every target renders it through its consumer (Godot through the exported scene, which
// stores these in half-float viewports: the shader reduces its output to the format's channels
// and steps, and 32-bit floats lose their detail).
TEST_CASE("R32G32B32A32, A2B10G10R10, R16 and R16G16 framebuffers hold what RetroArch's hold, on every target",
          "[retroarch][import][format]") {
    test::TempDir dir;
    const std::string head = kStockHead;
    const std::vector<std::string> formats = {"R32G32B32A32_SFLOAT", "R16G16B16A16_SFLOAT", "A2B10G10R10_UNORM_PACK32", "R16_SFLOAT",
                                              "R16G16_SFLOAT"};
    std::string slangp = fmt::format("shaders = {}\n", formats.size() + 1);
    for (size_t i = 0; i < formats.size(); ++i) {
        test::write_file(dir / fmt::format("shaders/f{}.slang", i),
                         head + fmt::format("#pragma format {}\n", formats[i]) +
                             "void main() { FragColor = vec4(1.0 + 1.0 / 16384.0, 1.5, 300.4 / 1023.0, 0.4) + 0.0 * texture(Source, vTexCoord); }\n");
        slangp += fmt::format("shader{0} = ../shaders/f{0}.slang\nalias{0} = f{0}\nfilter_linear{0} = false\nscale_type{0} = absolute\nscale{0} = 2\n", i);
    }
    std::string show = head;
    for (size_t i = 0; i < formats.size(); ++i) show += fmt::format("layout(set = 0, binding = {}) uniform sampler2D f{};\n", 3 + i, i);
    show += R"(void main() {
    int column = int(vTexCoord.x * 5.0);
    vec4 s = column == 0 ? texture(f0, vec2(0.5)) : column == 1 ? texture(f1, vec2(0.5)) : column == 2 ? texture(f2, vec2(0.5))
           : column == 3 ? texture(f3, vec2(0.5)) : texture(f4, vec2(0.5));
    // In [0, 1]: Godot's screen is 8-bit.
    FragColor = vTexCoord.y < 0.5 ? vec4((s.r - 1.0) * 16384.0, s.g / 1.5, clamp(0.5 + s.b * 1023.0 - 300.0, 0.0, 1.0), 1.0)
                                  : vec4(s.a, 0.0, 0.0, 1.0);
}
)";
    test::write_file(dir / "shaders/show.slang", show);
    slangp += fmt::format("shader{0} = ../shaders/show.slang\nfilter_linear{0} = false\nscale_type{0} = viewport\n", formats.size());
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "formats", slangp, formats.size() + 1);
    const Preset* preset = lib->find_preset("formats");
    const std::vector<PixelFormat> expected_formats = {PixelFormat::Rgba32F, PixelFormat::Rgba16F, PixelFormat::Rgb10A2, PixelFormat::R16F,
                                                       PixelFormat::Rg16F};
    for (size_t i = 0; i < formats.size(); ++i) CHECK(preset->passes[i].format == expected_formats[i]);

    struct Held {
        float red_detail, green, blue, alpha;
    };
    // What the five hold: 32-bit floats keep red's 2^-14 (half floats round it away) and blue's
    // 0.4 of a 10-bit step; 10 bits clamp green to 1 and round blue to its step and alpha to 1/3.
    const std::vector<Held> held = {{1.0f, 1.0f, 0.9f, 0.4f}, {0.0f, 1.0f, 0.9f, 0.4f}, {0.0f, 1.0f / 1.5f, 0.5f, 1.0f / 3.0f},
                                    {0.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}};
    const Image input = Image::make(10, 2, {0.5f, 0.5f, 0.5f, 1.0f});  // the display's aspect: no letterbox
    TargetRenderer renderer;
    for (TargetId target : {TargetId::Spirv, TargetId::Glsl450, TargetId::Glsl330, TargetId::GlslEs300, TargetId::WebGl2, TargetId::Hlsl50,
                            TargetId::Hlsl60, TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3}) {
        INFO(target_info(target).name);
        const std::vector<Image> images = render_imported_or_fail(renderer, *lib, *preset, target, input, 10, 2, {1});
        const Image& v = images.front();
        const bool godot = target == TargetId::Godot4 || target == TargetId::Godot3;
        for (size_t i = 0; i < formats.size(); ++i) {
            INFO(formats[i]);
            const float* top = v.rgba.data() + (2 * i) * 4;
            const float* bottom = v.rgba.data() + (10 + 2 * i) * 4;
            INFO("held: red detail " << top[0] << ", green " << top[1] << ", blue " << top[2] << ", alpha " << bottom[0]);
            const Held want = godot && i == 0 ? Held{0.0f, 1.0f, 0.9f, 0.4f} : held[i];  // Godot: a half-float viewport
            CHECK(std::abs(top[0] - want.red_detail) < 0.01f);
            CHECK(std::abs(top[1] - want.green) < 0.003f);  // Godot's screen: 8 bits
            // A half float holds 300.4 / 1023 within 2^-12 (Vulkan lets a float -> half store round
            // to zero, as lavapipe does): 0.25 of a 10-bit step.
            CHECK(std::abs(top[2] - want.blue) < (formats[i] == "R16G16B16A16_SFLOAT" || godot ? 0.26f : 0.02f));
            CHECK(std::abs(bottom[0] - want.alpha) < 0.003f);
        }
    }
    // Read linearly, an rgba32f output needs a device that filters 32-bit floats: the shipped
    // WebGPU driver keeps it in rgba16float where Dawn lacks float32-filterable (its GL ES
    // backend here) rather than failing; the other formats are filterable everywhere.
    std::string linear_text = slangp;
    // (filter_linearN says how pass N - 1's output is read: here f0's.)
    linear_text.replace(linear_text.find("filter_linear1 = false"), 22, "filter_linear1 = true");
    const std::shared_ptr<TemplateLibrary> linear = import_text_or_fail(dir, "linear", linear_text, formats.size() + 1);
    const std::vector<Image> filtered = render_imported_or_fail(renderer, *linear, *linear->find_preset("linear"), TargetId::Wgsl, input, 10, 2, {1});
    for (size_t i = 0; i < formats.size(); ++i) {
        INFO(formats[i] << " read linearly");
        const float* top = filtered.front().rgba.data() + (2 * i) * 4;
        CHECK(std::abs(top[1] - held[i].green) < 0.003f);
        CHECK(std::abs(top[2] - held[i].blue) < (i < 2 ? 0.26f : 0.02f));  // rgba32f: maybe half floats
    }
}

TEST_CASE("an sRGB framebuffer holds 8-bit sRGB codes on every target: Godot's half-float viewports rounded to them",
          "[retroarch][import][format]") {
    // Dark values, where an sRGB code is far from the next: the first pass stores 0..0.02 across
    // the width, the second shows 45x what it reads back, a staircase of codes.
    test::TempDir dir;
    test::write_file(dir / "shaders/dark.slang", kStockHead + "#pragma format R8G8B8A8_SRGB\n"
                                                              "void main() { FragColor = vec4(vec3(vTexCoord.x * 0.02), 1.0) + 0.0 * texture(Source, vTexCoord); }\n");
    test::write_file(dir / "shaders/show.slang", kStockHead + "void main() { FragColor = vec4(texture(Source, vTexCoord).rgb * 45.0, 1.0); }\n");
    const std::string slangp = "shaders = 2\n"
                               "shader0 = ../shaders/dark.slang\nfilter_linear0 = false\nscale_type0 = absolute\nscale_x0 = 64\nscale_y0 = 4\n"
                               "shader1 = ../shaders/show.slang\nfilter_linear1 = false\nscale_type1 = viewport\n";
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "dark", slangp, 2);
    auto srgb_code = [](double linear) {
        return std::round((linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055) * 255.0);
    };
    auto from_code = [](double code) { return code / 255.0 <= 0.04045 ? code / 255.0 / 12.92 : std::pow((code / 255.0 + 0.055) / 1.055, 2.4); };
    // Godot rounds to the exact sRGB code (IEC 61966-2-1): its values are the staircase's, within
    // its 8-bit screen. The drivers' own sRGB formats are within a code of it: lavapipe's encoding
    // is an approximation (measured: 3 of these 64 columns a code off, 13.54 stored as 13, 30.42 as
    // 31, 37.46 as 38), and Dawn's GL ES backend decodes these codes 1.6-2.0 % low.
    render_on_each(*lib, "dark", {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50, TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3},
                   {64, 4}, {64, 4}, [&](TargetId target, const Image& image) {
                       const bool godot = target == TargetId::Godot4 || target == TargetId::Godot3;
                       for (int x = 0; x < 64; ++x) {
                           INFO("column " << x);
                           const double code = srgb_code((x + 0.5) / 64.0 * 0.02);
                           const double code_step = 45.0 * (from_code(code + 1.0) - from_code(code));  // 0.014 to 0.041 here
                           CHECK(image.rgba[size_t(x) * 4] == Approx(45.0 * from_code(code)).margin(godot ? 0.003 : code_step * 1.05));
                       }
                   });
}

TEST_CASE("baked parameters keep RetroArch's 32-bit arithmetic: a float loop bounded by a division runs as often as with them live",
          "[retroarch][import][specialize]") {
    // crt-maximus-royale's H_blur: as `const`s glslang folds 0.001 / 10.0 in double (9.99999975e-05,
    // not the 32-bit quotient 1.00000005e-04) and this loop then runs 11 times, not 10.
    test::TempDir dir;
    const std::shared_ptr<TemplateLibrary> lib =
        one_pass_or_fail(dir, "steps",
                         {"float SHARP; ", "#pragma parameter SHARP \"Sharpness\" 10.0 1.0 20.0 0.5\n", "", "",
                          "void main() {\n"
                          "    float n = 0.0;\n"
                          "    for (float i = -0.005 / params.SHARP; i < 0.005 / params.SHARP; i += 0.001 / params.SHARP) n += 1.0;\n"
                          "    FragColor = vec4(n / 20.0, 0.0, 0.0, 1.0);\n"
                          "}\n"});
    const Preset& preset = *lib->find_preset("steps");
    const Image input = Image::make(4, 4, {0.5f, 0.5f, 0.5f, 1.0f});
    TargetRenderer renderer;
    VariantOptions baked;
    baked.uniforms = UniformSelection::parse("none").value();
    VariantOptions live;
    live.uniforms = UniformSelection::parse("all").value();
    for (const VariantOptions* options : {&live, &baked}) {
        INFO((options == &baked ? "baked" : "live"));
        auto images = render_imported(renderer, *lib, preset, TargetId::Spirv, input, 4, 4, {0}, *options);
        INFO((images.ok() ? std::string() : images.error().str()));
        REQUIRE(images.ok());
        CHECK(images.value().front().rgba[0] == Approx(10.0 / 20.0).margin(1e-6));  // ten steps, in 32 bits
    }
}

TEST_CASE("a compile found under a shared key is the module a fresh compile gives", "[compile][cache][retroarch][specialize]") {
    // Two presets share a pass and differ in its values: the second finds the first's compile by
    // key, gets its own values written in, and must equal a compile of its own source.
    test::TempDir dir;
    test::write_file(dir / "shaders/gain.slang",
                     test::slang_program({"float GAIN; float BIAS; ",
                                          "#pragma parameter GAIN \"Gain\" 0.5 0.0 2.0 0.05\n#pragma parameter BIAS \"Bias\" 0.0 -1.0 1.0 0.05\n",
                                          "", "",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "void main() { FragColor = vec4(texture(Source, vTexCoord).rgb * params.GAIN + params.BIAS, 1.0); }\n"}));
    test::write_file(dir / "a.slangp", "shaders = 1\nshader0 = shaders/gain.slang\nGAIN = 1.5\nBIAS = 0.1\n");
    test::write_file(dir / "b.slangp", "shaders = 1\nshader0 = shaders/gain.slang\nGAIN = 0.3\nBIAS = -0.7\n");
    auto baked = UniformSelection::parse("none");
    REQUIRE(baked.ok());
    VariantOptions options;
    options.uniforms = baked.value();
    options.local_names = false;
    options.specialize_baked = true;
    std::vector<CompiledVariant> compiled;
    for (const std::string name : {"a", "b"}) {
        auto lib = import_into(dir / (name + ".slangp"), dir / ("overlay_" + name), dir.path(), name);
        INFO((lib.ok() ? std::string() : lib.error().str()));
        REQUIRE(lib.ok());
        auto scene = compile_scene(*lib.value(), *lib.value()->find_preset(name), options, Cache());
        INFO((scene.ok() ? std::string() : scene.error().str()));
        REQUIRE(scene.ok());
        compiled.push_back(std::move(scene.value()[0]));
    }
    CHECK(source_key(compiled[0].fragment_glsl).text == source_key(compiled[1].fragment_glsl).text);
    CHECK(compiled[0].fragment != compiled[1].fragment);  // each holds its own values
    CompileOptions fresh;
    fresh.stage = ShaderStage::Fragment;
    fresh.local_names = false;
    auto own = compile_to_spirv(compiled[1].fragment_glsl, fresh);
    REQUIRE(own.ok());
    CHECK(own.value() == compiled[1].fragment);
}
