// Variants: which params are baked and which stay uniforms.
#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

std::vector<std::string> uniform_names(const Variant& v) {
    std::vector<std::string> out;
    for (const auto* p : v.uniforms()) out.push_back(p->spec->name);
    return out;
}

Variant variant_or_fail(const std::string& preset, const std::string& uniforms) {
    const TemplateLibrary& lib = test::shipped_library();
    auto sel = UniformSelection::parse(uniforms);
    REQUIRE(sel.ok());
    VariantOptions options;
    options.uniforms = sel.value();
    auto v = make_variant(lib, *lib.find_preset(preset), options);
    if (!v.ok()) FAIL(v.error().str());
    return v.value();
}

}  // namespace

TEST_CASE("default: runtime-tunable params stay uniforms, the rest is baked", "[variant]") {
    Variant v = variant_or_fail("crt-shadow-mask", "default");
    CHECK(uniform_names(v) == std::vector<std::string>{"curvature", "bezelColor", "scanlineIntensity", "maskSize",
                                                       "maskIntensity", "vignetteExponent"});
    std::vector<std::string> baked;
    for (const auto* p : v.baked()) baked.push_back(p->spec->name);
    CHECK(baked == std::vector<std::string>{"curvatureForm", "bezelAlpha", "scanlineForm", "scanlineSharpness", "scanlineSpacing",
                                            "scanlineBrightBoost", "maskMode", "maskBorder", "maskQuantize", "vignetteForm"});
    CHECK(v.builtins == std::vector<Builtin>{Builtin::OutputSize});
}

TEST_CASE("none bakes everything, and all equals every runtime-capable param", "[variant]") {
    CHECK(uniform_names(variant_or_fail("quiet-frame", "none")).empty());
    CHECK(variant_or_fail("quiet-frame", "none").has_uniform_block());  // outputSize still needed
    CHECK(uniform_names(variant_or_fail("quiet-frame", "all")) ==
          std::vector<std::string>{"curvature", "bezelColor", "bloomStrength", "scanlineIntensity", "maskDim", "vignetteScale"});
}

TEST_CASE("a named list keeps exactly those params as uniforms", "[variant]") {
    Variant v = variant_or_fail("classic", "scanlineIntensity,curvature");
    CHECK(uniform_names(v) == std::vector<std::string>{"curvature", "scanlineIntensity"});
    CHECK(v.builtins == std::vector<Builtin>{Builtin::OutputSize, Builtin::SourceSize});
}

TEST_CASE("passthrough has no uniform block at all", "[variant]") {
    Variant v = variant_or_fail("passthrough", "all");
    CHECK_FALSE(v.has_uniform_block());
    CHECK(v.params.empty());
}

TEST_CASE("bad --uniforms lists are rejected with the reason", "[variant][errors]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto try_names = [&](const std::string& preset, const std::string& names) {
        VariantOptions options;
        options.uniforms = UniformSelection::parse(names).value();
        return make_variant(lib, *lib.find_preset(preset), options);
    };
    auto unknown = try_names("classic", "scanlineIntensty");
    REQUIRE_FALSE(unknown.ok());
    CHECK(unknown.error().field == "--uniforms");
    CHECK_THAT(unknown.error().message, Catch::Contains("not a param"));

    auto fixed = try_names("classic", "maskBlend");
    REQUIRE_FALSE(fixed.ok());
    CHECK_THAT(fixed.error().message, Catch::Contains("runtime = false"));
    CHECK_THAT(fixed.error().message, Catch::Contains("mask.toml:"));

    auto unused = try_names("classic", "maskSize");
    REQUIRE_FALSE(unused.ok());
    CHECK_THAT(unused.error().message, Catch::Contains("not used by preset 'classic'"));

    CHECK_FALSE(UniformSelection::parse("a,,b").ok());
}
