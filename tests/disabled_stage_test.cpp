// A stage that is off is absent from the output: no code, no uniform. Checked on the reflected
// SPIR-V, with positive controls so the checks could fail.
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

bool has_name_containing(const Reflection& r, const std::string& needle) {
    for (const auto& n : r.names)
        if (n.find(needle) != std::string::npos) return true;
    return false;
}

std::vector<std::string> member_names(const Reflection& r) {
    std::vector<std::string> out;
    for (const auto& b : r.uniform_blocks)
        for (const auto& m : b.members) out.push_back(m.name);
    return out;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

// The variant compiled without optimisation keeps every function's name, so the absence of a
// stage's functions is visible.
Reflection unoptimized_reflection(const TemplateLibrary& lib, const Preset& preset, const VariantOptions& options, size_t pass) {
    auto variant = make_variant(lib, preset, options, pass);
    REQUIRE(variant.ok());
    CompileOptions co;
    co.optimize = false;
    auto spirv = compile_to_spirv(assemble(lib, variant.value()).fragment, co);
    REQUIRE(spirv.ok());
    return reflect(spirv.value()).value();
}

}  // namespace

TEST_CASE("disabled stages leave no code and no uniform in any preset", "[disabled]") {
    const TemplateLibrary& lib = test::shipped_library();
    VariantOptions all;
    all.uniforms.mode = UniformSelection::Mode::All;  // the strictest case: every runtime param a uniform
    for (const Preset& preset : lib.presets())
      for (size_t pass = 0; pass < preset.passes.size(); ++pass) {
        const Reflection raw = unoptimized_reflection(lib, preset, all, pass);
        auto compiled = compile_variant(lib, preset, all, Cache(), pass);
        REQUIRE(compiled.ok());
        const auto members = member_names(compiled.value().reflection);
        for (const StageSpec& stage : lib.stages()) {
            INFO(preset.name << " pass " << preset.passes[pass].alias << " / " << stage.name);
            const ResolvedStage* on = preset.passes[pass].find_stage(stage.name);
            for (const FormSpec& form : stage.forms) {
                for (const std::string& fn : form.functions) {
                    if (fn.empty()) continue;
                    // Expected exactly when the active form uses this function (forms may share one).
                    const bool expected =
                        on && std::find(std::begin(on->form->functions), std::end(on->form->functions), fn) !=
                                  std::end(on->form->functions);
                    CHECK(has_name_containing(raw, fn + "(") == expected);
                }
            }
            for (const ParamSpec& p : stage.params) {
                const bool expected = on && on->values.count(p.name) && p.runtime;
                CHECK(contains(members, p.name) == expected);
            }
        }
        CHECK(contains(members, "time") == (preset.passes[pass].find_stage("glow") != nullptr));
    }
}

TEST_CASE("texture reads: one per enabled tap, none left by disabled stages", "[disabled]") {
    const TemplateLibrary& lib = test::shipped_library();
    const std::pair<const char*, unsigned> expected[] = {
        {"passthrough", 1},       // plain blit
        {"crt-shadow-mask", 1},   // one (cell-quantised) sample
        {"crt-aperture-grille", 1},
        {"webgpu-post", 3},       // aberration: centre + red + blue taps
        {"classic", 3},
        {"quiet-frame", 3},       // bloom: centre + two taps
    };
    for (const auto& [name, samples] : expected) {
        INFO(name);
        CHECK(test::compile_or_fail(lib, name).reflection.texture_samples == samples);
    }
}

TEST_CASE("enabling the pulsing glow adds exactly its code and time", "[disabled]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto file = parse_preset_file("name = \"pulse\"\ndoc = \"d\"\nbase = \"crt-shadow-mask\"\n[stages.glow]\n",
                                  "pulse.toml", &lib);
    REQUIRE(file.ok());
    std::vector<PresetFile> files{file.value()};
    const std::string base_path = test::shipped_template_dir() + "/presets/crt-shadow-mask.toml";
    auto base = parse_preset_file(test::slurp(base_path), base_path, &lib);
    REQUIRE(base.ok());
    files.push_back(base.value());
    auto preset = lib.resolve(files, "pulse");
    REQUIRE(preset.ok());
    auto compiled = compile_variant(lib, preset.value(), {}, Cache());
    REQUIRE(compiled.ok());
    const auto members = member_names(compiled.value().reflection);
    CHECK(contains(members, "time"));
    CHECK(contains(members, "pulseIntensity"));
    CHECK(contains(members, "pulseSpeed"));
    CHECK_FALSE(contains(members, "pulseWidth"));  // not runtime: baked
}
