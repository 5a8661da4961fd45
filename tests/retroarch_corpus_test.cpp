// crtforge corpus: a small library of our own (a preset that draws, one that reads a sampler only a
// macro names and one an #ifdef hides, one that counts rows by gl_FragCoord, one whose value lies
// outside its range, one that does not import, one whose SPIR-V fails) through the corpus run on
// Vulkan, GL, HLSL and a real Godot 3: rows, statuses, reasons, shards and a byte-identical report.
// Then libraries that read outside their textures (clamp_to_border), hand matrices, arrays and flat
// integers between stages and read a pass's own last output (feedback), through Dawn and through
// real Godot 4 and Godot 3.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>

#include <fmt/format.h>

#include "crtforge/runtime/image_io.hpp"
#include "crtforge/slang_import.hpp"

#include "crtforge/validate/corpus.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

// A pass whose fragment main() body is `body` (reads `Source` at vTexCoord as `c`).
std::string pass(const std::string& declarations, const std::string& body) {
    return test::slang_program({"float GAIN; ", "#pragma parameter GAIN \"Gain\" 1.0 0.5 2.0 0.1\n", "", "",
                                declarations + "void main() {\n" + body + "\n}\n"});
}

const char* kDraw = "    FragColor = vec4(texture(Source, vTexCoord).rgb * params.GAIN, 1.0);";

// The library: good/plain.slangp, good/macro.slangp (reads the first pass by a macro, an #ifdef
// hides a sampler no texture backs), good/wide.slangp (GAIN = 3 outside [0.5, 2]),
// bad/broken.slangp (a missing shader), bad/nospirv.slangp (a type error).
void write_library(const test::TempDir& dir) {
    test::write_file(dir / "shaders/plain.slang", pass("layout(set = 0, binding = 2) uniform sampler2D Source;\n", kDraw));
    test::write_file(dir / "shaders/macro.slang",
          pass("#define Source firstPass\n"
               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
               "#ifdef NEVER_DEFINED\n"
               "layout(set = 0, binding = 3) uniform sampler2D NoSuchTexture;\n"
               "#endif\n",
               kDraw));
    // Bands of three rows counted by gl_FragCoord: GL counts from the bottom and a y-up clip space
    // draws upside down unless the host corrects both, so a mirrored count shows.
    test::write_file(dir / "shaders/rows.slang",
          pass("layout(set = 0, binding = 2) uniform sampler2D Source;\n",
               "    float band = mod(floor(gl_FragCoord.y / 3.0), 2.0);\n"
               "    FragColor = vec4(texture(Source, vTexCoord).rgb * (0.25 + 0.75 * band) * params.GAIN, 1.0);"));
    test::write_file(dir / "good/rows.slangp", "shaders = 1\nshader0 = ../shaders/rows.slang\n");
    test::write_file(dir / "shaders/typo.slang", pass("layout(set = 0, binding = 2) uniform sampler2D Source;\n", "    FragColor = 1.0;"));
    test::write_file(dir / "good/plain.slangp", "shaders = 1\nshader0 = ../shaders/plain.slang\n");
    test::write_file(dir / "good/macro.slangp",
          "shaders = 2\nshader0 = ../shaders/plain.slang\nalias0 = firstPass\nshader1 = ../shaders/macro.slang\n");
    test::write_file(dir / "good/wide.slangp", "shaders = 1\nshader0 = ../shaders/plain.slang\nGAIN = 3.0\n");
    test::write_file(dir / "bad/broken.slangp", "shaders = 1\nshader0 = ../shaders/missing.slang\n");
    test::write_file(dir / "bad/nospirv.slangp", "shaders = 1\nshader0 = ../shaders/typo.slang\n");
}

const CorpusRow& row_of(const CorpusReport& report, const std::string& preset) {
    for (const CorpusRow& row : report.rows)
        if (row.preset == preset) return row;
    FAIL("no row for " << preset);
    return report.rows.front();
}

}  // namespace

