// Where an imported pass draws, on every target as on Vulkan: a pass 1 pixel wide or tall in both
// Godots, a vertex stage that moves its quad (and the location its corner takes beside the
// stage's own varyings), SourceSize in whole pixels, gl_FragCoord's rows on GL ES and WebGL 2.
#include <catch2/catch.hpp>

#include <array>
#include <functional>

#include <fmt/format.h>

#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "tests/retroarch_test_support.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
using namespace crtforge::test::retroarch;

namespace {

// A one-pass preset drawn at 8 x 4 on each of `targets`: every pixel's red, green and blue against
// `expected(x, y)`.
void check_pixels_8x4(const TemplateLibrary& lib, const std::string& name, std::initializer_list<TargetId> targets,
                      const std::function<std::array<double, 3>(int x, int y)>& expected) {
    render_on_each(lib, name, targets, {8, 4}, {8, 4}, [&](TargetId, const Image& image) {
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x) {
                INFO("pixel " << x << "," << y);
                const std::array<double, 3> want = expected(x, y);
                for (int c = 0; c < 3; ++c) CHECK(pixel_at(image, x, y)[c] == Approx(want[c]).margin(0.002));
            }
    });
}

}  // namespace

TEST_CASE("a pass 1 pixel wide or tall renders in both Godots as on Vulkan: drawn 2 pixels for 1, its readers told 1",
          "[retroarch][import][godot]") {
    // Godot draws nothing into a viewport under 2 pixels (godotengine/godot#26187). Column is 1 x 4
    // and Dot 1 x 1: each must compute its one pixel (its x coordinate 0.5, gl_FragCoord.x 0.5) in
    // both of Godot's, and every reader must see a texture 1 pixel wide: its size queries, the
    // clamp-to-border emulation (whose fade scales with the size) and SourceSize.
    test::TempDir dir;
    test::write_file(dir / "shaders/column.slang",
                     test::slang_program({"", "", "", "",
                                          "void main() { FragColor = vec4(vTexCoord.x, vTexCoord.y, gl_FragCoord.x / 4.0, 1.0); }\n"}));
    test::write_file(dir / "shaders/dot.slang",
                     test::slang_program({"", "", "", "",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "void main() {\n"
                                          "    vec2 size = vec2(textureSize(Source, 0));\n"
                                          "    FragColor = vec4(texture(Source, vec2(0.5, 0.6)).g, size.x / 4.0, size.y / 8.0, params.SourceSize.x / 4.0);\n"
                                          "}\n"}));
    test::write_file(dir / "shaders/show.slang",
                     test::slang_program({"", "", "", "",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "layout(set = 0, binding = 3) uniform sampler2D Column;\n"
                                          "void main() {\n"
                                          "    int column = int(vTexCoord.x * 4.0);\n"
                                          "    vec4 dot = texture(Source, vec2(0.5));\n"
                                          "    if (column == 0) FragColor = vec4(texture(Column, vec2(0.5, vTexCoord.y)).rgb, 1.0);\n"
                                          "    else if (column == 1) FragColor = vec4(texture(Column, vec2(0.1, vTexCoord.y)).rgb, 1.0);\n"
                                          "    else if (column == 2) FragColor = vec4(dot.rgb, 1.0);\n"
                                          "    else FragColor = vec4(dot.a, float(textureSize(Column, 0).x) / 4.0, params.SourceSize.y / 4.0, 1.0);\n"
                                          "}\n"}));
    const std::string slangp =
        "shaders = 3\n"
        "shader0 = ../shaders/column.slang\nalias0 = Column\nscale_type0 = absolute\nscale_x0 = 1\nscale_y0 = 4\n"
        "shader1 = ../shaders/dot.slang\nalias1 = Dot\nscale_type1 = absolute\nscale1 = 1\n"
        "filter_linear1 = true\nwrap_mode1 = clamp_to_border\n"  // how Column is read, by Dot and by show
        "shader2 = ../shaders/show.slang\nfilter_linear2 = false\nscale_type2 = viewport\n";
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "thin", slangp, 3);
    const Preset& preset = *lib->find_preset("thin");
    const Image input = Image::make(8, 4, {0.5f, 0.5f, 0.5f, 1.0f});  // the display's aspect: no letterbox
    TargetRenderer renderer;
    const Image vulkan = render_imported_or_fail(renderer, *lib, preset, TargetId::Spirv, input, 8, 4, {1}).front();
    // What Vulkan draws (each row's centre v = (row + 0.5) / 4, Column's rows at y = (r + 0.5) / 4).
    for (int row = 0; row < 4; ++row) {
        INFO("row " << row);
        const float y = (row + 0.5f) / 4.0f;
        CHECK(pixel_at(vulkan, 0, row)[0] == Approx(0.5).margin(0.002));     // Column's x: its one pixel's centre
        CHECK(pixel_at(vulkan, 0, row)[1] == Approx(y).margin(0.002));
        CHECK(pixel_at(vulkan, 0, row)[2] == Approx(0.125).margin(0.002));   // gl_FragCoord.x 0.5
        CHECK(pixel_at(vulkan, 4, row)[0] == Approx(0.6).margin(0.002));     // rows 1 and 2 of Column, linearly
        CHECK(pixel_at(vulkan, 4, row)[1] == Approx(0.25).margin(0.002));    // textureSize: 1 wide
        CHECK(pixel_at(vulkan, 4, row)[2] == Approx(0.5).margin(0.002));     // and 4 tall
        CHECK(pixel_at(vulkan, 6, row)[0] == Approx(0.25).margin(0.002));    // Dot's SourceSize.x: 1
        CHECK(pixel_at(vulkan, 6, row)[1] == Approx(0.25).margin(0.002));    // show's textureSize(Column).x: 1
        CHECK(pixel_at(vulkan, 6, row)[2] == Approx(0.25).margin(0.002));    // show's SourceSize.y (Dot): 1
        // u = 0.1 reads 0.6 of the texel and 0.4 of the (black) border: the fade of a texture 1 wide.
        for (int c = 0; c < 3; ++c) CHECK(pixel_at(vulkan, 2, row)[c] == Approx(pixel_at(vulkan, 0, row)[c] * 0.6f).margin(0.003));
    }
    for (TargetId target : {TargetId::Godot4, TargetId::Godot3}) {
        INFO(target_info(target).name);
        const Image godot = render_imported_or_fail(renderer, *lib, preset, target, input, 8, 4, {1}).front();
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x)
                for (int c = 0; c < 3; ++c) {
                    INFO("pixel " << x << "," << y << " channel " << c);
                    CHECK(pixel_at(godot, x, y)[c] == Approx(pixel_at(vulkan, x, y)[c]).margin(0.003));  // Godot's screen: 8 bits
                }
    }
    // Where the two pixels could differ, the pass is refused, saying why: derivatives, which are
    // 0 across two equal pixels and RetroArch's helper pixel's slope on one.
    test::write_file(dir / "shaders/column.slang",
                     test::slang_program({"", "", "", "", "void main() { FragColor = vec4(dFdx(vTexCoord.x), vTexCoord.y, 0.0, 1.0); }\n"}));
    const std::shared_ptr<TemplateLibrary> slope = import_text_or_fail(dir, "slope", slangp, 3);
    for (TargetId target : {TargetId::Godot4, TargetId::Godot3}) {
        auto images = render_imported(renderer, *slope, *slope->find_preset("slope"), target, input, 8, 4, {1});
        REQUIRE_FALSE(images.ok());
        CHECK_THAT(images.error().str(), Catch::Contains("pass Column is 1 pixel wide") && Catch::Contains("derivatives"));
    }
}

