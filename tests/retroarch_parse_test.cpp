// The RetroArch parsers (generator/retroarch/): a .slang shader's includes, pragmas and stages, and a
// .slangp preset with its #reference chain. Well-formed inputs read back every field; each error
// class names its file, line and field; the shipped corpus's crt/ presets all load.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "crtforge/spirv_compiler.hpp"
#include "generator/retroarch/slang_source.hpp"
#include "generator/retroarch/slangp_file.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
using namespace crtforge::retroarch;
namespace fs = std::filesystem;

namespace {

const char* const kCorpus = "/work/shared/slang-shaders";

// Writes `text` to dir/rel (creating folders) and returns that path, normalised as the parsers form it.
std::string put(const test::TempDir& dir, const std::string& rel, const std::string& text) {
    const fs::path p = fs::path(dir.path()) / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary | std::ios::trunc) << text;
    return p.lexically_normal().string();
}

std::string at(const test::TempDir& dir, const std::string& rel) {
    return (fs::path(dir.path()) / rel).lexically_normal().string();
}

template <typename T>
void require_error(const Result<T>& result, const std::string& file, int line, const std::string& field,
                   const std::string& contains = {}) {
    REQUIRE_FALSE(result.ok());
    const Diagnostic& e = result.error();
    INFO(e.str());
    CHECK(e.file == file);
    CHECK(e.line == line);
    CHECK(e.field == field);
    if (!contains.empty()) CHECK_THAT(e.message, Catch::Contains(contains));
    CHECK(e.str().find('\n') == std::string::npos);
}

// The two stage sections every test shader ends with (5 lines).
const std::string kStages =
    "#pragma stage vertex\n"
    "layout(location = 0) in vec4 Position;\n"
    "void main() { gl_Position = Position; }\n"
    "#pragma stage fragment\n"
    "layout(location = 0) out vec4 FragColor;\n"
    "void main() { FragColor = vec4(1.0); }\n";

std::string shader(const std::string& head = {}) { return "#version 450\n" + head + kStages; }

// A minimal valid preset line set for one pass.
std::string one_pass(const std::string& extra = {}) { return "shaders = 1\nshader0 = pass.slang\n" + extra; }

bool has_warning(const SlangpPreset& preset, const std::string& field) {
    for (const auto& w : preset.warnings)
        if (w.field == field) return true;
    return false;
}

}  // namespace