TEST_CASE("corpus runs every preset of a library through import, SPIR-V, each target's consumer and a judged render",
          "[retroarch][corpus-command]") {
    test::TempDir dir;
    write_library(dir);
    auto presets = list_corpus_presets(dir.path());
    REQUIRE(presets.ok());
    REQUIRE(presets.value() ==
            std::vector<std::string>{"bad/broken.slangp", "bad/nospirv.slangp", "good/macro.slangp", "good/plain.slangp", "good/rows.slangp",
                                     "good/wide.slangp"});

    CorpusRequest request;
    request.root = dir.path();
    request.presets = presets.value();
    request.targets = {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50, TargetId::Godot3};
    request.source_width = 32;
    request.source_height = 24;
    request.display_width = 64;
    request.display_height = 48;
    request.frame = 1;
    auto run = run_corpus(request, Cache());
    INFO((run.ok() ? std::string() : run.error().str()));
    REQUIRE(run.ok());
    const CorpusReport& report = run.value();
    REQUIRE(report.rows.size() == 6);
    REQUIRE(report.targets == std::vector<std::string>{"spirv", "glsl330", "hlsl50", "godot3"});

    SECTION("presets that import render on Vulkan, and GL and HLSL agree with it") {
        for (const char* name : {"good/plain.slangp", "good/macro.slangp", "good/rows.slangp", "good/wide.slangp"}) {
            INFO(name);
            const CorpusRow& row = row_of(report, name);
            CHECK(row.import_error.empty());
            CHECK(row.spirv_error.empty());
            CHECK(row.passes_spirv == row.passes);
            for (const char* target : {"spirv", "glsl330", "hlsl50"}) {
                INFO(target << ": " << row.targets.at(target).reason);
                CHECK(row.targets.at(target).status == "agrees");
                CHECK(row.targets.at(target).passes_compiled == row.passes);
            }
            CHECK(row.targets.at("glsl330").psnr >= 40.0);
            CHECK(row.targets.at("hlsl50").psnr >= 40.0);
            // A real Godot 3 runs the exported scene: each program pass's vertex() and fragment().
            const CorpusTargetResult& godot = row.targets.at("godot3");
            INFO("godot3: " << godot.reason);
            CHECK(godot.status == "agrees");
            CHECK(godot.passes_compiled == row.passes);
        }
        CHECK(row_of(report, "good/macro.slangp").passes == 2);
        // A value outside its range is kept (widened), with a warning, as RetroArch keeps it.
        CHECK(row_of(report, "good/wide.slangp").warnings == 1);
    }
    SECTION("failures say which step failed and why, and skip what follows") {
        const CorpusRow& broken = row_of(report, "bad/broken.slangp");
        CHECK_THAT(broken.import_error, Catch::Matchers::Contains("missing.slang"));
        CHECK(broken.targets.at("spirv").status == "skipped");
        const CorpusRow& nospirv = row_of(report, "bad/nospirv.slangp");
        CHECK(nospirv.import_error.empty());
        CHECK_THAT(nospirv.spirv_error, Catch::Matchers::Contains("typo.slang"));
        CHECK(nospirv.passes_spirv == 0);
        for (const char* target : {"spirv", "glsl330"}) CHECK(nospirv.targets.at(target).status == "compile");
        CHECK(corpus_reason_class(nospirv.spirv_error).find("typo.slang") == std::string::npos);
        // A reason names the imported stage file without the run's temporary folder, so reports
        // compare run to run.
        CHECK_THAT(nospirv.spirv_error, Catch::Matchers::Contains("<imported>/stages/") || Catch::Matchers::Contains("typo.slang"));
        CHECK(nospirv.spirv_error.find("crtforge-corpus-") == std::string::npos);
    }
    SECTION("the report is byte-identical run to run, and shards split the rows") {
        auto again = run_corpus(request, Cache());
        REQUIRE(again.ok());
        CHECK(corpus_json(again.value()) == corpus_json(report));
        CHECK(corpus_html(again.value()) == corpus_html(report));
        std::vector<std::string> seen;
        for (unsigned k = 1; k <= 2; ++k) {
            CorpusRequest shard = request;
            shard.targets = {TargetId::Spirv};
            shard.shard = Shard{k, 2};
            auto part = run_corpus(shard, Cache());
            REQUIRE(part.ok());
            for (const CorpusRow& row : part.value().rows) seen.push_back(row.preset);
        }
        std::sort(seen.begin(), seen.end());
        CHECK(seen == presets.value());
        const std::string html = corpus_html(report);
        for (const std::string& p : presets.value()) CHECK(html.find(p) != std::string::npos);
    }
}

TEST_CASE("a failure's reason class drops where it happened and what varies", "[retroarch][corpus-command]") {
    CHECK(corpus_reason_class("/a/b.slang:12: error: frag shader: 'foo' : undeclared identifier") ==
          "frag shader: 'X' : undeclared identifier");
    CHECK(corpus_reason_class("x.toml:3:7: error: field 'f': preset p, target wgsl: binding 4 of 12") ==
          "field 'X': preset p, target wgsl: binding N of N");
    CHECK(corpus_reason_class("error: preset p, target wgsl: the stages differ") == "the stages differ");
}

