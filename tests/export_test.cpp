// The export pipeline: determinism, the cache, and the manifest's contents.
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

using namespace crtforge;
using json = nlohmann::json;

TEST_CASE("exports are byte-identical across runs, cold or warm cache", "[export][determinism]") {
    const TemplateLibrary& lib = test::shipped_library();
    test::TempDir cache_dir;
    Cache cache(cache_dir.path());
    auto first = run_export(lib, {}, Cache());
    auto cold = run_export(lib, {}, cache);
    auto warm = run_export(lib, {}, cache);
    REQUIRE(first.ok());
    REQUIRE(cold.ok());
    REQUIRE(warm.ok());
    CHECK(first.value().files == cold.value().files);
    CHECK(first.value().files == warm.value().files);
    CHECK(cache.hits() > 0);
    // Per pass: 6 targets x 2 shaders, 2 Godot targets x (2 shaders + material) and one WGSL module;
    // per preset: its LUTs, and per Godot target its scene and a copy of the LUTs; one README and
    // one pipeline script per Godot addon, the manifest.
    size_t expected = 2 + 2 + 1;
    for (const Preset& p : lib.presets()) expected += p.passes.size() * (6 * 2 + 2 * 3 + 1) + p.luts.size() + 2 * (1 + p.luts.size());
    CHECK(first.value().files.size() == expected);
}

TEST_CASE("written files match the in-memory export", "[export]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto result = run_export(lib, {}, Cache());
    REQUIRE(result.ok());
    test::TempDir out;
    REQUIRE(write_files(out.path(), result.value().files).ok());
    for (const auto& [path, data] : result.value().files) {
        std::ifstream in(out / path, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        CHECK(ss.str() == data);
    }
}

TEST_CASE("the cache treats damaged entries as misses", "[export][cache]") {
    test::TempDir dir;
    Cache cache(dir.path());
    const std::string key = Cache::key({"a", "b"});
    CHECK(key != Cache::key({"ab", ""}));
    CHECK(key.size() == 32);
    CHECK_FALSE(cache.get("kind", key).has_value());
    cache.put("kind", key, "payload");
    CHECK(cache.get("kind", key) == std::optional<std::string>("payload"));
    // Truncate the entry: it must not come back.
    std::ofstream(dir / ("kind/" + key), std::ios::trunc) << "pay";
    CHECK_FALSE(cache.get("kind", key).has_value());
}

TEST_CASE("the manifest lists files, uniform layout and baked values", "[export][manifest]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto result = run_export(lib, {}, Cache());
    REQUIRE(result.ok());
    const auto& files = result.value().files;
    json m = json::parse(files.at("manifest.json"));
    REQUIRE(m["presets"].size() == lib.presets().size());
    for (const auto& [name, preset] : m["presets"].items()) {
        REQUIRE(preset["passes"].size() == lib.find_preset(name)->passes.size());
        for (const TargetInfo& t : all_targets()) {
            INFO(name << " " << t.name);
            const json& entry = preset["passes"][0]["targets"][t.name];
            std::vector<std::string> roles = t.shader_roles;
            if (t.id == TargetId::Godot4 || t.id == TargetId::Godot3) roles.insert(roles.end(), {"material", "readme"});
            for (const std::string& role : roles) {
                REQUIRE(entry.contains(role));
                CHECK(files.count(entry[role].get<std::string>()) == 1);
            }
        }
    }
    CHECK(m["manifestVersion"] == 2);
    const json& shadow_preset = m["presets"]["crt-shadow-mask"];
    CHECK(shadow_preset["scene"]["fps"] == 60.0);
    CHECK(shadow_preset["scene"]["display"]["fit"] == "stretch");
    const json& shadow = shadow_preset["passes"][0];
    CHECK(shadow["alias"] == "main");
    CHECK(shadow["format"] == "rgba8");
    CHECK(shadow["scale"]["x"]["type"] == "viewport");
    CHECK(shadow["textures"][0]["from"] == "original");
    CHECK(shadow["textures"][0]["wrap"] == "clamp_to_edge");
    CHECK(shadow["baked"]["maskBorder"] == 0.8);
    CHECK(shadow["baked"]["maskMode"] == "shadow");
    CHECK(shadow["baked"]["maskQuantize"] == true);
    const json& block = shadow["uniformBlock"];
    CHECK(block["set"] == 0);
    CHECK(block["binding"] == 0);
    // std140: vec2 at 0, float at 8, vec3 aligned to 16, then floats packed after it.
    std::vector<std::tuple<std::string, std::string, int, int>> layout;
    for (const auto& member : block["members"])
        layout.emplace_back(member["name"], member["type"], member["offset"], member["size"]);
    CHECK(layout == std::vector<std::tuple<std::string, std::string, int, int>>{
                        {"outputSize", "vec2", 0, 8}, {"curvature", "float", 8, 4}, {"bezelColor", "vec3", 16, 12},
                        {"scanlineIntensity", "float", 28, 4}, {"maskSize", "float", 32, 4},
                        {"maskIntensity", "float", 36, 4}, {"vignetteExponent", "float", 40, 4}});
    CHECK(block["size"] == 44);
    CHECK(block["allocationSize"] == 48);
    const json& mask_size = block["members"][4];
    CHECK(mask_size["range"] == json::array({2.0, 24.0}));
    CHECK(mask_size["default"] == 8.0);
    CHECK(mask_size["unit"] == "px");
    CHECK(mask_size["stage"] == "mask");
    CHECK(shadow["textures"][0]["binding"] == 1);
    CHECK(m["presets"]["passthrough"]["passes"][0]["uniformBlock"].is_null());
    CHECK(shadow["targets"]["hlsl50"]["bindings"]["CrtParams"] == "cbuffer register(b0)");
}

TEST_CASE("export rejects unknown presets without producing files", "[export][errors]") {
    ExportRequest request;
    request.presets = {"classic", "nope"};
    auto result = run_export(test::shipped_library(), request, Cache());
    REQUIRE_FALSE(result.ok());
    CHECK(result.error().field == "--preset");
    CHECK_THAT(result.error().message, Catch::Contains("nope"));
}