TEST_CASE("a .slang shader splits into stages with its includes, pragmas and #line directives", "[retroarch]") {
    test::TempDir dir;
    put(dir, "inc/deeper.inc", "float deeper() { return 1.0; }\n");
    const std::string common = put(dir, "inc/common.inc",
                                   "layout(push_constant) uniform Push { float gain; float nostep; } params;\n"
                                   "#pragma parameter gain \"Gain\" 1.0 0.0 2.0 0.05\n"
                                   "#include \"deeper.inc\"\n");
    // A byte order mark and CRLF line endings, as some corpus files have.
    const std::string path = put(dir, "shaders/main.slang",
                                 "\xEF\xBB\xBF#version 450\r\n"
                                 "#include \"../inc/common.inc\"\r\n"
                                 "#pragma name MyPass\r\n"
                                 "#pragma format R16G16B16A16_SFLOAT\r\n"
                                 "#pragma parameter gain \"Gain\" 1.0 0.0 2.0 0.05\r\n"
                                 "#pragma parameter nostep \"No step\" 0.5 0.0 1.0\r\n"
                                 "#pragma include_optional \"absent.inc\"\r\n"
                                 "#pragma stage vertex\r\n"
                                 "layout(location = 0) in vec4 Position;\r\n"
                                 "void main() { gl_Position = Position * params.gain * deeper(); }\r\n"
                                 "#pragma stage fragment\r\n"
                                 "layout(location = 0) out vec4 FragColor;\r\n"
                                 "void main() { FragColor = vec4(params.nostep); }\r\n");
    auto loaded = load_slang_source(path, dir.path());
    INFO((loaded.ok() ? std::string() : loaded.error().str()));
    REQUIRE(loaded.ok());
    const SlangSource& s = loaded.value();
    CHECK(s.path == path);
    CHECK(s.name == "MyPass");
    CHECK(s.format == "R16G16B16A16_SFLOAT");
    REQUIRE(s.parameters.size() == 2);  // gain declared twice, identically: kept once
    CHECK(s.parameters[0].id == "gain");
    CHECK(s.parameters[0].description == "Gain");
    CHECK(s.parameters[0].initial == 1.0);
    CHECK(s.parameters[0].maximum == 2.0);
    CHECK(s.parameters[0].step == 0.05);
    CHECK(s.parameters[0].has_step);
    CHECK(s.parameters[0].where.file == common);
    CHECK(s.parameters[0].where.line == 2);
    CHECK(s.parameters[1].id == "nostep");
    CHECK_FALSE(s.parameters[1].has_step);
    CHECK(s.parameters[1].step == Approx(0.1));  // RetroArch's default: a tenth of the range
    CHECK(s.parameters[1].where.file == path);
    CHECK(s.parameters[1].where.line == 6);
    CHECK(s.files == std::vector<std::string>{path, common, at(dir, "inc/deeper.inc")});
    CHECK(s.missing_optional == std::vector<std::string>{at(dir, "shaders/absent.inc")});

    for (const std::string* stage : {&s.vertex, &s.fragment}) {
        CHECK(stage->rfind("#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n", 0) == 0);
        CHECK(stage->find("#pragma") == std::string::npos);
        CHECK(stage->find('\r') == std::string::npos);
        CHECK(stage->find("#line 1 \"" + common + "\"") != std::string::npos);
        CHECK(stage->find("float deeper()") != std::string::npos);
    }
    CHECK(s.vertex.find("FragColor") == std::string::npos);
    CHECK(s.fragment.find("gl_Position") == std::string::npos);

    CompileOptions options;
    options.optimize = false;
    options.stage = ShaderStage::Vertex;
    auto vertex = compile_to_spirv(s.vertex, options);
    INFO((vertex.ok() ? std::string() : vertex.error().str()));
    CHECK(vertex.ok());
    options.stage = ShaderStage::Fragment;
    auto fragment = compile_to_spirv(s.fragment, options);
    INFO((fragment.ok() ? std::string() : fragment.error().str()));
    CHECK(fragment.ok());
}

TEST_CASE("glslang's errors in a .slang stage point at the original file and line", "[retroarch]") {
    test::TempDir dir;
    const std::string inc = put(dir, "helper.inc",
                                "float helper() { return 1.0; }\n"
                                "float broken() { return missing_in_include; }\n");
    const std::string never = put(dir, "never.inc", "float never_used() { return 0.0; }\n");
    (void)never;
    const std::string body =
        "#version 450\n"                                    // 1
        "#pragma parameter a \"A\" 0.5 0.0 1.0 0.1\n"       // 2
        "#if 0\n"                                           // 3
        "#include \"never.inc\"\n"                          // 4
        "#endif\n"                                          // 5
        "#pragma stage vertex\n"                            // 6
        "layout(location = 0) in vec4 Position;\n"          // 7
        "void main() { gl_Position = Position; }\n"         // 8
        "#pragma stage fragment\n"                          // 9
        "#pragma parameter b \"B\" 0.5 0.0 1.0 0.1\n"       // 10
        "layout(location = 0) out vec4 FragColor;\n"        // 11
        "void main() {\n"                                   // 12
        "    FragColor = vec4(missing_in_main);\n"          // 13
        "}\n";                                              // 14
    const std::string path = put(dir, "main.slang", body);
    auto s = load_slang_source(path, dir.path());
    REQUIRE(s.ok());
    CompileOptions options;
    options.optimize = false;
    options.stage = ShaderStage::Fragment;
    auto fragment = compile_to_spirv(s.value().fragment, options);
    REQUIRE_FALSE(fragment.ok());
    INFO(fragment.error().str());
    CHECK(fragment.error().file == path);
    CHECK(fragment.error().line == 13);

    // An error inside an included file, with the include in the fragment section.
    const std::string path2 = put(dir, "main2.slang",
                                  "#version 450\n"                                  // 1
                                  "#pragma stage vertex\n"                          // 2
                                  "layout(location = 0) in vec4 Position;\n"        // 3
                                  "void main() { gl_Position = Position; }\n"       // 4
                                  "#pragma stage fragment\n"                        // 5
                                  "#include \"helper.inc\"\n"                       // 6
                                  "layout(location = 0) out vec4 FragColor;\n"      // 7
                                  "void main() { FragColor = vec4(undeclared); }\n");  // 8
    auto s2 = load_slang_source(path2, dir.path());
    REQUIRE(s2.ok());
    auto f2 = compile_to_spirv(s2.value().fragment, options);
    REQUIRE_FALSE(f2.ok());
    INFO(f2.error().str());
    CHECK(f2.error().file == inc);
    CHECK(f2.error().line == 2);
    // ... and once the include's error is fixed, the main file's at its own line.
    put(dir, "helper.inc", "float helper() { return 1.0; }\n");
    auto s3 = load_slang_source(path2, dir.path());
    REQUIRE(s3.ok());
    auto f3 = compile_to_spirv(s3.value().fragment, options);
    REQUIRE_FALSE(f3.ok());
    INFO(f3.error().str());
    CHECK(f3.error().file == path2);
    CHECK(f3.error().line == 8);
}

