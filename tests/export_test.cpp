// The export pipeline: determinism, the cache, and the manifest's contents.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
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
    // Per pass: 7 targets x 2 shaders, 2 Godot targets x (2 shaders + material) and one WGSL module
    // (and its copy in the npm package); per preset: its LUTs, per Godot target its scene and a
    // copy of the LUTs, a copy in the npm package, and for a single-pass preset the screen material
    // and the overlay scene; per Godot addon a README, the pipeline script and the editor plugin
    // (plugin.cfg, its script, the overlay node's script); the manifest; and the npm package's
    // package.json, manifest, index.mjs, index.d.ts, crt-webgpu.mjs, README, the three.js, PixiJS
    // and Babylon.js adapters (.mjs and .d.ts each) and the framework-pass.mjs they share.
    size_t expected = 2 * 5 + 1 + 13;
    for (const Preset& p : lib.presets())
        expected += p.passes.size() * (7 * 2 + 2 * 3 + 1 + 1) + p.luts.size() + 2 * (1 + p.luts.size()) + p.luts.size() +
                    (p.single_pass() ? 2 * 2 : 0);
    CHECK(first.value().files.size() == expected);
}

TEST_CASE("written files match the in-memory export", "[export]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto result = run_export(lib, {}, Cache());
    REQUIRE(result.ok());
    test::TempDir out;
    REQUIRE(write_files(out.path(), result.value().files).ok());
    for (const auto& [path, data] : result.value().files) CHECK(test::slurp(out / path) == data);
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

TEST_CASE("an export replaces its directory all at once, under a lock, and cleans up after a killed run", "[export][atomic]") {
    namespace fs = std::filesystem;
    test::TempDir tmp;
    const std::string out = tmp / "out";
    auto files_in = [](const std::string& dir) {
        std::set<std::string> names;
        for (const auto& e : fs::recursive_directory_iterator(dir))
            if (e.is_regular_file()) names.insert(fs::relative(e.path(), dir).string());
        return names;
    };
    auto run = [&](const std::string& args) { return test::run_crtforge("export --quiet --out '" + out + "' " + args); };

    REQUIRE(run("--preset classic --preset crt-pulse").exit_code == 0);
    const auto two = files_in(out);
    CHECK(two.count("manifest.json") == 1);
    // A re-export of fewer presets leaves no stale file behind.
    REQUIRE(run("--preset classic").exit_code == 0);
    const auto one = files_in(out);
    CHECK(one.size() < two.size());
    for (const std::string& f : one) CHECK(f.find("crt-pulse") == std::string::npos);
    // Nothing beside --out is left over, the lock file included.
    for (const auto& e : fs::directory_iterator(tmp.path())) CHECK(e.path().filename() == "out");

    // While another export holds the lock, a second one fails clearly and writes nothing.
    {
        const int fd = ::open((tmp / ".out.crtforge-lock").c_str(), O_CREAT | O_RDWR, 0644);
        REQUIRE(fd >= 0);
        REQUIRE(::flock(fd, LOCK_EX) == 0);
        const auto busy = run("--preset crt-pulse");
        ::close(fd);
        CHECK(busy.exit_code == 2);
        CHECK_THAT(busy.err, Catch::Contains("another crtforge export is writing this directory"));
        CHECK(files_in(out) == one);
    }

    // A run killed between moving the old export aside and moving the new one in: the next run
    // puts the old one back before deciding, and removes the half-written staging.
    fs::rename(out, tmp / ".out.crtforge-old");
    fs::create_directories(tmp / ".out.crtforge-staging/glsl330");
    std::ofstream(tmp / ".out.crtforge-staging/glsl330/half.frag") << "half";
    REQUIRE(run("--preset classic").exit_code == 0);
    CHECK(files_in(out) == one);
    CHECK_FALSE(fs::exists(tmp / ".out.crtforge-old"));
    CHECK_FALSE(fs::exists(tmp / ".out.crtforge-staging"));

    // A folder of someone else's files is not replaced.
    const std::string mine = tmp / "mine";
    fs::create_directories(mine);
    std::ofstream(mine + "/notes.txt") << "mine";
    const auto refused = test::run_crtforge("export --quiet --preset classic --out '" + mine + "'");
    CHECK(refused.exit_code == 2);
    CHECK_THAT(refused.err, Catch::Contains("is not a crtforge export"));
    CHECK(files_in(mine) == std::set<std::string>{"notes.txt"});
    // Nor is one that merely holds a file named manifest.json (a web extension's, say)...
    std::ofstream(mine + "/manifest.json") << "{\"name\": \"extension\"}";
    const auto extension = test::run_crtforge("export --quiet --preset classic --out '" + mine + "'");
    CHECK(extension.exit_code == 2);
    CHECK_THAT(extension.err, Catch::Contains("it has no .crtforge-export index"));
    CHECK(files_in(mine) == std::set<std::string>{"manifest.json", "notes.txt"});
    // ...nor an earlier export the user has added a file to: it names the file.
    std::ofstream(out + "/glsl330/my-notes.txt") << "mine";
    const auto added = run("--preset classic");
    CHECK(added.exit_code == 2);
    CHECK_THAT(added.err, Catch::Contains("holds 'glsl330/my-notes.txt', which no crtforge export wrote"));
    CHECK(fs::exists(out + "/glsl330/my-notes.txt"));
}