TEST_CASE("a pass that moves its quad draws it there on every target: where its clip position puts it, gl_FragCoord too",
          "[retroarch][import][godot]") {
    // RetroArch draws the quad where gl_Position puts it (newpixie-mini turns it upside down,
    // metacrt's bufC mirrors it); a Godot node has a quad of its own. Moved's quad covers the
    // middle half of the width, upside down: its pixels read their coordinates from the moved
    // corners and gl_FragCoord from the framebuffer, and the pixels it leaves keep the clear (0).
    // Middle is 8 x 4 between two passes; the last pass (Last, the display) moves its quad too.
    const std::string moved_vertex = "gl_Position = global.MVP * vec4(Position.x * 0.5 + 0.25, 1.0 - Position.y, 0.0, 1.0);\n";
    const std::string fragment =
        "void main() { FragColor = vec4(vTexCoord.y, gl_FragCoord.x / params.OutputSize.x, gl_FragCoord.y / params.OutputSize.y, 1.0); }\n";
    test::TempDir dir;
    test::write_file(dir / "shaders/moved.slang", test::slang_program({"vec4 OutputSize; ", "", "", moved_vertex, fragment}));
    test::write_file(dir / "shaders/copy.slang",
                     test::slang_program({"", "", "", "",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "void main() { FragColor = texture(Source, vTexCoord); }\n"}));
    test::write_file(dir / "shaders/flip.slang",  // the last pass: turned upside down only
                     test::slang_program({"", "", "", "gl_Position = global.MVP * vec4(Position.x, 1.0 - Position.y, 0.0, 1.0);\n",
                                          "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                          "void main() { FragColor = vec4(texture(Source, vTexCoord).rgb, 1.0); }\n"}));
    const std::string slangp = "shaders = 3\n"
                               "shader0 = ../shaders/moved.slang\nalias0 = Middle\nscale_type0 = absolute\nscale_x0 = 8\nscale_y0 = 4\n"
                               "shader1 = ../shaders/copy.slang\nfilter_linear1 = false\nscale_type1 = source\n"
                               "shader2 = ../shaders/flip.slang\nfilter_linear2 = false\nscale_type2 = viewport\n";
    const std::shared_ptr<TemplateLibrary> lib = import_text_or_fail(dir, "moved", slangp, 3);
    const Preset& preset = *lib->find_preset("moved");
    const Image input = Image::make(8, 4, {0.5f, 0.5f, 0.5f, 1.0f});  // the display's aspect: no letterbox
    TargetRenderer renderer;
    const Image vulkan = render_imported_or_fail(renderer, *lib, preset, TargetId::Spirv, input, 8, 4, {1}).front();
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            INFO("pixel " << x << "," << y);
            const int row = 3 - y;  // Middle's row, the last pass having turned the picture over
            const bool inside = x >= 2 && x < 6;
            CHECK(pixel_at(vulkan, x, y)[0] == Approx(inside ? 1.0 - (row + 0.5) / 4.0 : 0.0).margin(0.002));  // v from the moved corners
            CHECK(pixel_at(vulkan, x, y)[1] == Approx(inside ? (x + 0.5) / 8.0 : 0.0).margin(0.002));          // gl_FragCoord: the framebuffer's
            CHECK(pixel_at(vulkan, x, y)[2] == Approx(inside ? (row + 0.5) / 4.0 : 0.0).margin(0.002));
        }
    // Every other target draws the import's triangle (the pixels past the quad dropped) or, in
    // Godot, a node's quad moved to the corners.
    for (TargetId target : {TargetId::Glsl450, TargetId::Glsl330, TargetId::GlslEs300, TargetId::WebGl2, TargetId::Hlsl50, TargetId::Hlsl60,
                            TargetId::Wgsl, TargetId::Godot4, TargetId::Godot3}) {
        INFO(target_info(target).name);
        const Image image = render_imported_or_fail(renderer, *lib, preset, target, input, 8, 4, {1}).front();
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x)
                for (int c = 0; c < 3; ++c) {
                    INFO("pixel " << x << "," << y << " channel " << c);
                    CHECK(pixel_at(image, x, y)[c] == Approx(pixel_at(vulkan, x, y)[c]).margin(0.003));  // Godot's screen: 8 bits
                }
    }
}

TEST_CASE("SourceSize is whole pixels in both Godots' stages: yo6's round((233 - SourceSize.y) / 2) is RetroArch's -4",
          "[retroarch][import][godot]") {
    // Godot gives a node's texture size as TEXTURE_PIXEL_SIZE: 1 / (1 / 240) in 32 bits is not
    // 240, and crt-yo6's vertex stage, rounding half its height difference, moved the picture a row.
    test::TempDir dir;
    const std::shared_ptr<TemplateLibrary> lib =
        one_pass_or_fail(dir, "size",
                         {"", "", "layout(location = 1) {io} float vRow;\n", "vRow = round((233.0 - params.SourceSize.y) / 2.0);\n",
                          "void main() {\n"
                          "    float whole = params.SourceSize.x == 320.0 && params.SourceSize.y == 240.0 ? 1.0 : 0.0;\n"
                          "    FragColor = vec4(-vRow / 8.0, whole, round((233.0 - params.SourceSize.y) / 2.0) / -8.0, 1.0);\n"
                          "}\n"});
    render_on_each(*lib, "size", {TargetId::Spirv, TargetId::Godot4, TargetId::Godot3}, {320, 240}, {8, 6}, [](TargetId, const Image& image) {
        for (size_t i = 0; i < image.rgba.size(); i += 4) {
            INFO("pixel " << i / 4);
            CHECK(image.rgba[i] == Approx(0.5).margin(0.002));      // the vertex stage's -4
            CHECK(image.rgba[i + 1] == Approx(1.0).margin(0.002));  // 320 x 240 exactly
            CHECK(image.rgba[i + 2] == Approx(0.5).margin(0.002));  // the fragment stage's -4
        }
    });
}

TEST_CASE("gl_FragCoord counts rows from the top on GL ES and WebGL 2 in a pass that reads nothing else",
          "[retroarch][import][glsl]") {
    // ES has no origin_upper_left: its GLSL counts rows by outputSize, which a pass reading only
    // gl_FragCoord (no params, no sizes) once lacked: upside down on ES, refused on WebGL 2.
    test::TempDir dir;
    const std::shared_ptr<TemplateLibrary> lib =
        one_pass_or_fail(dir, "rows", {"", "", "", "", "void main() { FragColor = vec4(gl_FragCoord.x / 8.0, gl_FragCoord.y / 4.0, 0.0, 1.0); }\n"});
    check_pixels_8x4(*lib, "rows", {TargetId::Spirv, TargetId::Glsl330, TargetId::GlslEs300, TargetId::WebGl2},
                     [](int x, int y) { return std::array<double, 3>{(x + 0.5) / 8.0, (y + 0.5) / 4.0, 0.0}; });
}

TEST_CASE("a moved quad's corner takes the location after the widest of the stage's varyings: a matrix, an array, a struct",
          "[retroarch][import]") {
    // Locations 1-3 (a mat3), 4-5 (a vec2[2]) and 6-8 (a struct of a vec4 and a mat2): the corner
    // goes at 9. Had it gone after the highest location written (7), it would overlap the struct.
    const std::string head = "struct Pair { vec4 a; mat2 b; };\n";
    const std::string varyings = "layout(location = 1) {io} mat3 M;\nlayout(location = 4) {io} vec2 W[2];\nlayout(location = 6) {io} Pair P;\n";
    const std::string vertex = "gl_Position = global.MVP * vec4(Position.x * 0.5 + 0.25, Position.y, 0.0, 1.0);\n"
                               "M = mat3(0.25); W[0] = vec2(0.0); W[1] = vec2(0.0, 0.5); P.a = vec4(0.0); P.b = mat2(0.75);\n";
    const std::string fragment = "void main() { FragColor = vec4(M[2][2], W[1].y, P.b[1][1], 1.0); }\n";
    test::TempDir dir;
    const std::shared_ptr<TemplateLibrary> lib = one_pass_or_fail(dir, "wide", {"", head, varyings, vertex, fragment});
    check_pixels_8x4(*lib, "wide", {TargetId::Spirv, TargetId::Glsl330, TargetId::Hlsl50, TargetId::Wgsl}, [](int x, int) {
        const bool inside = x >= 2 && x < 6;
        return inside ? std::array<double, 3>{0.25, 0.5, 0.75} : std::array<double, 3>{0.0, 0.0, 0.0};
    });
}