TEST_CASE("every .slang error is one line at its file, line and field", "[retroarch]") {
    test::TempDir dir;
    const std::string root = dir.path();

    SECTION("the first line is not #version") {
        const std::string p = put(dir, "a.slang", "// comment\n#version 450\n" + kStages);
        require_error(load_slang_source(p, root), p, 1, "version");
    }
    SECTION("a missing shader") {
        require_error(load_slang_source(at(dir, "none.slang"), root), at(dir, "none.slang"), 0, "", "does not exist");
    }
    SECTION("a missing include") {
        const std::string p = put(dir, "a.slang", shader("// x\n#include \"nowhere.inc\"\n"));
        require_error(load_slang_source(p, root), p, 3, "include", "nowhere.inc");
    }
    SECTION("an include statement without a quoted file") {
        const std::string p = put(dir, "a.slang", shader("#include <common.inc>\n"));
        require_error(load_slang_source(p, root), p, 2, "include");
    }
    SECTION("an include cycle") {
        put(dir, "x.inc", "#include \"y.inc\"\n");
        const std::string y = put(dir, "y.inc", "// y\n#include \"x.inc\"\n");
        const std::string p = put(dir, "a.slang", shader("#include \"x.inc\"\n"));
        require_error(load_slang_source(p, root), y, 2, "include", "cycle");
    }
    SECTION("includes nested too deep") {
        for (int i = 0; i <= kMaxIncludeDepth + 1; ++i)
            put(dir, "deep" + std::to_string(i) + ".inc", "#include \"deep" + std::to_string(i + 1) + ".inc\"\n");
        put(dir, "deep" + std::to_string(kMaxIncludeDepth + 2) + ".inc", "\n");
        const std::string p = put(dir, "a.slang", shader("#include \"deep0.inc\"\n"));
        require_error(load_slang_source(p, root), at(dir, "deep" + std::to_string(kMaxIncludeDepth - 1) + ".inc"), 1,
                      "include", "nested");
    }
    SECTION("an include outside the root, by .. or by a symlink") {
        put(dir, "outside.inc", "\n");
        const std::string p = put(dir, "sub/a.slang", shader("#include \"../outside.inc\"\n"));
        require_error(load_slang_source(p, at(dir, "sub")), p, 2, "include", "outside the root");
        fs::create_symlink(at(dir, "outside.inc"), at(dir, "sub/link.inc"));
        const std::string q = put(dir, "sub/b.slang", shader("\n#include \"link.inc\"\n"));
        require_error(load_slang_source(q, at(dir, "sub")), q, 3, "include", "outside the root");
        CHECK(load_slang_source(q, root).ok());  // inside the wider root
        CHECK(load_slang_source(q, "").ok());    // no root: no limit
    }
    SECTION("the shader itself outside the root") {
        const std::string p = put(dir, "a.slang", shader());
        put(dir, "sub/keep", "");
        require_error(load_slang_source(p, at(dir, "sub")), p, 0, "path", "outside the root");
    }
    SECTION("an included file over the size bound") {
        put(dir, "big.inc", std::string(5u << 20, ' '));
        const std::string p = put(dir, "a.slang", shader("#include \"big.inc\"\n"));
        require_error(load_slang_source(p, root), p, 2, "include", "bytes");
    }
    SECTION("a file name a #line directive cannot carry") {
        put(dir, "we\"ird.inc", "\n");
        const std::string p = put(dir, "a.slang", shader("#include \"we\\\"ird.inc\"\n"));
        // The include's name ends at the second '"': `we\` does not exist.
        require_error(load_slang_source(p, root), p, 2, "include");
        const std::string q = put(dir, "q\"uote.slang", shader());
        require_error(load_slang_source(q, root), q, 0, "path", "double quote");
    }
    SECTION("malformed #pragma parameter lines") {
        const char* bad[] = {
            "#pragma parameter gain Gain 1.0 0.0 2.0 0.1",                 // description not quoted
            "#pragma parameter gain \"Gain 1.0 0.0 2.0 0.1",               // description not closed
            "#pragma parameter gain \"Gain\" 1.0 0.0",                     // MAXIMUM missing
            "#pragma parameter gain \"Gain\" one 0.0 2.0",                 // not a number
            "#pragma parameter  ",                                         // no id
            "#pragma parameter gain \"A description that is longer than the sixty-three bytes RetroArch keeps\" 1 0 2",
        };
        for (const char* line : bad) {
            INFO(line);
            const std::string p = put(dir, "a.slang", shader("\n" + std::string(line) + "\n"));
            require_error(load_slang_source(p, root), p, 3, "pragma parameter");
        }
    }
    SECTION("a parameter declared again with other values names both places") {
        const std::string inc = put(dir, "p.inc", "#pragma parameter gain \"Gain\" 1.0 0.0 2.0 0.1\n");
        const std::string p =
            put(dir, "a.slang", shader("#include \"p.inc\"\n#pragma parameter gain \"Gain\" 1.0 0.0 3.0 0.1\n"));
        require_error(load_slang_source(p, root), p, 3, "pragma parameter", inc + ":1");
    }
    SECTION("numbers read the way RetroArch's strtod reads them") {
        const std::string p = put(dir, "a.slang",
                                  shader("#pragma parameter t \"Title\" 0 0 0.0.001\n"
                                         "#pragma parameter u \"U\" 9.0 0.0 20.0 1.0' // trailing\n"));
        auto s = load_slang_source(p, root);
        REQUIRE(s.ok());
        CHECK(s.value().parameters[0].maximum == 0.0);
        CHECK(s.value().parameters[0].step == 0.001);
        CHECK(s.value().parameters[1].step == 1.0);
    }
    SECTION("a stage section is missing") {
        const std::string p = put(dir, "a.slang", "#version 450\n#pragma stage vertex\nvoid main() {}\n");
        require_error(load_slang_source(p, root), p, 0, "pragma stage", "fragment");
    }
    SECTION("an unknown stage") {
        const std::string p = put(dir, "a.slang", shader("#pragma stage geometry\n"));
        require_error(load_slang_source(p, root), p, 2, "pragma stage");
    }
    SECTION("an unknown format and a second name") {
        const std::string p = put(dir, "a.slang", shader("#pragma format RGBA8\n"));
        require_error(load_slang_source(p, root), p, 2, "pragma format", "RGBA8");
        const std::string q = put(dir, "b.slang", shader("#pragma name A\n#pragma name B\n"));
        require_error(load_slang_source(q, root), q, 3, "pragma name", q + ":2");
    }
    SECTION("a missing root folder") {
        const std::string p = put(dir, "a.slang", shader());
        require_error(load_slang_source(p, at(dir, "no-such-root")), at(dir, "no-such-root"), 0, "root");
    }
}