namespace {

// A pass that zooms out, so a fifth of the picture samples outside the texture, and hands the
// zoom to the fragment stage as a matrix, an array and a flat integer (stage I/O WGSL has no form
// for but one location per slot).
std::string zoom_out_pass() {
    return test::slang_program({"", "",
                                "layout(location = 1) {io} mat2 vZoom;\n"
                                "layout(location = 3) {io} vec2 vShift[2];\n"
                                "layout(location = 5) flat {io} int vOn;\n",
                                "    vZoom = mat2(1.55, 0.0, 0.0, 1.55); vShift[0] = vec2(0.5); vShift[1] = vec2(-0.5); vOn = 1;\n",
                                "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                "void main() {\n"
                                "    vec2 uv = vOn == 1 ? vZoom * (vTexCoord + vShift[1]) + vShift[0] : vTexCoord;\n"
                                "    FragColor = vec4(texture(Source, uv).rgb, 1.0);\n"
                                "}\n"});
}

// A pass that leaves a trail: this frame's picture over the pass's own last output (its feedback),
// half and half, moved a little each frame so the trail shows.
std::string trail_pass() {
    return test::slang_program({"uint FrameCount; ", "#pragma name trail\n", "", "",
                                "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                "layout(set = 0, binding = 3) uniform sampler2D trailFeedback;\n"
                                "void main() {\n"
                                "    vec2 shift = vec2(float(params.FrameCount % 4u) * 0.04, 0.0);\n"
                                "    vec3 now = texture(Source, vTexCoord + shift).rgb;\n"
                                "    FragColor = vec4(mix(now, texture(trailFeedback, vTexCoord).rgb, 0.5), 1.0);\n"
                                "}\n"});
}

// Runs `presets` of the library in `dir` on Vulkan and `target` (a 32x24 source on a 64x48 or the given
// display, frame `frame`) and checks every pass compiles and every preset agrees with Vulkan.
// `presets` of the library in `dir` swept through `targets` (a 32 x 24 source, frame `frame`, on a
// `display_width` x `display_height` display); the test stops unless the sweep runs.
CorpusReport sweep_or_fail(const test::TempDir& dir, const std::vector<std::string>& presets, const std::vector<TargetId>& targets,
                           int frame = 0, int display_width = 64, int display_height = 48) {
    CorpusRequest request;
    request.root = dir.path();
    request.presets = presets;
    request.targets = targets;
    request.source_width = 32;
    request.source_height = 24;
    request.display_width = display_width;
    request.display_height = display_height;
    request.frame = frame;
    auto run = run_corpus(request, Cache());
    INFO((run.ok() ? std::string() : run.error().str()));
    REQUIRE(run.ok());
    REQUIRE(run.value().rows.size() == presets.size());
    return std::move(run).value();
}

void check_all_agree(const test::TempDir& dir, const std::vector<std::string>& presets, TargetId target, int frame = 0,
                     int display_width = 64, int display_height = 48) {
    const CorpusReport report = sweep_or_fail(dir, presets, {TargetId::Spirv, target}, frame, display_width, display_height);
    const std::string name = target_info(target).name;
    for (const CorpusRow& row : report.rows) {
        INFO(row.preset << ": " << row.import_error << row.targets.at(name).reason);
        CHECK(row.targets.at("spirv").status == "agrees");
        CHECK(row.targets.at(name).passes_compiled == row.passes);
        CHECK(row.targets.at(name).status == "agrees");
        CHECK(row.targets.at(name).psnr >= 40.0);
    }
}


// linear.slangp (a zoom out, read linearly outside the texture: clamp_to_border) and chain.slangp
// (the zoom, then bands of three rows by gl_FragCoord, columns by the output size the vertex
// stage reads, and a mask's triads by floor(gl_FragCoord.x - 0.5), which only exact pixel centres
// count right).
void write_program_library(const test::TempDir& dir) {
    test::write_file(dir / "shaders/zoom.slang", zoom_out_pass());
    test::write_file(dir / "shaders/rows.slang",
          test::slang_program({"vec4 OutputSize; ", "", "layout(location = 1) {io} vec2 vPixel;\n",
                               "    vPixel = TexCoord * params.OutputSize.xy;\n",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "void main() {\n"
                               "    float band = mod(floor(gl_FragCoord.y / 3.0), 2.0);\n"
                               "    float column = mod(floor(vPixel.x / 4.0), 2.0);\n"
                               "    float triad = mod(floor(gl_FragCoord.x - 0.5), 3.0);  // a mask's column: exact centres only\n"
                               "    FragColor = vec4(texture(Source, vTexCoord).rgb * (0.25 + 0.5 * band + 0.25 * column) * (0.5 + 0.25 * triad), 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "linear.slangp", "shaders = 1\nshader0 = shaders/zoom.slang\nfilter_linear0 = true\n");
    test::write_file(dir / "chain.slangp", "shaders = 2\nshader0 = shaders/zoom.slang\nfilter_linear0 = false\nscale_type0 = source\n"
                                "shader1 = shaders/rows.slang\nfilter_linear1 = true\n");
}

// NAME.slangp, one pass of the program shaders/NAME.slang (`push`: its push-constant members after
// SourceSize; `fragment`: its fragment stage), with the preset's `keys` after shader0.
void write_one_pass(const test::TempDir& dir, const std::string& name, const std::string& push, const std::string& fragment,
                    const std::string& keys) {
    test::write_file(dir / ("shaders/" + name + ".slang"), test::slang_program({push, "", "", "", fragment}));
    test::write_file(dir / (name + ".slangp"), "shaders = 1\nshader0 = shaders/" + name + ".slang\n" + keys);
}

// tables.slangp: what Godot's language and GLSL 3.30 / ES 3.00 have no type for, as RetroArch's
// shaders write it: a mask table as an array of arrays read at the output pixel's cell (crt-geom), four
// taps as the columns of a mat4x3 blended by a vec4 and weighed by luma (xbr, crt-hyllian), a
// vector indexed by a loop counter (crt-yo6's per-channel reads).
void write_tables_library(const test::TempDir& dir) {
    write_one_pass(dir, "tables", "vec4 OutputSize; ",
                   "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                   "const vec3 kMasks[3][2] = vec3[3][2](vec3[2](vec3(1.0, 0.2, 1.0), vec3(0.2, 1.0, 0.2)),\n"
                   "    vec3[2](vec3(0.6), vec3(0.3, 0.2, 0.9)), vec3[2](vec3(0.2, 0.2, 1.0), vec3(1.0, 1.0, 0.2)));\n"
                   "void main() {\n"
                   "    ivec2 cell = ivec2(vTexCoord * params.OutputSize.xy) % ivec2(3, 2);\n"
                   "    vec2 dx = vec2(params.SourceSize.z, 0.0);\n"
                   "    mat4x3 taps = mat4x3(texture(Source, vTexCoord - dx).rgb, texture(Source, vTexCoord).rgb,\n"
                   "                         texture(Source, vTexCoord + dx).rgb, texture(Source, vTexCoord + 2.0 * dx).rgb);\n"
                   "    vec3 blend = taps * vec4(0.15, 0.45, 0.3, 0.1);\n"
                   "    vec4 lumas = vec3(0.299, 0.587, 0.114) * taps;\n"
                   "    float edge = clamp(abs(lumas.z - lumas.x) * 2.0, 0.0, 1.0);\n"
                   "    vec3 lifted;  // a vector indexed by a loop counter (Godot 3: constants only)\n"
                   "    for (int i = 0; i < 3; ++i) lifted[i] = pow(blend[i], 1.0 + 0.25 * float(i));\n"
                   "    FragColor = vec4(mix(lifted, taps[1], edge) * kMasks[cell.x][cell.y], 1.0);\n"
                   "}\n",
                   "filter_linear0 = false\n");
}

// gather.slangp: textureGather of each channel, at the pass's pixel and between texels, weighed
// so that the order of the four texels shows (GLSL 3.30, ES 3.00 and Godot have no gather).
void write_gather_library(const test::TempDir& dir) {
    write_one_pass(dir, "gather", "",
                   "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                   "void main() {\n"
                   "    vec4 r = textureGather(Source, vTexCoord, 0);\n"
                   "    vec4 g = textureGather(Source, vTexCoord + vec2(0.3, 0.7) * params.SourceSize.zw, 1);\n"
                   "    vec4 b = textureGather(Source, vTexCoord - vec2(0.6, 0.2) * params.SourceSize.zw, 2);\n"
                   "    FragColor = vec4(dot(r, vec4(0.4, 0.3, 0.2, 0.1)), dot(g, vec4(0.05, 0.15, 0.3, 0.5)),\n"
                   "                     dot(b, vec4(0.6, 0.1, 0.25, 0.05)), 1.0);\n"
                   "}\n",
                   "filter_linear0 = true\nwrap_mode0 = repeat\n");
}

// original.slangp: a second pass that reads only Original (not its own input, whose size is still
// its SourceSize) and sizes its stripes by FinalViewportSize, which the host must set.
void write_original_library(const test::TempDir& dir) {
    test::write_file(dir / "shaders/zoom.slang", zoom_out_pass());
    test::write_file(dir / "shaders/original.slang",
          test::slang_program({"vec4 FinalViewportSize; ", "", "", "",
                               "layout(set = 0, binding = 3) uniform sampler2D Original;\n"
                               "void main() {\n"
                               "    float stripe = mod(floor(vTexCoord.x * params.FinalViewportSize.x / 8.0), 2.0);\n"
                               "    float texel = params.SourceSize.z * 40.0;  // the first pass's width: 1 / 32\n"
                               "    FragColor = vec4(texture(Original, vTexCoord).rgb * (0.5 + 0.5 * stripe) + vec3(texel - 1.25), 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "original.slangp", "shaders = 2\nshader0 = shaders/zoom.slang\nscale_type0 = source\nscale0 = 1.0\n"
                                   "shader1 = shaders/original.slang\nfilter_linear1 = false\n");
}

// structs.slangp: scanline-classic's way of handing the vertex stage's work to the fragment stage,
// struct varyings (one with a nested struct and a matrix, a flat one with an int), a struct built
// whole and a constant one, read whole and by member; and inverse() of each size (its colour
// matrices), which WGSL has no builtin for. Every varying is affine in TexCoord or the same at every
// vertex: RetroArch's quad and crtforge's full-screen triangle interpolate those alike.
void write_structs_library(const test::TempDir& dir) {
    test::write_file(dir / "shaders/structs.slang",
          test::slang_program({"", "struct Timing { float phase; vec2 scale; };\n"
                                   "struct Grade { vec3 tint; Timing timing; mat3 matrix; };\n"
                                   "struct Counter { int band; float weight; };\n",
                               "layout(location = 1) {io} Grade grade;\n"
                               "layout(location = 7) flat {io} Counter counter;\n",
                               "    grade = Grade(vec3(0.9, 0.6, 0.3) + 0.1 * TexCoord.x, Timing(TexCoord.y * 6.0, vec2(1.0, 0.5 + TexCoord.x)),\n"
                               "                  mat3(1.0, 0.2, 0.1, 0.1, 0.9 + 0.1 * TexCoord.y, 0.1, 0.05, 0.1, 1.1));\n"
                               "    if (params.SourceSize.x > 16.0) grade.timing = Timing(1.0, vec2(0.5, 2.0));  // a constant struct stored\n"
                               "    counter.band = int(params.SourceSize.x) / 3 + 1;  // flat: the same at every vertex\n"
                               "    counter.weight = 0.75;\n",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "vec3 graded(Grade g, vec3 rgb) {\n"
                               "    vec2 k = inverse(mat2(g.timing.scale.x, 0.3, 0.2, g.timing.scale.y)) * vec2(0.5, 0.25);\n"
                               "    vec4 w = inverse(mat4(2.0, 0.1, 0.0, 0.3, 0.0, 1.5 + k.x, 0.2, 0.0, 0.1, 0.0, 1.0 + k.y, 0.1, 0.0, 0.2, 0.0, 1.0)) * vec4(rgb, 1.0);\n"
                               "    return inverse(g.matrix) * w.xyz * g.tint * (0.75 + 0.25 * sin(g.timing.phase)) + 0.1 * vec3(k, w.w);\n"
                               "}\n"
                               "void main() {\n"
                               "    Grade whole = grade;  // the struct read whole, handed to a function\n"
                               "    vec3 rgb = graded(whole, texture(Source, vTexCoord).rgb);\n"
                               "    FragColor = vec4(rgb * (counter.band % 2 == 0 ? 1.0 : counter.weight), 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "structs.slangp", "shaders = 1\nshader0 = shaders/structs.slang\nfilter_linear0 = false\n");
    // many.slangp: 18 locations from the vertex stage to the fragment stage (floats, vectors, a
    // matrix, flat ints), more than WebGPU's 15: the WGSL packs them into fewer. And a constant
    // infinity (uborder's), which a WGSL constant expression may not compute.
    std::string varyings, writes, reads = "vec3(0.0)";
    for (int i = 0; i < 12; ++i) {
        varyings += fmt::format("layout(location = {}) {{io}} {} v{};\n", i + 1, i % 3 == 0 ? "vec2" : "float", i);
        writes += fmt::format("    v{} = {};\n", i, i % 3 == 0 ? fmt::format("TexCoord * {}.0", i + 1) : fmt::format("TexCoord.x + 0.{}", i));
        reads += fmt::format(" + vec3({}) * 0.05", i % 3 == 0 ? fmt::format("v{}.x + v{}.y", i, i) : fmt::format("v{}", i));
    }
    varyings += "layout(location = 13) {io} mat3 tint;\nlayout(location = 16) flat {io} ivec2 band;\nlayout(location = 17) flat {io} int phase;\n";
    writes += "    tint = mat3(1.0, 0.1, 0.0, 0.0, 0.9, 0.1, 0.1, 0.0, 1.0 - 0.2 * TexCoord.y);\n"
              "    band = ivec2(int(params.SourceSize.x) / 4, 3);\n    phase = 5;\n";
    test::write_file(dir / "shaders/many.slang",
          test::slang_program({"", "", varyings, writes,
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "void main() {\n"
                               "    vec3 rgb = tint * texture(Source, vTexCoord).rgb;\n"
                               "    rgb = max(rgb, vec3(-1.0 / 0.0));  // an infinity, which WGSL may not spell as a constant\n"
                               "    FragColor = vec4(0.5 * rgb + 0.25 + 0.25 * sin((" + reads + ") * 0.1 * float(band.x % band.y + phase)), 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "many.slangp", "shaders = 1\nshader0 = shaders/many.slang\nfilter_linear0 = false\n");
    // renamed.slangp: a vertex output and the fragment input at its location named apart
    // (scanline-classic's vTexCoord_out / vTexCoord_in), which GLSL without locations meets by name;
    // and a constant six digits do not hold (scanline-classic's 1.0 - EPS: Godot 3 prints %g).
    test::write_file(dir / "shaders/renamed.slang",
          "#version 450\n"
          "layout(push_constant) uniform Push { vec4 SourceSize; } params;\n"
          "layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; } global;\n"
          "#pragma stage vertex\n"
          "layout(location = 0) in vec4 Position;\n"
          "layout(location = 1) in vec2 TexCoord;\n"
          "layout(location = 0) out vec2 uv_out;\n"
          "layout(location = 1) out vec3 shade_out;\n"
          "void main() { gl_Position = global.MVP * Position; uv_out = TexCoord; shade_out = vec3(1.0, 0.6 + 0.4 * TexCoord.x, 0.8); }\n"
          "#pragma stage fragment\n"
          "layout(location = 0) in vec2 uv_in;\n"
          "layout(location = 1) in vec3 shade_in;\n"
          "layout(location = 0) out vec4 FragColor;\n"
          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
          "void main() {\n"
          "    vec4 c = texture(Source, uv_in);  // opaque: alpha 1.0, above 0.9999999 (not in six digits: 1.0)\n"
          "    FragColor = vec4(c.rgb * shade_in * (c.a > 0.9999999 ? 1.0 : 0.25), 1.0);\n"
          "}\n");
    test::write_file(dir / "renamed.slangp", "shaders = 1\nshader0 = shaders/renamed.slang\nfilter_linear0 = false\n");
    // interface.slangp: koko-aio's stage interface. `noperspective` varyings (WebGPU's compatibility
    // mode has no `linear`), two of them at locations 16 and 17 though fewer than 15 are used (past
    // WebGPU's last), a flat array (five locations), an output the fragment stage declares but never
    // reads (the HLSL vertex shader must leave it out, or every later TEXCOORD lands one location
    // off), and a loop whose condition starts with a type constructor (`float(n) < TAPS`, which
    // Godot 4 parses as a declaration unless it is in parentheses).
    test::write_file(dir / "shaders/interface.slang",
          test::slang_program({"float TAPS; ", "#pragma parameter TAPS \"Taps\" 3.0 1.0 5.0 1.0\n",
                               "layout(location = 1) flat {io} float unread;\n"
                               "layout(location = 2) flat {io} float weights[5];\n"
                               "layout(location = 7) noperspective {io} vec2 uv_linear;\n"
                               "layout(location = 16) noperspective {io} vec2 glow_plus;\n"
                               "layout(location = 17) noperspective {io} vec2 glow_minus;\n",
                               "    unread = 7.0 + params.SourceSize.x;\n"
                               "    for (int i = 0; i < 5; ++i) weights[i] = 0.1 * float(i + 1) + 0.25 * params.SourceSize.z;\n"
                               "    uv_linear = TexCoord * 0.75 + 0.125;\n"
                               "    glow_plus = TexCoord + vec2(0.1, 0.0);\n"
                               "    glow_minus = TexCoord - vec2(0.0, 0.1);\n",
                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                               "void main() {\n"
                               "    float sum = 0.0;\n"
                               "    for (int n = 0; float(n) < params.TAPS; n++) sum += weights[n];\n"
                               "    vec3 c = texture(Source, uv_linear).rgb;\n"
                               "    vec3 g = texture(Source, glow_plus).rgb - 0.5 * texture(Source, glow_minus).rgb;\n"
                               "    FragColor = vec4(c * sum + 0.5 * g, 1.0);\n"
                               "}\n"}));
    test::write_file(dir / "interface.slangp", "shaders = 1\nshader0 = shaders/interface.slang\nfilter_linear0 = false\n");
}

// feedback.slangp: three passes, the second reading its own last output (trailFeedback).
void write_feedback_library(const test::TempDir& dir) {
    test::write_file(dir / "shaders/zoom.slang", zoom_out_pass());
    test::write_file(dir / "shaders/trail.slang", trail_pass());
    test::write_file(dir / "shaders/plain.slang", pass("layout(set = 0, binding = 2) uniform sampler2D Source;\n", kDraw));
    test::write_file(dir / "feedback.slangp", "shaders = 3\nshader0 = shaders/zoom.slang\nscale_type0 = source\n"
                                   "shader1 = shaders/trail.slang\nscale_type1 = source\nfilter_linear1 = false\n"
                                   "shader2 = shaders/plain.slang\nfilter_linear2 = true\n");
}

// long13.slangp and long14.slangp: the zoom, the trail (which reads its own feedback: one copy
// viewport in Godot) and 11 or 12 copies of the picture, so 14 or 15 viewports in Godot; a pass
// drawn out of order reads an earlier frame's output or none.
void write_long_chain_library(const test::TempDir& dir) {
    write_feedback_library(dir);
    for (int passes : {13, 14}) {
        std::string text = fmt::format("shaders = {}\nshader0 = shaders/zoom.slang\nscale_type0 = source\n"
                                       "shader1 = shaders/trail.slang\nscale_type1 = source\nfilter_linear1 = false\n",
                                       passes);
        // The last pass has no scale: one with a scale gets a copy pass to the display (as RetroArch).
        for (int i = 2; i < passes; ++i)
            text += fmt::format("shader{0} = shaders/plain.slang\n{1}", i, i + 1 < passes ? fmt::format("scale_type{} = source\n", i) : "");
        test::write_file(dir / fmt::format("long{}.slangp", passes), text);
    }
}

}  // namespace

TEST_CASE("WebGPU renders imported presets like Vulkan: clamp_to_border faded in the WGSL, the host clamping to the edge, feedback",
          "[retroarch][corpus-command][wgsl][dawn]") {
    test::TempDir dir;
    test::write_file(dir / "shaders/zoom.slang", zoom_out_pass());
    test::write_file(dir / "linear.slangp", "shaders = 1\nshader0 = shaders/zoom.slang\nfilter_linear0 = true\n");
    test::write_file(dir / "nearest.slangp", "shaders = 1\nshader0 = shaders/zoom.slang\nfilter_linear0 = false\n");
    // Two passes: the second reads the first's output (clamp_to_border by default) outside it.
    test::write_file(dir / "chain.slangp", "shaders = 2\nshader0 = shaders/zoom.slang\nfilter_linear0 = true\nscale_type0 = source\n"
                                "shader1 = shaders/zoom.slang\nfilter_linear1 = true\n");
    test::write_file(dir / "edge.slangp", "shaders = 1\nshader0 = shaders/zoom.slang\nfilter_linear0 = true\nwrap_mode0 = clamp_to_edge\n");
    check_all_agree(dir, {"chain.slangp", "edge.slangp", "linear.slangp", "nearest.slangp"}, TargetId::Wgsl);
    // The npm scene package runs a multi-pass preset with feedback as Vulkan does, and a pass that
    // reads only Original and the final viewport's size.
    write_feedback_library(dir);
    write_original_library(dir);
    check_all_agree(dir, {"feedback.slangp", "original.slangp"}, TargetId::Wgsl, 3);
}


TEST_CASE("struct varyings travel member by member where a target has none (Godot, WGSL, ES), GLSL meets varyings named apart, Godot 3 gets constants whole, and more than 15 locations, inverse() and an infinite constant run on WebGPU, like Vulkan",
          "[retroarch][corpus-command][structs]") {
    test::TempDir dir;
    write_structs_library(dir);
    for (TargetId target : {TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3, TargetId::GlslEs300, TargetId::Glsl330}) {
        INFO(target_info(target).name);
        check_all_agree(dir, {"structs.slangp"}, target, 0, 100, 75);
        check_all_agree(dir, {"many.slangp", "renamed.slangp"}, target);  // 2x: no texel edge under a pixel centre
    }
}

TEST_CASE("koko-aio's stage interface runs like Vulkan: noperspective varyings on WebGPU's compatibility mode, locations past 15, a flat array, an output the fragment stage never reads (HLSL), a loop condition starting with a type (Godot 4)",
          "[retroarch][corpus-command][structs][interface]") {
    test::TempDir dir;
    write_structs_library(dir);
    for (TargetId target : {TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3, TargetId::Hlsl50, TargetId::GlslEs300}) {
        INFO(target_info(target).name);
        check_all_agree(dir, {"interface.slangp"}, target);
    }
}

TEST_CASE("GLSL ES 3.00 and GLSL 3.30 run a pass with a non-square matrix and an array of arrays (flattened) like Vulkan",
          "[retroarch][corpus-command][flat-arrays]") {
    test::TempDir dir;
    write_tables_library(dir);
    check_all_agree(dir, {"tables.slangp"}, TargetId::GlslEs300);
    check_all_agree(dir, {"tables.slangp"}, TargetId::Glsl330);
}

TEST_CASE("Godot 4 runs imported program passes like Vulkan: vertex() and varyings, host-set sizes, gl_FragCoord, feedback, clamp_to_border, mat4x3, arrays of arrays, textureGather",
          "[retroarch][corpus-command][godot4]") {
    test::TempDir dir;
    write_program_library(dir);
    write_tables_library(dir);
    write_gather_library(dir);
    // 100 columns: (i + 0.5) / 100 is inexact, so an interpolated coordinate times the width misses
    // the pixel centre by an ulp (64 would hide it).
    check_all_agree(dir, {"chain.slangp", "gather.slangp", "linear.slangp", "tables.slangp"}, TargetId::Godot4, 0, 100, 75);
    write_feedback_library(dir);
    write_original_library(dir);
    check_all_agree(dir, {"feedback.slangp", "original.slangp"}, TargetId::Godot4, 3);
}

TEST_CASE("Godot 4, which draws on SwiftShader, is judged again against Vulkan on SwiftShader where it differs from lavapipe",
          "[retroarch][corpus-command][godot4]") {
    // Lavapipe ends a shader invocation after 65535 loop steps; SwiftShader, under Godot 4's WebGL 2
    // in Chromium, runs all 70000: the same SPIR-V gives 0.936 on one driver and 1.0 on the other.
    test::TempDir dir;
    test::write_file(dir / "steps.slang",
                     test::slang_program({"float Steps; ", "#pragma parameter Steps \"steps\" 70000.0 1.0 100000.0 1.0\n", "", "",
                                          "void main() {\n"
                                          "    float sum = 0.0;\n"
                                          "    for (int i = 0; i < int(params.Steps); ++i) sum += 1.0 / 70000.0;\n"
                                          "    FragColor = vec4(sum, sum, sum, 1.0);\n"
                                          "}\n"}));
    test::write_file(dir / "steps.slangp", "shaders = 1\nshader0 = steps.slang\n");
    const CorpusReport report = sweep_or_fail(dir, {"steps.slangp"}, {TargetId::Spirv, TargetId::Godot4});
    const CorpusTargetResult& godot4 = report.rows[0].targets.at("godot4");
    INFO(godot4.reason);
    CHECK(report.rows[0].targets.at("spirv").status == "agrees");
    CHECK(godot4.status == "agrees");
    CHECK(godot4.psnr >= 40.0);
    CHECK_THAT(godot4.reason, Catch::Contains("agrees with Vulkan on SwiftShader, the driver it draws on") &&
                                  Catch::Contains("against Vulkan on lavapipe"));
    // Against lavapipe alone it differs: 1.0 against 0.936 (PSNR about 24 dB).
    const size_t at = godot4.reason.find("); ");
    REQUIRE(at != std::string::npos);
    CHECK(std::stod(godot4.reason.substr(at + 3)) < 30.0);
}

TEST_CASE("Godot 3 runs imported program passes like Vulkan: vertex() and varyings, host-set sizes, gl_FragCoord, feedback, clamp_to_border, mat4x3, arrays of arrays, textureGather",
          "[retroarch][corpus-command][godot3]") {
    test::TempDir dir;
    write_program_library(dir);
    write_feedback_library(dir);
    write_tables_library(dir);
    write_gather_library(dir);
    check_all_agree(dir, {"chain.slangp", "gather.slangp", "linear.slangp", "tables.slangp"}, TargetId::Godot3, 0, 100, 75);
    write_original_library(dir);
    check_all_agree(dir, {"feedback.slangp", "original.slangp"}, TargetId::Godot3, 3);
}

TEST_CASE("Godot 3 keeps its passes in order up to 14 viewports and refuses a scene that needs more, naming why, while Godot 4 orders any number",
          "[retroarch][corpus-command][godot3][godot4]") {
    test::TempDir dir;
    write_long_chain_library(dir);
    check_all_agree(dir, {"long13.slangp"}, TargetId::Godot3, 3);  // 13 passes and a feedback copy
    check_all_agree(dir, {"long14.slangp"}, TargetId::Godot4, 3);
    auto refused = test::run_crtforge("export --preset '" + (dir / "long14.slangp") + "' --target godot3 --out '" + (dir / "out") + "'");
    CHECK(refused.exit_code == 2);
    // Told at the .slangp given (the overlay it was imported into is temporary), the overlay's line kept.
    CHECK_THAT(refused.err, Catch::Contains("long14.slangp: error: field 'godot3'") && Catch::Contains("(in its import: presets/long14.toml:1)") && Catch::Contains("needs 15 viewports in Godot 3 (14 passes, 1 feedback copies, 0 history copies)") &&
                                Catch::Contains("Godot 4"));
    CHECK(std::count(refused.err.begin(), refused.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_CASE("corpus --vulkan-only --uniforms none: the quick sweep bakes each preset's values, says so in its report, and refuses what it cannot run",
          "[retroarch][corpus-command]") {
    test::TempDir dir;
    write_library(dir);
    const std::string base = "corpus '" + dir.path() + "' --only good/plain.slangp,good/wide.slangp -j 1";
    auto swept = test::run_crtforge(base + " --vulkan-only --uniforms none --report '" + (dir / "report") + "'");
    INFO(swept.out << swept.err);
    REQUIRE(swept.exit_code == 0);
    std::ifstream in(dir / "report/corpus.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(json.find("\"uniforms\": \"none\"") != std::string::npos);
    CHECK(json.find("\"agrees\": 2") != std::string::npos);
    CHECK(json.find("\"glsl330\"") == std::string::npos);  // Vulkan only

    auto uber = test::run_crtforge(base + " --vulkan-only --uniforms uber");
    CHECK(uber.exit_code == 2);
    CHECK(uber.err.find("--uniforms") != std::string::npos);
    auto jit = test::run_crtforge(base + " --target glsl330 --optimised-jit");
    CHECK(jit.exit_code == 2);
    CHECK(jit.err.find("'--optimised-jit': only with --vulkan-only") != std::string::npos);
    auto names = test::run_crtforge(base + " --vulkan-only --uniforms 'GAIN,' --report '" + (dir / "named") + "'");
    INFO(names.err);
    CHECK(names.exit_code == 0);
}

TEST_CASE("corpus in worker processes writes the report one process writes byte for byte", "[retroarch][corpus-command]") {
    test::TempDir dir;
    write_library(dir);  // six presets, two of them failing: three workers of two
    const std::string base = "corpus '" + dir.path() + "' --vulkan-only --uniforms none -j 1 --source-size 32x24 --size 64x48";
    auto one = test::run_crtforge(base + " --presets-per-process 0 --report '" + (dir / "one") + "'");
    INFO(one.out << one.err);
    REQUIRE(one.exit_code == 0);
    auto workers = test::run_crtforge(base + " --presets-per-process 2 --report '" + (dir / "workers") + "'");
    INFO(workers.out << workers.err);
    REQUIRE(workers.exit_code == 0);
    for (const char* file : {"corpus.json", "corpus.html"}) {
        INFO(file);
        std::ifstream a(dir.path() + "/one/" + file), b(dir.path() + "/workers/" + file);
        const std::string x((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
        const std::string y((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
        CHECK(!x.empty());
        CHECK(x == y);
    }
    // The summary counts the same rows: the two failing presets are rows, not a failed run.
    CHECK(workers.out.find("6 presets (shard 1/1): 5 imported") != std::string::npos);
    // What only the sweep's workers are given is refused on its own.
    auto lone = test::run_crtforge(base + " --rows-fd 3");
    CHECK(lone.exit_code == 2);
    CHECK(lone.err.find("--rows-fd") != std::string::npos);
    auto closed = test::run_crtforge(base + " --rows-fd 1000 --worker-preset good/plain.slangp");
    CHECK(closed.exit_code == 2);
    CHECK(closed.err.find("'--rows-fd': descriptor 1000 is not open") != std::string::npos);
}

TEST_CASE("GLSL ES 3.00 and WebGL 2 count gl_FragCoord's rows from the top as Vulkan does (ES has no origin_upper_left)",
          "[retroarch][corpus-command][gl-es]") {
    test::TempDir dir;
    write_program_library(dir);  // chain.slangp: bands of three rows by gl_FragCoord.y, triads by its x
    check_all_agree(dir, {"chain.slangp"}, TargetId::GlslEs300);
    check_all_agree(dir, {"chain.slangp"}, TargetId::WebGl2);
}

TEST_CASE("GLSL 3.30, ES 3.00 and WebGL 2 run textureGather as four reads of its footprint, like Vulkan", "[retroarch][corpus-command][gather]") {
    test::TempDir dir;
    write_gather_library(dir);
    for (TargetId target : {TargetId::Glsl330, TargetId::GlslEs300, TargetId::WebGl2}) check_all_agree(dir, {"gather.slangp"}, target, 0, 100, 75);
}

TEST_CASE("presets with long file names import into names crtforge takes, kept apart by a hash", "[retroarch][corpus-command]") {
    test::TempDir dir;
    write_library(dir);
    // Two passes each (so the stage has a pass selector, <stage>_pass), names of 70 characters that
    // differ only past the 56th: the corpus has file names of up to 73.
    const std::string stem = "crt-royale-fast-ntsc-composite-slotmask-genesis-rainbow-effect-longer";
    const std::string two = "shaders = 2\nshader0 = ../shaders/plain.slang\nshader1 = ../shaders/plain.slang\n";
    test::write_file(dir / ("long/" + stem + "-a.slangp"), two);
    test::write_file(dir / ("long/" + stem + "-b.slangp"), two);
    std::set<std::string> stages;
    for (const char* end : {"-a", "-b"}) {
        SlangImportOptions options;
        options.root = dir.path();
        auto imported = import_slangp(dir / ("long/" + stem + end + ".slangp"), options);
        REQUIRE(imported.ok());
        INFO(imported.value().stage);
        CHECK(imported.value().stage.size() + 5 <= 64);
        CHECK(imported.value().name.size() <= 64);
        CHECK(imported.value().stage.rfind("ra_crt_royale_fast_ntsc", 0) == 0);
        CHECK(imported.value().stage.find("__") == std::string::npos);
        stages.insert(imported.value().stage);
    }
    CHECK(stages.size() == 2);

    check_all_agree(dir, {"long/" + stem + "-a.slangp", "long/" + stem + "-b.slangp"}, TargetId::Glsl330);
}

TEST_CASE("parameters named like layout qualifiers leave the qualifiers alone", "[retroarch][corpus-command]") {
    // misc/cocktail-cabinet names a parameter `location`: renamed away from the shader's own words,
    // it must not reach `layout(location = 1)`.
    test::TempDir dir;
    test::write_file(dir / "shaders/words.slang",
                     test::slang_program({"float location; float binding; ",
                                          "#pragma parameter location \"Location\" 0.25 0.0 1.0 0.05\n"
                                          "#pragma parameter binding \"Binding\" 2.0 1.0 3.0 1.0\n",
                                          "layout(location = 1) {io} vec2 vShift;\n", "    vShift = vec2(params.location, 0.0);\n",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "void main() {\n"
                                          "    FragColor = vec4(texture(Source, vTexCoord + vShift).rgb * params.binding * 0.5, 1.0);\n"
                                          "}\n"}));
    test::write_file(dir / "words.slangp", "shaders = 1\nshader0 = shaders/words.slang\n");
    check_all_agree(dir, {"words.slangp"}, TargetId::Glsl330);
}

TEST_CASE("a JPEG LUT ships as the PNG of its texels, which the shipped WebGPU driver reads like Vulkan", "[retroarch][corpus-command][wgsl]") {
    // 654 presets of the library (scanline-classic's, uborder's, koko-aio's backdrops) name JPEG
    // pictures; the driver decodes PNG only. A picture of the library's own, so skipped without it.
    const std::string jpeg = std::string(CRTFORGE_SOURCE_DIR) + "/../shared/slang-shaders/bezel/koko-aio/textures/backdrop.jpg";
    if (!std::filesystem::is_regular_file(jpeg)) {
        WARN("no RetroArch corpus JPEG at " << jpeg << ": skipped");
        return;
    }
    test::TempDir dir;
    std::filesystem::copy_file(jpeg, dir / "backdrop.jpg");
    test::write_file(dir / "shaders/lut.slang",
                     pass("layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                          "layout(set = 0, binding = 3) uniform sampler2D backdrop;\n",
                          "    FragColor = vec4(mix(texture(Source, vTexCoord).rgb, texture(backdrop, vTexCoord).rgb, 0.75) * params.GAIN, 1.0);"));
    test::write_file(dir / "lut.slangp", "shaders = 1\nshader0 = shaders/lut.slang\ntextures = backdrop\nbackdrop = backdrop.jpg\n");
    check_all_agree(dir, {"lut.slangp"}, TargetId::Wgsl);

    // What an export ships: a .png, a whole PNG of the JPEG's texels as the renders decode them.
    auto exported = test::run_crtforge("export --preset '" + (dir / "lut.slangp") + "' --target wgsl --out '" +
                                       (dir / "out") + "'");
    INFO(exported.out << exported.err);
    REQUIRE(exported.exit_code == 0);
    std::vector<std::string> luts;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir / "out"))
        if (entry.path().parent_path().filename() == "luts") luts.push_back(entry.path().string());
    REQUIRE_FALSE(luts.empty());  // the export's luts/ and the npm package's
    auto original = read_image(dir / "backdrop.jpg");
    REQUIRE(original.ok());
    for (const std::string& lut : luts) {
        INFO(lut);
        CHECK(std::filesystem::path(lut).extension() == ".png");
        auto shipped = read_image(lut);
        REQUIRE(shipped.ok());
        CHECK(shipped.value().width == original.value().width);
        const bool same_texels = shipped.value().rgba == original.value().rgba;  // not the vectors: Catch would print them
        CHECK(same_texels);
    }
}
