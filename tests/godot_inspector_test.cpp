// The Godot inspector check (issue 29): validate reads each runtime param back from the exported
// shader and material and holds it to the spec and the preset. The exported files agree; each
// kind of slip a writer could make to them (the blind spots the issue lists) is named.
#include <catch2/catch.hpp>

#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/validate/godot_inspector.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

struct Exported {
    std::vector<CompiledVariant> passes;
    std::vector<TargetOutput> outputs;
};

Exported export_godot(const std::string& preset_name, TargetId target) {
    const TemplateLibrary& lib = test::shipped_library();
    const Preset* preset = lib.find_preset(preset_name);
    REQUIRE(preset);
    auto passes = compile_scene(lib, *preset, VariantOptions{}, Cache());
    REQUIRE(passes.ok());
    auto outputs = emit_scene(passes.value(), target, Cache());
    REQUIRE(outputs.ok());
    return {std::move(passes.value()), std::move(outputs.value())};
}

// The pass's files with `find` replaced by `replace` in the file of `role` (found exactly once).
TargetOutput edited(TargetOutput out, const std::string& role, const std::string& find, const std::string& replace) {
    for (OutputFile& f : out.files) {
        if (f.manifest_role() != role) continue;
        const size_t at = f.data.find(find);
        INFO(role << ": " << find);
        REQUIRE(at != std::string::npos);
        REQUIRE(f.data.find(find, at + 1) == std::string::npos);
        f.data.replace(at, find.size(), replace);
        return out;
    }
    FAIL("no file of role " << role);
    return out;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

}  // namespace

TEST_CASE("exported Godot shaders and materials show every runtime param as the spec and preset say", "[godot][inspector]") {
    for (TargetId target : {TargetId::Godot4, TargetId::Godot3})
        for (const Preset& preset : test::shipped_library().presets()) {
            if (preset.test_only) continue;
            INFO(preset.name << " on Godot " << (target == TargetId::Godot4 ? 4 : 3));
            const Exported e = export_godot(preset.name, target);
            for (size_t i = 0; i < e.outputs.size(); ++i)
                CHECK(joined(godot_inspector_problems(e.passes[i].variant, e.outputs[i], target == TargetId::Godot4 ? 4 : 3)).empty());
        }
}

TEST_CASE("the inspector check names each kind of slip in a Godot shader or material", "[godot][inspector]") {
    struct Slip {
        const char* what;
        const char* preset;
        TargetId target;
        const char* role;
        const char* find;
        const char* replace;
        const char* says;
    } slips[] = {
        {"range swapped", "classic", TargetId::Godot4, "shader", "hint_range(0.0, 0.5, 0.01)", "hint_range(0.5, 0.0, 0.01)", "has range [0.5, 0]"},
        {"a wrong step", "classic", TargetId::Godot4, "shader", "hint_range(0.0, 0.01, 0.0005)", "hint_range(0.0, 0.01, 0.001)", "has step 0.001"},
        {"an int's max", "atari-16", TargetId::Godot4, "shader", "hint_range(4, 256, 4)", "hint_range(4, 255, 4)", "has range [4, 255]"},
        {"an int's step", "atari-16", TargetId::Godot3, "shader", "hint_range(4, 256, 4)", "hint_range(4, 256, 1)", "has step 1"},
        {"no slider", "classic", TargetId::Godot3, "shader", " : hint_range(0.0, 1.0, 0.01) = 0.5", " = 0.5", "no hint_range"},
        {"a default that is not the preset's", "classic", TargetId::Godot4, "shader", "hint_range(0.0, 1.0, 0.01) = 0.5", "hint_range(0.0, 1.0, 0.01) = 0.05", "preset's value is 0.5"},
        {"colour channels swapped (default)", "super-win", TargetId::Godot4, "shader", "vec3(1.0, 0.7, 0.45)", "vec3(0.45, 0.7, 1.0)", "preset's colour"},
        {"colour channels swapped (material)", "super-win", TargetId::Godot4, "material", "Color(1, 0.7, 0.45, 1)", "Color(0.45, 0.7, 1, 1)", "preset's colour"},
        {"colour alpha 0 (material)", "super-win", TargetId::Godot3, "material", "Color( 1, 0.7, 0.45, 1 )", "Color( 1, 0.7, 0.45, 0 )", "alpha 0"},
        {"colour alpha 0 (default)", "super-win", TargetId::Godot3, "shader", "vec4(1.0, 0.7, 0.45, 1.0)", "vec4(1.0, 0.7, 0.45, 0.0)", "alpha 0"},
        {"no colour picker", "super-win", TargetId::Godot4, "shader", "trailTint : source_color", "trailTint", "colour picker"},
        {"a material value that is not the preset's", "classic", TargetId::Godot3, "material", "shader_param/maskDim = 0.7", "shader_param/maskDim = 0.07", "preset's value is 0.7"},
        {"a param missing from the material", "classic", TargetId::Godot4, "material", "shader_parameter/maskDim = 0.7\n", "", "missing from the material"},
        {"a material entry nothing declares", "classic", TargetId::Godot4, "material", "shader_parameter/maskDim = 0.7", "shader_parameter/maskDimm = 0.7", "declares no such uniform"},
        {"the screen material's value", "classic", TargetId::Godot4, "screenMaterial", "shader_parameter/maskDim = 0.7", "shader_parameter/maskDim = 0.75", "preset's value is 0.7"},
        {"a runtime param baked", "classic", TargetId::Godot4, "shader", "uniform float maskDim : hint_range(0.0, 1.0, 0.01) = 0.7;", "const float maskDim = 0.7;", "not a uniform"},
        {"an int declared float", "atari-16", TargetId::Godot4, "shader", "uniform int paletteSize", "uniform float paletteSize", "declared float"},
    };
    for (const Slip& s : slips) {
        INFO(s.what);
        const Exported e = export_godot(s.preset, s.target);
        // The pass whose file of that role holds the text.
        size_t pass = 0;
        for (size_t i = 0; i < e.outputs.size(); ++i)
            for (const OutputFile& f : e.outputs[i].files)
                if (f.manifest_role() == s.role && f.data.find(s.find) != std::string::npos) pass = i;
        const auto problems = godot_inspector_problems(e.passes[pass].variant, edited(e.outputs[pass], s.role, s.find, s.replace),
                                                       s.target == TargetId::Godot4 ? 4 : 3);
        CHECK_THAT(joined(problems), Catch::Contains(s.says));
    }
}