TEST_CASE("a .slangp preset reads back every key", "[retroarch]") {
    test::TempDir dir;
    put(dir, "shaders/first.slang", shader());
    put(dir, "shaders/second.slang", shader());
    put(dir, "textures/mask.png", "png");
    const std::string path = put(dir, "presets/p.slangp",
                                 "\xEF\xBB\xBF# A preset\r\n"                              // 1
                                 "shaders = \"2\"\r\n"                                     // 2
                                 "feedback_pass = \"0\"\r\n"                               // 3
                                 "shader0 = ../shaders/first.slang\r\n"                    // 4
                                 "alias0 = \"FirstPass\"\r\n"                              // 5
                                 "filter_linear0 = true // sampled linearly\r\n"           // 6
                                 "wrap_mode0 = mirrored_repeat\r\n"                        // 7
                                 "mipmap_input0 = \"1\"\r\n"                               // 8
                                 "float_framebuffer0 = false\r\n"                          // 9
                                 "srgb_framebuffer0 = 0\r\n"                               // 10
                                 "frame_count_mod0 = 100\r\n"                              // 11
                                 "scale_type0 = source\r\n"                                // 12
                                 "scale0 = 2.0\r\n"                                        // 13
                                 "\r\n"                                                    // 14
                                 "/* a block\r\n"                                          // 15
                                 "   comment */\r\n"                                       // 16
                                 "shader1 = \"../shaders/second.slang\"\r\n"               // 17
                                 "scale_type_x1 = absolute\r\n"                            // 18
                                 "scale_x1 = 640.0\r\n"                                    // 19
                                 "scale_type_y1 = viewport\r\n"                            // 20
                                 "scale_y1 = 1.0  # trailing comment\r\n"                  // 21
                                 "textures = \"Mask;;Lut\"\r\n"                            // 22
                                 "Mask = ../textures/mask.png\r\n"                         // 23
                                 "Mask_linear = true\r\n"                                  // 24
                                 "Mask_mipmap = false\r\n"                                 // 25
                                 "Mask_wrap_mode = repeat\r\n"                             // 26
                                 "Lut = \"../textures/mask.png\"\r\n"                      // 27
                                 "parameters = \"gain;bias\"\r\n"                          // 28
                                 "gain = \"1.5\"\r\n"                                      // 29
                                 "bias = -0.25\r\n"                                        // 30
                                 "wild = 3\r\n");                                          // 31
    auto loaded = load_slangp(path, dir.path());
    INFO((loaded.ok() ? std::string() : loaded.error().str()));
    REQUIRE(loaded.ok());
    const SlangpPreset& p = loaded.value();
    CHECK(p.path == path);
    CHECK(p.files == std::vector<std::string>{path});
    CHECK(p.warnings.empty());
    REQUIRE(p.passes.size() == 2);
    const SlangpPass& a = p.passes[0];
    CHECK(a.shader == at(dir, "shaders/first.slang"));
    CHECK(a.alias == "FirstPass");
    CHECK(a.filter_linear == std::optional<bool>(true));
    CHECK(a.wrap_mode == std::optional<std::string>("mirrored_repeat"));
    CHECK(a.mipmap_input == std::optional<bool>(true));
    CHECK(a.float_framebuffer == std::optional<bool>(false));
    CHECK(a.srgb_framebuffer == std::optional<bool>(false));
    CHECK(a.frame_count_mod == std::optional<int>(100));
    CHECK(a.scale_type == std::optional<std::string>("source"));
    CHECK(a.scale == std::optional<double>(2.0));
    CHECK_FALSE(a.scale_x.has_value());
    CHECK(a.where.file == path);
    CHECK(a.where.line == 4);
    CHECK(a.key_lines.at("scale_type").line == 12);
    CHECK(a.key_lines.at("shader").line == 4);
    const SlangpPass& b = p.passes[1];
    CHECK(b.shader == at(dir, "shaders/second.slang"));
    CHECK(b.alias.empty());
    CHECK_FALSE(b.filter_linear.has_value());
    CHECK(b.scale_type_x == std::optional<std::string>("absolute"));
    CHECK(b.scale_x == std::optional<double>(640.0));
    CHECK(b.scale_type_y == std::optional<std::string>("viewport"));
    CHECK(b.scale_y == std::optional<double>(1.0));
    CHECK(b.where.line == 17);
    REQUIRE(p.textures.size() == 2);
    CHECK(p.textures[0].name == "Mask");
    CHECK(p.textures[0].path == at(dir, "textures/mask.png"));
    CHECK(p.textures[0].linear == std::optional<bool>(true));
    CHECK(p.textures[0].mipmap == std::optional<bool>(false));
    CHECK(p.textures[0].wrap_mode == std::optional<std::string>("repeat"));
    CHECK(p.textures[0].where.line == 23);
    CHECK(p.textures[1].name == "Lut");
    CHECK_FALSE(p.textures[1].linear.has_value());
    using Values = std::vector<std::pair<std::string, double>>;
    CHECK(p.parameters == Values{{"gain", 1.5}, {"bias", -0.25}, {"wild", 3.0}});
    CHECK(p.parameter_lines.at("gain").line == 29);
    CHECK(p.parameter_lines.at("wild").line == 31);
}

