// The manifest-only host (issue 29): validate's Vulkan renders bind and fill every pass from the
// preset's manifest.json entry, so the manifest must carry everything reflection knows.
#include <catch2/catch.hpp>

#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/validate/manifest_host.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

TEST_CASE("a manifest-only host knows every pass's uniform block and textures as reflection does", "[manifest]") {
    const TemplateLibrary& lib = test::shipped_library();
    for (const Preset& preset : lib.presets()) {
        INFO(preset.name);
        auto passes = compile_scene(lib, preset, VariantOptions{}, Cache());
        REQUIRE(passes.ok());
        auto hosted = as_manifest_host(preset, passes.value());
        REQUIRE(hosted.ok());
        for (size_t i = 0; i < passes.value().size(); ++i) {
            const Reflection& want = passes.value()[i].reflection;
            const Reflection& got = hosted.value()[i].reflection;
            REQUIRE(got.uniform_blocks.size() == want.uniform_blocks.size());
            for (size_t b = 0; b < want.uniform_blocks.size(); ++b) {
                const ReflectedBlock &w = want.uniform_blocks[b], &g = got.uniform_blocks[b];
                CHECK((g.name == w.name && g.set == w.set && g.binding == w.binding && g.size == w.size));
                REQUIRE(g.members.size() == w.members.size());
                for (size_t m = 0; m < w.members.size(); ++m) {
                    INFO(w.members[m].name);
                    CHECK((g.members[m].name == w.members[m].name && g.members[m].type == w.members[m].type &&
                           g.members[m].offset == w.members[m].offset && g.members[m].size == w.members[m].size &&
                           g.members[m].scalar == w.members[m].scalar && g.members[m].components == w.members[m].components &&
                           g.members[m].columns == w.members[m].columns));
                }
            }
            REQUIRE(got.textures.size() == want.textures.size());
            for (size_t t = 0; t < want.textures.size(); ++t)
                CHECK((got.textures[t].name == want.textures[t].name && got.textures[t].set == want.textures[t].set &&
                       got.textures[t].binding == want.textures[t].binding));
        }
    }
}