TEST_CASE("a .slangp #reference chain: passes from the root, values from every file", "[retroarch]") {
    test::TempDir dir;
    put(dir, "pass.slang", shader());
    put(dir, "lut.png", "png");
    put(dir, "other/lut2.png", "png");
    const std::string base = put(dir, "base.slangp", one_pass("textures = LUT\nLUT = lut.png\nA = 1\nB = 2\n"));
    const std::string mid = put(dir, "mid.slangp",
                                "#reference \"base.slangp\"\n"   // 1
                                "A = 3\n"                        // 2
                                "LUT = \"other/lut2.png\"\n"     // 3
                                "filter_linear0 = true\n");      // 4: ignored, the passes are base's
    const std::string params = put(dir, "top/overrides.params", "A = 5\nC = 6\n");
    const std::string top = put(dir, "top/top.slangp",
                                "#reference \"../mid.slangp\"\n"
                                "#reference \"overrides.params\"\n"
                                "B = 4\n");
    auto loaded = load_slangp(top, dir.path());
    INFO((loaded.ok() ? std::string() : loaded.error().str()));
    REQUIRE(loaded.ok());
    const SlangpPreset& p = loaded.value();
    REQUIRE(p.passes.size() == 1);
    CHECK(p.passes[0].shader == at(dir, "pass.slang"));
    CHECK(p.passes[0].where.file == base);
    CHECK_FALSE(p.passes[0].filter_linear.has_value());
    CHECK(has_warning(p, "filter_linear0"));
    REQUIRE(p.textures.size() == 1);
    CHECK(p.textures[0].path == at(dir, "other/lut2.png"));
    CHECK(p.textures[0].where.file == mid);
    CHECK(p.textures[0].where.line == 3);
    // Applied in the order base, mid, overrides.params, top: a later #reference beats an earlier one,
    // and a file beats what it references.
    using Values = std::vector<std::pair<std::string, double>>;
    CHECK(p.parameters == Values{{"A", 5.0}, {"B", 4.0}, {"C", 6.0}});
    CHECK(p.parameter_lines.at("A").file == params);
    CHECK(p.parameter_lines.at("B").file == top);
    CHECK(p.files == std::vector<std::string>{top, mid, base, params});
}

TEST_CASE("every .slangp error is one line at its file, line and field", "[retroarch]") {
    test::TempDir dir;
    const std::string root = dir.path();
    put(dir, "pass.slang", shader());

    SECTION("a missing preset and a missing #reference target") {
        require_error(load_slangp(at(dir, "none.slangp"), root), at(dir, "none.slangp"), 0, "", "does not exist");
        const std::string p = put(dir, "a.slangp", "# refers\n#reference \"gone.slangp\"\n");
        require_error(load_slangp(p, root), p, 2, "#reference", "does not exist");
    }
    SECTION("a malformed line") {
        // What RetroArch's config reader drops is dropped, with a warning at its line.
        const std::string p = put(dir, "a.slangp", one_pass("gain \"1.0\"\n"));
        auto dropped = load_slangp(p, root);
        REQUIRE(dropped.ok());
        REQUIRE(dropped.value().warnings.size() == 1);
        CHECK(dropped.value().warnings[0].line == 3);
        CHECK(dropped.value().warnings[0].field == "gain");
        CHECK_THAT(dropped.value().warnings[0].message, Catch::Matchers::Contains("drops this line"));
        const std::string q = put(dir, "b.slangp", "shaders=1\nshader0 = pass.slang\n");
        require_error(load_slangp(q, root), q, 0, "shaders", "no 'shaders' entry");
        const std::string r = put(dir, "c.slangp", one_pass("/* note\nscale0 = 2.0\n*/\n"));
        require_error(load_slangp(r, root), r, 4, "", "block comments");
        const std::string s = put(dir, "d.slangp", one_pass("  #reference \"x.slangp\"\n"));
        require_error(load_slangp(s, root), s, 3, "#reference", "first column");
    }
    SECTION("shaders missing or out of range") {
        const std::string p = put(dir, "a.slangp", "shader0 = pass.slang\n");
        require_error(load_slangp(p, root), p, 0, "shaders");
        for (const char* value : {"0", "65", "two", "-1", "1.5"}) {
            INFO(value);
            const std::string q = put(dir, "b.slangp", "\nshaders = " + std::string(value) + "\nshader0 = pass.slang\n");
            require_error(load_slangp(q, root), q, 2, "shaders");
        }
    }
    SECTION("a shaderN missing") {
        const std::string p = put(dir, "a.slangp", "shaders = 3\nshader0 = pass.slang\nshader2 = pass.slang\n");
        require_error(load_slangp(p, root), p, 1, "shader1", "shader0 to shader2");
        const std::string q = put(dir, "b.slangp", "shaders = 1\nshader0 = missing.slang\n");
        require_error(load_slangp(q, root), q, 2, "shader0", "does not exist");
    }
    SECTION("bad enum values, booleans and numbers") {
        const std::pair<const char*, const char*> bad[] = {
            {"scale_type0 = big", "scale_type0"},    {"scale_type_y0 = Source", "scale_type_y0"},
            {"filter_linear0 = yes", "filter_linear0"}, {"mipmap_input0 = True", "mipmap_input0"},
            {"scale0 = 2x", "scale0"},               {"scale_x0 = \"\"  \nscale_y0 = nan", "scale_y0"},
            {"frame_count_mod0 = -1", "frame_count_mod0"},
        };
        for (const auto& [line, field] : bad) {
            INFO(line);
            const std::string p = put(dir, "a.slangp", one_pass(std::string(line) + "\n"));
            auto r = load_slangp(p, root);
            REQUIRE_FALSE(r.ok());
            CHECK(r.error().file == p);
            CHECK(r.error().field == field);
            CHECK(r.error().line >= 3);
        }
        // An unknown wrap mode is RetroArch's default with a warning, not an error (as in RetroArch).
        const std::string q = put(dir, "b.slangp", one_pass("wrap_mode0 = clamp\n"));
        auto r = load_slangp(q, root);
        REQUIRE(r.ok());
        CHECK_FALSE(r.value().passes[0].wrap_mode.has_value());
        CHECK(has_warning(r.value(), "wrap_mode0"));
    }
    SECTION("textures") {
        const std::string p = put(dir, "a.slangp", one_pass("textures = \"A;B\"\nA = pass.slang\n"));
        require_error(load_slangp(p, root), p, 3, "textures", "'B'");
        const std::string q = put(dir, "b.slangp", one_pass("textures = A\nA = nothing.png\n"));
        require_error(load_slangp(q, root), q, 4, "A", "does not exist");
    }
    SECTION("a #reference cycle and a chain too deep") {
        put(dir, "x.slangp", "#reference \"y.slangp\"\n");
        const std::string y = put(dir, "y.slangp", "\n#reference \"x.slangp\"\n");
        require_error(load_slangp(at(dir, "x.slangp"), root), y, 2, "#reference", "cycle");
        for (int i = 0; i <= kMaxReferenceDepth + 1; ++i)
            put(dir, fmt::format("r{}.slangp", i), fmt::format("#reference \"r{}.slangp\"\n", i + 1));
        put(dir, fmt::format("r{}.slangp", kMaxReferenceDepth + 2), one_pass());
        require_error(load_slangp(at(dir, "r0.slangp"), root), at(dir, "r" + std::to_string(kMaxReferenceDepth) + ".slangp"),
                      1, "#reference", "more than");
        // 16 steps are fine.
        CHECK(load_slangp(at(dir, "r2.slangp"), root).ok());
    }
    SECTION("a second #reference leading to a full preset") {
        put(dir, "full.slangp", one_pass());
        const std::string p = put(dir, "a.slangp", "#reference \"full.slangp\"\n#reference \"full.slangp\"\n");
        require_error(load_slangp(p, root), p, 2, "#reference", "only the first");
    }
    SECTION("a path escaping the root") {
        put(dir, "outside.slang", shader());
        const std::string p = put(dir, "sub/a.slangp", "shaders = 1\nshader0 = ../outside.slang\n");
        require_error(load_slangp(p, at(dir, "sub")), p, 2, "shader0", "outside the root");
        put(dir, "outside.slangp", one_pass());
        const std::string q = put(dir, "sub/b.slangp", "#reference \"../outside.slangp\"\n");
        require_error(load_slangp(q, at(dir, "sub")), q, 1, "#reference", "outside the root");
        require_error(load_slangp(at(dir, "outside.slangp"), at(dir, "sub")), at(dir, "outside.slangp"), 0, "path",
                      "outside the root");
    }
    SECTION("a file over the size bound") {
        put(dir, "big.slangp", one_pass() + std::string(5u << 20, '\n'));
        const std::string p = put(dir, "a.slangp", "#reference \"big.slangp\"\n");
        require_error(load_slangp(p, root), p, 1, "#reference", "bytes");
    }
}

TEST_CASE("every crt/ preset of the RetroArch corpus loads with all its shaders", "[retroarch]") {
    const fs::path crt = fs::path(kCorpus) / "crt";
    if (!fs::is_directory(crt)) {
        WARN("the RetroArch corpus is not at " << kCorpus << ": skipped");
        return;
    }
    int presets = 0, shaders = 0;
    std::map<std::string, bool> seen;
    for (const auto& entry : fs::recursive_directory_iterator(crt)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".slangp") continue;
        ++presets;
        auto preset = load_slangp(entry.path().string(), kCorpus);
        INFO(entry.path().string());
        if (!preset.ok()) FAIL_CHECK(preset.error().str());
        if (!preset.ok()) continue;
        for (const SlangpPass& pass : preset.value().passes) {
            if (!seen.emplace(pass.shader, true).second) continue;
            ++shaders;
            auto source = load_slang_source(pass.shader, kCorpus);
            if (!source.ok()) FAIL_CHECK(source.error().str());
        }
    }
    CHECK(presets == 131);
    CHECK(shaders > 300);
}

// The whole corpus (2547 presets, a few seconds): hidden, run by name or with "[retroarch-corpus]".
// Reports how many load and why the others do not; fails only on a crash-like result (none loaded).
TEST_CASE("the whole RetroArch corpus: how many presets load", "[.][retroarch-corpus]") {
    if (!fs::is_directory(kCorpus)) {
        WARN("the RetroArch corpus is not at " << kCorpus << ": skipped");
        return;
    }
    std::vector<std::string> paths;
    for (const auto& entry : fs::recursive_directory_iterator(kCorpus))
        if (entry.is_regular_file() && entry.path().extension() == ".slangp") paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
    std::map<std::string, std::string> shader_errors;  // shader -> error ("" when it loads)
    int loaded = 0;
    std::string failures;
    for (const std::string& path : paths) {
        auto preset = load_slangp(path, kCorpus);
        std::string error = preset.ok() ? std::string() : preset.error().str();
        if (preset.ok())
            for (const SlangpPass& pass : preset.value().passes) {
                auto it = shader_errors.find(pass.shader);
                if (it == shader_errors.end()) {
                    auto source = load_slang_source(pass.shader, kCorpus);
                    it = shader_errors.emplace(pass.shader, source.ok() ? std::string() : source.error().str()).first;
                }
                if (!it->second.empty()) {
                    error = path + ": pass " + pass.shader + ": " + it->second;
                    break;
                }
            }
        if (error.empty()) ++loaded;
        else failures += "\n  " + error;
    }
    WARN(loaded << " of " << paths.size() << " presets load (" << shader_errors.size() << " shaders read)" << failures);
    CHECK(loaded > 0);
}
