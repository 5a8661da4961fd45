// Issue 13's hostile and careless inputs: a cache that cannot lie, bounded inputs, exceptions that
// stay Diagnostics. Each case here failed on main before its fix.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/files.hpp"
#include "crtforge/inert_text.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/variant.hpp"
#include "generator/macro_budget.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

using test::slurp;

// A command that must be refused as bad usage, naming the argument at fault.
void check_refused(const std::string& args, const std::string& field) {
    INFO(args);
    auto run = test::run_crtforge(args);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains(field));
}

void overwrite(const fs::path& path, const std::string& data) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
}

// Every file below dir, keyed by its path relative to dir.
std::map<std::string, std::string> tree(const std::string& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = slurp(e.path());
    return out;
}

std::vector<fs::path> cache_entries(const std::string& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("a cache entry edited in place is a miss, and the next put heals it", "[hostile][cache]") {
    test::TempDir dir;
    Cache cache(dir.path());
    const std::string key = Cache::key({"edited"});
    cache.put("kind", key, "const float k = 1.25;");
    const fs::path entry = dir / ("kind/" + key);
    std::string data = slurp(entry);
    const size_t at = data.find("1.25");
    REQUIRE(at != std::string::npos);
    data.replace(at, 4, "9.75");  // same length: only the checksum can tell
    overwrite(entry, data);
    CHECK_FALSE(cache.get("kind", key).has_value());
    CHECK(cache.rejected() == 1);
    cache.put("kind", key, "const float k = 1.25;");
    CHECK(cache.get("kind", key) == std::optional<std::string>("const float k = 1.25;"));
    // Another key's entry copied over this one is not this key's answer.
    const std::string other = Cache::key({"other"});
    cache.put("kind", other, "other payload");
    fs::copy_file(dir / ("kind/" + other), entry, fs::copy_options::overwrite_existing);
    CHECK_FALSE(cache.get("kind", key).has_value());
}

TEST_CASE("flipped bits in cached SPIR-V and target entries never reach an export", "[hostile][cache]") {
    // Fresh processes, so only the on-disk cache can answer (no in-process memo).
    test::TempDir cache, expected_dir;
    const std::string args = " export --preset classic,crt-pulse --target spirv,glsl330,hlsl50,wgsl,godot4 -q --out ";
    auto uncached = test::run_crtforge("--no-cache" + args + expected_dir.path());
    REQUIRE(uncached.exit_code == 0);
    const auto expected = tree(expected_dir.path());
    REQUIRE(test::run_crtforge("--cache-dir " + cache.path() + args + (expected_dir / "warm")).exit_code == 0);
    const std::vector<fs::path> entries = cache_entries(cache.path());
    REQUIRE(entries.size() >= 10);
    // A bit in the header, in the checksum and in the payload of several entries, SPIR-V ones included.
    uint32_t seed = 12345;
    for (int trial = 0; trial < 12; ++trial) {
        const fs::path& entry = entries[static_cast<size_t>(trial) * 7 % entries.size()];
        std::string data = slurp(entry);
        REQUIRE(!data.empty());
        seed = seed * 1664525u + 1013904223u;
        const size_t at = trial % 3 == 0 ? 3 : trial % 3 == 1 ? 60 % data.size() : data.size() / 2 + seed % (data.size() / 2);
        data[at] = static_cast<char>(data[at] ^ (1 << (seed >> 29)));
        overwrite(entry, data);
        test::TempDir out;
        auto run = test::run_crtforge("--cache-dir " + cache.path() + args + out.path());
        INFO("trial " << trial << ": bit flipped at byte " << at << " of " << entry.string() << "\n" << run.err);
        REQUIRE(run.exit_code == 0);
        CHECK(tree(out.path()) == expected);
        // Healed: the entry holds the right answer again.
        auto again = test::run_crtforge("--cache-dir " + cache.path() + args + (out / "again"));
        CHECK(again.exit_code == 0);
        CHECK(tree(out / "again") == expected);
    }
}

TEST_CASE("the target cache key covers every param field that reaches the output", "[hostile][cache]") {
    test::ScratchTemplates scratch;
    test::TempDir cache_dir;
    Cache cache(cache_dir.path());
    ExportRequest request;
    request.presets = {"classic"};
    request.targets = {TargetId::Godot4, TargetId::Godot3, TargetId::Wgsl};
    auto before_lib = scratch.load();
    REQUIRE(before_lib.ok());
    REQUIRE(run_export(*before_lib.value(), request, cache).ok());
    const std::string spec = scratch.read("stages/scanlines.toml");
    // Each edit changes no GLSL: only the range, step, unit or doc of a runtime param.
    const std::vector<std::pair<std::string, std::string>> edits = {
        {"range = [0.0, 1.0]\nstep = 0.01\ndefault = 0.3\ndoc = \"Darkness", "range = [0.0, 0.9]\nstep = 0.01\ndefault = 0.3\ndoc = \"Darkness"},
        {"step = 0.01\ndefault = 0.3\ndoc = \"Darkness", "step = 0.05\ndefault = 0.3\ndoc = \"Darkness"},
        {"doc = \"Darkness of the scanlines (0 = none)\"", "doc = \"Darkness of the scanlines (0 = none), edited\""},
        {"doc = \"Darkness of the scanlines (0 = none)\"", "doc = \"Darkness of the scanlines (0 = none)\"\nunit = \"fraction\""},
    };
    for (const auto& [from, to] : edits) {
        INFO(to);
        std::string edited = spec;
        const size_t at = edited.find(from);
        REQUIRE(at != std::string::npos);
        edited.replace(at, from.size(), to);
        scratch.write("stages/scanlines.toml", edited);
        auto lib = scratch.load();
        REQUIRE(lib.ok());
        auto warm = run_export(*lib.value(), request, cache);
        auto fresh = run_export(*lib.value(), request, Cache());
        REQUIRE(warm.ok());
        REQUIRE(fresh.ok());
        CHECK(warm.value().files == fresh.value().files);
        scratch.write("stages/scanlines.toml", spec);
    }
}

TEST_CASE("a TOML key of thousands of dotted segments is an error at its line, not a stack overflow", "[hostile][toml]") {
    std::string segments = "a";
    for (int i = 0; i < 40000; ++i) segments += ".a";
    for (const std::string& text : {"name = \"deep\"\n[" + segments + "]\nx = 1\n", "name = \"deep\"\nx = { " + segments + " = 1 }\n",
                                    "name = \"deep\"\n" + segments + " = 1\n"}) {
        auto preset = parse_preset_file(text, "deep.toml", &test::shipped_library());
        REQUIRE_FALSE(preset.ok());
        CHECK(preset.error().line == 2);
        CHECK_THAT(preset.error().message, Catch::Contains("dotted segments"));
        auto spec = parse_stage_spec(text, "deep.toml");
        REQUIRE_FALSE(spec.ok());
        CHECK(spec.error().line == 2);
    }
    // Dots inside strings, comments and numbers are not key segments.
    std::string fine = "name = \"fine\"  # " + segments + "\ndoc = \"" + segments + "\"\n";
    auto ok = parse_preset_file(fine, "fine.toml", &test::shipped_library());
    CHECK(ok.ok());
}

TEST_CASE("a write that fails part-way (file size limit) is an error and leaves no file", "[hostile][io]") {
    test::TempDir dir;
    // RLIMIT_FSIZE of 20 KiB: the kernel refuses the write past it, like a full disk.
    const std::string limit = "trap '' XFSZ; ulimit -f 20; ";
    auto png = test::run_command(limit + "'" CRTFORGE_BINARY "' render --preset classic --input pixel_art --size 640x480 --output " +
                                 (dir / "out.png"));
    CHECK(png.exit_code == 2);
    CHECK_THAT(png.err, Catch::Contains("write failed"));
    CHECK_FALSE(fs::exists(dir / "out.png"));
    auto exr = test::run_command(limit + "'" CRTFORGE_BINARY "' render --preset classic --input pixel_art --size 640x480 --output " +
                                 (dir / "out.exr"));
    CHECK(exr.exit_code == 2);
    CHECK_FALSE(fs::exists(dir / "out.exr"));
    // An export whose manifest cannot be written: nothing at --out.
    auto exported = test::run_command("trap '' XFSZ; ulimit -f 2; '" CRTFORGE_BINARY "' --no-cache export --preset super-win --out " +
                                      (dir / "export"));
    CHECK(exported.exit_code == 2);
    CHECK_FALSE(fs::exists(dir / "export"));
    size_t leftovers = 0;
    for (const auto& e : fs::directory_iterator(dir.path())) leftovers += e.path().filename().string().find("tmp") != std::string::npos;
    CHECK(leftovers == 0);
}

TEST_CASE("a param renamed in the templates is a reference error, not an abort", "[hostile][reference]") {
    test::ScratchTemplates scratch;
    // Renamed everywhere in the templates (spec, snippet, presets): only the reference still knows the old name.
    for (const auto& e : fs::recursive_directory_iterator(scratch.dir())) {
        if (!e.is_regular_file()) continue;
        std::string text = slurp(e.path());
        bool renamed = false;
        for (size_t at = text.find("scanlineIntensity"); at != std::string::npos; at = text.find("scanlineIntensity", at)) {
            text.replace(at, 17, "scanDarkness");
            renamed = true;
        }
        if (renamed) overwrite(e.path(), text);
    }
    test::TempDir out;
    auto run = test::run_crtforge("--templates " + scratch.dir() + " render --reference --preset classic --input pixel_art --size 64x48 --output " +
                                  (out / "r.png"));
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains("param 'scanlineIntensity'"));
    CHECK_THAT(run.err, Catch::Contains("classic.toml"));
    CHECK_FALSE(fs::exists(out / "r.png"));
    // The same templates still export and render on Vulkan: only the reference lacks the name.
    auto vulkan = test::run_crtforge("--templates " + scratch.dir() + " render --preset classic --input pixel_art --size 64x48 --output " +
                                     (out / "v.png"));
    CHECK(vulkan.exit_code == 0);
}

TEST_CASE("sizes, frames and shards beyond 32 bits are refused, not wrapped around", "[hostile][cli]") {
    for (std::string size : {"4294967297x1", "1x4294967297", "+64x48", "64x48x", " 64x48", "64 x48", "0x0", "16385x1"})
        check_refused("render --preset classic --input pixel_art --size '" + size + "' --output /tmp/never.png", "--size");
    auto budget = test::run_crtforge("render --preset classic --input pixel_art --size 16384x16384 --output /tmp/never.png");
    CHECK(budget.exit_code == 2);
    CHECK_THAT(budget.err, Catch::Contains("render memory budget"));
    // Within the image budget but not a render's: several framebuffers of that size would pass 2 GB.
    auto render = test::run_crtforge("render --preset super-win --input pixel_art --size 4096x4096 --output /tmp/never.png");
    CHECK(render.exit_code == 2);
    CHECK_THAT(render.err, Catch::Contains("'4096x4096' is 16.8 Mpx, beyond the render memory budget of 9.4 Mpx"));
    for (std::string shard : {"4294967297/4", "1/4294967297", "0/4", "5/4", "1/0", "-1/4"})
        check_refused("validate --preset classic --target spirv --shard '" + shard + "'", "--shard");
    auto frames = test::run_crtforge("render --preset classic --input pixel_art --frames 4294967296:4294967297 --output '/tmp/never_%d.png'");
    CHECK(frames.exit_code == 2);
}

// A PNG whose header says width x height (8-bit RGB) followed by no pixel data.
static std::string header_only_png(uint32_t width, uint32_t height) {
    auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    auto crc32 = [](const std::string& bytes) {
        uint32_t crc = 0xFFFFFFFFu;
        for (unsigned char c : bytes) {
            crc ^= c;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
        return crc ^ 0xFFFFFFFFu;
    };
    std::string png("\x89PNG\r\n\x1a\n", 8);
    const std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
    png += be32(13) + ihdr + be32(crc32(ihdr));
    png += be32(0) + "IDAT" + be32(crc32("IDAT")) + be32(0) + "IEND" + be32(crc32("IEND"));
    return png;
}

// Reads `dir`/name, a header-only PNG of width x height: it must fail, with `message`.
static void check_header_only_png_fails(const test::TempDir& dir, const std::string& name, uint32_t width, uint32_t height,
                                        const std::string& message) {
    overwrite(dir / name, header_only_png(width, height));
    auto read = read_image(dir / name);
    REQUIRE_FALSE(read.ok());
    CHECK_THAT(read.error().message, Catch::Contains(message));
}

TEST_CASE("an image beyond the memory budget is refused from its header, before decoding", "[hostile][image]") {
    // 4100 x 4100 (17 Mpx, past 4096 x 4096): refused for its size, not decoded (decoding would report a truncated file).
    test::TempDir dir;
    check_header_only_png_fails(dir, "huge.png", 4100, 4100, "image memory budget");
}

TEST_CASE("a file claiming a large picture it does not hold fails before the picture's memory is taken", "[hostile][image]") {
    // 4096 x 4096 is within the budget, so the header passes; the 256 MB of floats it claims must
    // not be committed before rows really decode (the buffer grows band by band).
    test::TempDir dir;
    check_header_only_png_fails(dir, "liar.png", 4096, 4096, "cannot read pixels");
    // The same through the CLI in a child process, whose peak resident memory the kernel keeps:
    // well under the claimed picture's 256 MB plus the process itself (~160 MB).
    auto run = test::run_crtforge("render --reference --preset classic --input '" + (dir / "liar.png") +
                                  "' --output '" + (dir / "out.png") + "'");
    CHECK(run.exit_code == 2);
    CHECK_FALSE(fs::exists(dir / "out.png"));
    CHECK(run.peak_rss_kib > 0);
    CHECK(run.peak_rss_kib < 300 * 1024);
}

TEST_CASE("keywords and builtins of any target are refused as param names at the spec line", "[hostile][spec]") {
    const std::map<std::string, std::string> names = {
        {"texture", "GLSL"}, {"mix", "GLSL"}, {"lerp", "HLSL"}, {"cbuffer", "HLSL"}, {"fn", "WGSL"}, {"override", "WGSL"},
        {"TIME", "Godot"}, {"SCREEN_UV", "Godot"}, {"hint_range", "Godot"}};
    for (const auto& [name, language] : names) {
        INFO(name);
        test::ScratchTemplates scratch;
        std::string spec = scratch.read("stages/vignette.toml");
        const size_t at = spec.find("[[param]]\nname = \"");
        REQUIRE(at != std::string::npos);
        spec.insert(at, "[[param]]\nname = \"" + name + "\"\ntype = \"float\"\nrange = [0.0, 1.0]\ndefault = 0.5\ndoc = \"x\"\n\n");
        scratch.write("stages/vignette.toml", spec);
        auto lib = scratch.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().message, Catch::Contains(language));
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/vignette.toml"));
        CHECK(lib.error().line == static_cast<int>(std::count(spec.begin(), spec.begin() + static_cast<std::ptrdiff_t>(at), '\n')) + 2);
    }
}

TEST_CASE("infinite or out-of-float range bounds are refused", "[hostile][spec]") {
    for (const std::string range : {"[0.0, inf]", "[-inf, 1.0]", "[0.0, nan]", "[0.0, 1e300]"}) {
        INFO(range);
        const std::string text = "name = \"s\"\ndoc = \"d\"\norder = 99\n\n[[param]]\nname = \"sParam\"\ntype = \"float\"\nrange = " + range +
                                 "\ndefault = 0.5\ndoc = \"x\"\n\n[[form]]\nname = \"f\"\ndoc = \"d\"\ncolor = \"s_color\"\n";
        auto spec = parse_stage_spec(text, "s.toml");
        REQUIRE_FALSE(spec.ok());
        CHECK(spec.error().line == 8);
        CHECK(spec.error().field == "param.sParam.range");
    }
}

TEST_CASE("an inherited stage's texture error points at the line that enabled the stage", "[hostile][preset]") {
    auto preset = test::resolve_preset_texts(
        {{"base.toml", "name = \"base\"\ndoc = \"b\"\n\n\n[stages.color_grade]\ngradeStrength = 0.5\n"},
         {"leaf.toml", "name = \"leaf\"\ndoc = \"l\"\nbase = \"base\"\n"}},
        "leaf");
    REQUIRE_FALSE(preset.ok());
    CHECK(preset.error().file == "base.toml");
    CHECK(preset.error().line == 5);
    CHECK(preset.error().field == "stages.color_grade");
}

TEST_CASE("what the machine lacks for validate is a usage error (exit 2), not failed checks", "[hostile][cli][validate]") {
    auto device = test::run_crtforge("validate --preset classic --target spirv --device 99");
    CHECK(device.exit_code == 2);
    CHECK_THAT(device.err, Catch::Contains("--device"));
    auto named = test::run_crtforge("validate --preset classic --target spirv --device no-such-gpu");
    CHECK(named.exit_code == 2);
    auto node = test::run_crtforge("validate --preset classic --target wgsl", "PATH=/nonexistent");
    CHECK(node.exit_code == 2);
    CHECK_THAT(node.err, Catch::Contains("nodejs and npm"));
    // WGSL's compile checks run in Dawn too; a run without the WGSL target needs no Node.js.
    auto no_wgsl = test::run_crtforge("validate --preset classic --target spirv --compile-only", "PATH=/nonexistent");
    CHECK(no_wgsl.exit_code == 0);
}

TEST_CASE("repeated --preset and --target entries run once", "[hostile][cli]") {
    auto once = test::run_crtforge("validate --preset classic --target spirv,glsl330 --compile-only");
    auto twice = test::run_crtforge("validate --preset classic,classic --preset classic --target spirv,glsl330,spirv --compile-only");
    REQUIRE(once.exit_code == 0);
    REQUIRE(twice.exit_code == 0);
    auto checks = [](const std::string& out) { return out.substr(out.find("validate:"), out.find(" checks") - out.find("validate:")); };
    CHECK(checks(once.out) == checks(twice.out));
}

TEST_CASE("validate --report replaces an earlier report and refuses a folder that is not one", "[hostile][cli][validate]") {
    test::TempDir report;
    fs::create_directories(report / "images/stale.golden");
    overwrite(report / "images/stale.golden/spirv.png", "old");
    overwrite(report / "report.json", "{}");
    auto run = test::run_crtforge("validate --preset webgpu-post --target spirv --input color_bars --report " + report.path());
    REQUIRE(run.exit_code == 0);
    CHECK_FALSE(fs::exists(report / "images/stale.golden"));
    CHECK(fs::exists(report / "report.html"));
    test::TempDir other;
    overwrite(other / "notes.txt", "mine");
    auto refused = test::run_crtforge("validate --preset webgpu-post --target spirv --input color_bars --report " + other.path());
    CHECK(refused.exit_code == 2);
    CHECK_THAT(refused.err, Catch::Contains("--report"));
    CHECK(slurp(other / "notes.txt") == "mine");
}

TEST_CASE("report merge takes every shard of one run once, and nothing else", "[hostile][cli][validate]") {
    test::TempDir root;
    const std::string common = "validate --preset classic,webgpu-post --target spirv,glsl330 --input color_bars --second-device none";
    for (int i = 1; i <= 3; ++i)
        REQUIRE(test::run_crtforge(common + fmt::format(" --shard {}/3 --report {}", i, root / fmt::format("s{}", i))).exit_code == 0);
    REQUIRE(test::run_crtforge(common + " --run-id other --shard 2/3 --report " + (root / "foreign")).exit_code == 0);
    REQUIRE(test::run_crtforge(common + " --shard 1/2 --report " + (root / "half")).exit_code == 0);
    auto merge = [&](const std::string& dirs) { return test::run_crtforge("report merge --out " + (root / "m") + " " + dirs); };
    auto all = merge(root / "s1" + " " + (root / "s2") + " " + (root / "s3"));
    CHECK(all.exit_code == 0);
    // The merged report shows every shard's pictures.
    size_t pictures = 0, shard_pictures = 0;
    for (const auto& e : fs::recursive_directory_iterator(root / "m/images")) pictures += e.is_regular_file();
    for (const char* shard : {"s1", "s2", "s3"})
        for (const auto& e : fs::recursive_directory_iterator(root / (std::string(shard) + "/images")))
            shard_pictures += e.is_regular_file() && e.path().filename().string().find("golden") == std::string::npos &&
                              e.path().filename().string().find("input") == std::string::npos;
    CHECK(shard_pictures > 0);
    CHECK(pictures >= shard_pictures);
    const std::string html = slurp(root / "m/report.html");
    for (size_t at = html.find("src=\"images/"); at != std::string::npos; at = html.find("src=\"images/", at + 1)) {
        const std::string src = html.substr(at + 5, html.find('"', at + 5) - at - 5);
        CHECK(fs::exists(root / ("m/" + src)));
    }
    auto repeated = merge(root / "s1" + " " + (root / "s2") + " " + (root / "s2"));
    CHECK(repeated.exit_code == 2);
    CHECK_THAT(repeated.err, Catch::Contains("twice"));
    auto missing = merge(root / "s1" + " " + (root / "s3"));
    CHECK(missing.exit_code == 2);
    CHECK_THAT(missing.err, Catch::Contains("missing: 2/3"));
    auto foreign = merge(root / "s1" + " " + (root / "foreign") + " " + (root / "s3"));
    CHECK(foreign.exit_code == 2);
    CHECK_THAT(foreign.err, Catch::Contains("another run"));
    auto counts = merge(root / "s1" + " " + (root / "half"));
    CHECK(counts.exit_code == 2);
}

TEST_CASE("a corrupt PNG is one crtforge line, with libpng's words inside it", "[hostile][image]") {
    test::TempDir dir;
    // A valid PNG cut short in its pixel data: libpng prints its own line unless crtforge folds it in.
    Image picture = Image::make(64, 64, {0.25f, 0.5f, 0.75f, 1.0f});
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) picture.set_pixel(x, y, {x / 63.0f, y / 63.0f, ((x * 7 + y * 13) % 64) / 63.0f, 1.0f});
    REQUIRE(write_png(dir / "whole.png", picture, 8).ok());
    const std::string whole = slurp(dir / "whole.png");
    overwrite(dir / "cut.png", whole.substr(0, whole.size() / 2));
    auto run = test::run_crtforge("render --preset classic --input " + (dir / "cut.png") + " --output " + (dir / "out.png"));
    CHECK(run.exit_code == 2);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_THAT(run.err, Catch::StartsWith("crtforge: "));
    CHECK_FALSE(fs::exists(dir / "out.png"));
}

TEST_CASE("text the loaders would refuse stays inert in generated code all the same", "[hostile][inert]") {
    // Past the loader (a tool building presets in memory): every line terminator a consumer may
    // honour, and a trailing backslash, in the preset's doc and a param's doc and unit.
    const std::string hostile = std::string("doc\r\x0b\x0c") + "\xC2\x85" + "\xE2\x80\xA8" + "\xE2\x80\xA9" + "\nvec4 injected; \\";
    Preset p = *test::shipped_library().find_preset("classic");
    p.doc = hostile;
    ParamSpec spec = *test::shipped_library().find_param("scanlineIntensity");
    spec.doc = hostile;
    spec.unit = hostile;
    auto variant = make_variant(test::shipped_library(), p, {});
    REQUIRE(variant.ok());
    for (VariantParam& vp : variant.value().params)
        if (vp.spec->name == spec.name) vp.spec = &spec;
    CompiledVariant compiled = test::compile_or_fail(test::shipped_library(), "classic");
    compiled.variant = variant.value();
    const AssembledShader assembled = assemble(test::shipped_library(), compiled.variant);
    std::vector<std::string> texts = {assembled.fragment};
    for (TargetId target : {TargetId::Godot3, TargetId::Godot4, TargetId::Wgsl, TargetId::Glsl450, TargetId::Hlsl50}) {
        auto out = emit_target(compiled, target, Cache());
        REQUIRE(out.ok());
        for (const OutputFile& f : out.value().files) texts.push_back(f.data);
    }
    for (const std::string& text : texts) {
        for (const char* terminator : {"\r", "\x0b", "\x0c", "\xC2\x85", "\xE2\x80\xA8", "\xE2\x80\xA9", "\\\n"})
            CHECK(text.find(terminator) == std::string::npos);
        // The would-be code stays in the comment it came with.
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);)
            if (line.find("vec4 injected;") != std::string::npos) CHECK(line.find("//") < line.find("vec4 injected;"));
    }
}

TEST_CASE("a preset without goldens is reported as not rendered, never as a measured pass", "[hostile][validate]") {
    test::ScratchTemplates scratch;
    scratch.write("presets/newlook.toml", "name = \"newlook\"\ndoc = \"A studio look\"\nbase = \"classic\"\n\n[stages.scanlines]\nscanlineIntensity = 0.7\n");
    test::TempDir report;
    auto run = test::run_crtforge("--templates " + scratch.dir() + " validate --preset newlook --target spirv --report " + report.path());
    CHECK(run.exit_code == 0);
    CHECK_THAT(run.out, Catch::Contains("1 not rendered (no golden)"));
    // No metrics that were never measured: the summary row shows dashes, not RMSE 0 / SSIM 1.
    CHECK_THAT(run.out, Catch::Contains("        -         -         -"));
    CHECK_THAT(run.out, !Catch::Contains("0.00000"));
    const std::string json = slurp(report / "report.json");
    CHECK_THAT(json, Catch::Contains("\"status\": \"not-rendered\""));
    CHECK_THAT(slurp(report / "junit.xml"), Catch::Contains("<skipped message=\"not rendered: no golden"));
    CHECK_THAT(slurp(report / "report.html"), Catch::Contains("Not rendered: no golden"));
    auto strict = test::run_crtforge("--templates " + scratch.dir() + " validate --preset newlook --target spirv --strict");
    CHECK(strict.exit_code == 1);
    CHECK_THAT(strict.out, Catch::Contains("failed under --strict"));
}

TEST_CASE("an empty value is refused, not taken as the option or key left out", "[hostile][cli]") {
    // Options: one line naming the option, exit 2, nothing written.
    test::TempDir out;
    for (const std::string& args : std::vector<std::string>{"--templates '' list presets",
                                   "render --preset classic --input color_bars --size '' --output " + (out / "x.png"),
                                   "export --preset '' --target spirv --out " + (out / "export")}) {
        INFO(args);
        auto run = test::run_crtforge(args);
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("has an empty value"));
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    }
    CHECK(std::filesystem::is_empty(out.path()));
    // Keys: `base = ""` once meant "no base"; now the file, line and field of the empty value.
    test::ScratchTemplates t;
    t.write("presets/empty-base.toml", "format = 2\nname = \"empty-base\"\nbase = \"\"\ndoc = \"d\"\n");
    auto lib = t.load();
    REQUIRE_FALSE(lib.ok());
    CHECK_THAT(lib.error().str(), Catch::Contains("empty-base.toml:3") && Catch::Contains("field 'base'") && Catch::Contains("is empty"));
}

TEST_CASE("a cache entry that is a FIFO, a device or a huge file is a rejected entry, never read", "[hostile][cache]") {
    test::TempDir dir;
    Cache cache(dir.path());
    const std::string fifo_key = Cache::key({"fifo"}), zero_key = Cache::key({"zero"});
    fs::create_directories(dir / "kind");
    REQUIRE(::mkfifo((dir / ("kind/" + fifo_key)).c_str(), 0600) == 0);
    fs::create_symlink("/dev/zero", dir / ("kind/" + zero_key));
    CHECK_FALSE(cache.get("kind", fifo_key).has_value());
    CHECK_FALSE(cache.get("kind", zero_key).has_value());
    CHECK(cache.rejected() == 2);
    // put replaces the planted entry with a real one.
    cache.put("kind", fifo_key, "payload");
    CHECK(cache.get("kind", fifo_key) == std::optional<std::string>("payload"));
}

TEST_CASE("a snippet declares no resources of its own: a sampler outside its form's textures is refused at its line", "[hostile][spec]") {
    for (const char* declaration : {"uniform sampler2D extraLut;", "layout(binding = 9) uniform sampler2D extraLut;",
                                    "buffer Extra { float values[]; };"}) {
        INFO(declaration);
        test::ScratchTemplates t;
        t.write("stages/glow.glsl", "// glow, with a texture nobody binds\n" + std::string(declaration) + "\n" + t.read("stages/glow.glsl"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/glow.glsl"));
        CHECK(lib.error().line == 2);
        CHECK(lib.error().field == "glsl");
        CHECK_THAT(lib.error().message, Catch::Contains("declares no"));
    }
}

TEST_CASE("a snippet function whose types differ from its hook's call is an error at the function, not in generated code", "[hostile][spec]") {
    test::ScratchTemplates t;
    // The colour hook calls color = glow_pulse(color, frag): a float result cannot be assigned.
    t.write("stages/glow.glsl", "// glow\n\nfloat glow_pulse(vec3 color, CrtFrag frag) {\n    return pulseIntensity;\n}\n");
    test::TempDir tmp;
    for (const char* uniforms : {"default", "uber"}) {
        INFO(uniforms);
        auto r = test::run_crtforge("--no-cache --templates '" + t.dir() + "' export --preset crt-pulse --target glsl330 --uniforms " +
                                    uniforms + " --out '" + (tmp / "out") + "'");
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Catch::Contains("stages/glow.glsl:3:") && Catch::Contains("cannot convert"));
        CHECK_THAT(r.err, !Catch::Contains("generated"));
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
    // An error the generated code makes itself still names the generated file, at its own line:
    // the attributed call lines leave the generated numbering as it was.
    test::ScratchTemplates fine;
    auto lib = fine.load();
    REQUIRE(lib.ok());
    auto variant = make_variant(*lib.value(), *lib.value()->find_preset("crt-pulse"), VariantOptions{});
    REQUIRE(variant.ok());
    const std::string src = assemble(*lib.value(), variant.value()).fragment;
    const size_t main_at = src.find("#line 1 \"<generated main");
    REQUIRE(main_at != std::string::npos);
    int generated = 0;
    std::istringstream lines(src.substr(src.find('\n', main_at) + 1));
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("#line ", 0) == 0) {
            if (line.find("<generated main") != std::string::npos) CHECK(line.rfind("#line " + std::to_string(generated + 1) + " ", 0) == 0);
            continue;
        }
        ++generated;
    }
    CHECK(src.find("#line @resume") == std::string::npos);
}

TEST_CASE("text for junit.xml is well-formed XML 1.0 whatever a crafted shard holds", "[hostile][report]") {
    CHECK(xml_escape("a<b & \"c\"") == "a&lt;b &amp; &quot;c&quot;");
    CHECK(xml_escape("tab\tline\nok") == "tab\tline\nok");
    CHECK(xml_escape("caf\xC3\xA9 \xE2\x9C\x93 \xF0\x9F\x93\xBA") == "caf\xC3\xA9 \xE2\x9C\x93 \xF0\x9F\x93\xBA");
    const std::string replacement = "\xEF\xBF\xBD";
    // C0 controls, U+FFFE/U+FFFF, stray continuation bytes, overlong forms, surrogates, cut sequences.
    for (const std::string& bad : {std::string("\x01", 1), std::string("\0", 1), std::string("\x1b"), std::string("\xEF\xBF\xBE"),
                                  std::string("\xEF\xBF\xBF"), std::string("\x80"), std::string("\xC0\xAF"), std::string("\xED\xA0\x80"),
                                  std::string("\xF4\x90\x80\x80"), std::string("\xE2\x9C")}) {
        INFO(bad.size());
        const std::string out = xml_escape("x" + bad + "y");
        CHECK(out.front() == 'x');
        CHECK(out.back() == 'y');
        CHECK(out.find(replacement) != std::string::npos);
        for (unsigned char c : out) CHECK((c >= 0x20 || c == '\t' || c == '\n'));
    }
}

TEST_CASE("a pass graph asking for a framebuffer beyond the memory budget is refused before it is allocated", "[hostile][scene]") {
    test::TempDir dir;
    // Eight times the viewport: 16384 x 16384 at a 2048 x 2048 screen (4 GiB as RGBA float).
    REQUIRE(write_file_atomic(dir / "overlay/presets/big.toml",
                              "name = \"big\"\ndoc = \"d\"\n[[pass]]\nalias = \"up\"\nscale_type = \"viewport\"\nscale = 8.0\n"
                              "[pass.stages.scanlines]\nscanlineIntensity = 0.5\n[[pass]]\nalias = \"down\"\n")
                .ok());
    for (const char* target : {"spirv", "glsl330"}) {
        INFO(target);
        auto r = test::run_crtforge("--templates '" + (dir / "overlay") + "' render --preset big --target " + target +
                                    " --input pixel_art --size 2048x2048 --output '" + (dir / "big.png") + "'");
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Catch::Contains("presets/big.toml:3") && Catch::Contains("pass.up.scale") && Catch::Contains("16384x16384") &&
                              Catch::Contains("budget"));
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(dir / "big.png"));
    }
}

TEST_CASE("a name too long for generated code is refused at its line, not deep in glslang", "[hostile][preset]") {
    test::TempDir dir;
    const std::string alias(5000, 'a');
    REQUIRE(write_file_atomic(dir / "overlay/presets/long.toml", "name = \"long\"\ndoc = \"d\"\n[[pass]]\nalias = \"" + alias +
                                                                    "\"\n[pass.stages.scanlines]\nscanlineIntensity = 0.5\n[[pass]]\nalias = \"b\"\n")
                .ok());
    auto r = test::run_crtforge("--templates '" + (dir / "overlay") + "' export --preset long --target glsl330 --out '" + (dir / "out") + "'");
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("presets/long.toml:4") && Catch::Contains("5000 characters long"));
    CHECK(r.err.size() < 400);  // the name is not quoted whole
    CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("a huge const array in a snippet is refused at its line, not deep in spirv-opt", "[hostile][spec]") {
    std::string elements = "0.5";
    for (int i = 1; i < 5000; ++i) elements += ", 0.5";
    for (const std::string& declaration : {std::string("const float crtBig[100000] = float[100000](0.5);"), "const float crtBig[] = float[](" + elements + ");"}) {
        test::ScratchTemplates t;
        t.write("stages/glow.glsl", "// glow\n" + declaration + "\n" + t.read("stages/glow.glsl"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/glow.glsl"));
        CHECK(lib.error().line == 2);
        CHECK_THAT(lib.error().message, Catch::Contains("at most 4096"));
    }
}

TEST_CASE("a report folder is written all or nothing: a refused or failed run leaves the earlier report", "[hostile][cli][validate]") {
    test::TempDir dir;
    const std::string report = dir / "report";
    const std::string run = "validate --preset classic --target spirv --input color_bars --second-device none --report '" + report + "'";
    REQUIRE(test::run_crtforge(run).exit_code == 0);
    const std::string before = slurp(report + "/report.json");
    REQUIRE_FALSE(before.empty());
    auto no_staging_left = [&] {
        for (const auto& e : fs::directory_iterator(dir.path()))
            if (e.path().filename().string().find("staging") != std::string::npos) return false;
        return true;
    };
    // Refused after the folder was checked: an unknown preset.
    auto refused = test::run_crtforge("validate --preset no-such-preset --target spirv --second-device none --report '" + report + "'");
    CHECK(refused.exit_code == 2);
    CHECK(slurp(report + "/report.json") == before);
    CHECK(no_staging_left());
    // A write refused part-way by a file-size limit, with SIGXFSZ at its default (it would kill
    // the process): an error, the earlier report kept whole.
    auto limited = test::run_command("ulimit -f 8; '" CRTFORGE_BINARY "' " + run);
    CHECK(limited.exit_code == 2);
    CHECK_THAT(limited.err, Catch::Contains("crtforge:"));
    CHECK(slurp(report + "/report.json") == before);
    CHECK(fs::exists(report + "/images"));
    CHECK(no_staging_left());
}

TEST_CASE("a macro that expands beyond any shader (macros within macros) is refused at its line before glslang's preprocessor runs",
          "[hostile][spec][macro]") {
    // Forty macros, each using the one before twice: 2^40 tokens.
    std::string chain = "#define B0 1.0\n";
    for (int i = 1; i <= 40; ++i) chain += fmt::format("#define B{} (B{} + B{})\n", i, i - 1, i - 1);
    SECTION("the estimate: an object-like chain, nested calls of a function-like macro, #line followed, real code kept") {
        auto bomb = detail::check_macro_expansion("float x;\n" + chain + "float y = B40;\n", "a.glsl");
        REQUIRE_FALSE(bomb.ok());
        CHECK(bomb.error().file == "a.glsl");
        CHECK(bomb.error().line == 2 + 20);  // B20 is the first past 4 million
        CHECK_THAT(bomb.error().message, Catch::Contains("macro 'B20' expands to more than 4000000 tokens"));

        std::string nested = "x";
        for (int i = 0; i < 40; ++i) nested = "TWICE(" + nested + ")";
        auto calls = detail::check_macro_expansion("#define TWICE(a) a + a\n#line 10 \"shader.slang\"\nfloat y =\n  " + nested + ";\n", "main");
        REQUIRE_FALSE(calls.ok());
        CHECK(calls.error().file == "shader.slang");
        CHECK(calls.error().line == 11);  // the call's line (#line 10 names the line after it)
        CHECK_THAT(calls.error().message, Catch::Contains("the shader expands to more than"));

        // What real shaders do: function-like helpers, a macro used thousands of times, variadic ones.
        std::string fine = "#define SAT(x) clamp(x, 0.0, 1.0)\n#define LUMA(c) dot(SAT(c), vec3(0.299, 0.587, 0.114))\n"
                           "#define LOG(...) __VA_ARGS__\n#define K B6\n" + chain.substr(0, chain.find("#define B7"));
        for (int i = 0; i < 2000; ++i) fine += fmt::format("float v{} = LUMA(vec3({}.0)) + LOG(1.0, 2.0) + K;\n", i, i);
        CHECK(detail::check_macro_expansion(fine, "fine.glsl").ok());
    }
    SECTION("in a stage snippet: generate names the snippet's line") {
        test::ScratchTemplates scratch;
        scratch.write("stages/vignette.glsl", chain + scratch.read("stages/vignette.glsl"));
        test::TempDir out;
        auto run = test::run_crtforge("--templates " + scratch.dir() + " generate --preset classic --target spirv --out " + out.path() + "/g");
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("stages/vignette.glsl:21: error: macro 'B20' expands to more than"));
        CHECK_FALSE(fs::exists(out.path() + "/g"));
    }
    SECTION("in an imported .slang: import names the shader's line and writes nothing") {
        test::TempDir dir;
        std::string nested = "1.0";
        for (int i = 0; i < 40; ++i) nested = "TWICE(" + nested + ")";
        test::write_file(dir / "bomb.slang", test::slang_program({"", "#define TWICE(a) (a + a)\n", "", "",
                                                               "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                                               "void main() { FragColor = texture(Source, vTexCoord) * " + nested + "; }\n"}));
        test::write_file(dir / "bomb.slangp", "shaders = 1\nshader0 = bomb.slang\n");
        auto run = test::run_crtforge("import '" + (dir / "bomb.slangp") + "' --out '" + (dir / "out") + "'");
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("bomb.slang:"));
        CHECK_THAT(run.err, Catch::Contains("expands to more than 4000000 tokens"));
        CHECK_FALSE(fs::exists(dir / "out"));
    }
}

TEST_CASE("hostile inputs of stop 51: stateful golden frames, bench frames, float range and empty values in .slangp, #extension, crafted report ids, links out of the templates, cache paths",
          "[hostile][stop51]") {
    test::TempDir dir;
    SECTION("a golden plan asking a stateful preset for a frame far away is refused at the rule's line") {
        test::write_file(dir / "plan/plan.toml", "[[golden]]\nwhy = \"x\"\npresets = [\"super-win\"]\ninputs = [\"color_bars\"]\n"
                                                  "size = [32, 24]\nframes = [1000000]\n");
        auto run = test::run_crtforge("golden update --dir '" + (dir / "plan") + "'");
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("plan.toml:1") && Catch::Contains("golden.frame") && Catch::Contains("keeps state"));
        check_refused("bench --preset super-win --size 64x48 --frame 100000000 --quick --no-tiers", "--frame");
    }
    SECTION("import: values beyond float range, an empty value for a shader parameter, --out a file") {
        const std::string shader = test::slang_program({"float P1; ", "#pragma parameter P1 \"p\" 0.5 0.0 1.0 0.1\n", "", "",
                                                        "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                                        "void main() { FragColor = texture(Source, vTexCoord) * params.P1; }\n"});
        test::write_file(dir / "s.slang", shader);
        std::string huge = shader;
        huge.replace(huge.find("0.5 0.0 1.0 0.1"), 15, "0.5 -1e308 1e308 0.1");
        test::write_file(dir / "huge.slang", huge);
        test::write_file(dir / "value.slangp", "shaders = 1\nshader0 = s.slang\nparameters = \"P1\"\nP1 = 1e39\n");
        test::write_file(dir / "bounds.slangp", "shaders = 1\nshader0 = huge.slang\n");
        test::write_file(dir / "empty.slangp", "shaders = 1\nshader0 = s.slang\nalias0 = \"\"\nP1 =\n");
        test::write_file(dir / "good.slangp", "shaders = 1\nshader0 = s.slang\nP1 = 0.25\n");
        const std::pair<const char*, const char*> cases[] = {{"value.slangp", "value.slangp:4: error: field 'P1'"},
                                                             {"bounds.slangp", "MINIMUM of 'P1' is not a finite number within float range"},
                                                             {"empty.slangp", "empty.slangp:4: error: field 'P1': the shader parameter 'P1' is given an empty value"}};
        for (const auto& [file, wanted] : cases) {
            INFO(file);
            auto run = test::run_crtforge("import '" + (dir / file) + "' --out '" + (dir / "out") + "'");
            CHECK(run.exit_code == 2);
            CHECK_THAT(run.err, Catch::Contains(wanted));
            CHECK_FALSE(fs::exists(dir / "out"));
        }
        overwrite(dir / "afile", "x");
        auto onto = test::run_crtforge("import '" + (dir / "good.slangp") + "' --out '" + (dir / "afile") + "'");
        CHECK(onto.exit_code == 2);
        CHECK_THAT(onto.err, Catch::Contains("afile: error: field '--out': exists and is not a folder"));
    }
    SECTION("a snippet enables no extension; template files stay inside their folder and are regular files") {
        test::ScratchTemplates t;
        t.write("stages/vignette.glsl", "#extension GL_EXT_debug_printf : enable\n" + t.read("stages/vignette.glsl"));
        auto lib = t.load();
        REQUIRE_FALSE(lib.ok());
        CHECK_THAT(lib.error().file, Catch::EndsWith("stages/vignette.glsl"));
        CHECK(lib.error().line == 1);
        CHECK_THAT(lib.error().message, Catch::Contains("#extension"));

        test::write_file(dir / "overlay/presets/keep.toml", "x");
        fs::remove(dir / "overlay/presets/keep.toml");
        fs::create_symlink("/etc/passwd", dir / "overlay/presets/evil.toml");
        auto out = test::run_crtforge("--templates '" + (dir / "overlay") + "' list presets");
        CHECK(out.exit_code == 2);
        CHECK_THAT(out.err, Catch::Contains("evil.toml: error: leads out of the template folder"));
        CHECK(out.err.find("root:") == std::string::npos);  // nothing of the file it points at
        fs::remove(dir / "overlay/presets/evil.toml");
        // An editor's lock beside a preset (Emacs: a link to nothing named .#name.toml) is hidden: not a preset.
        fs::create_symlink("user@host.1234:1700000000", dir / "overlay/presets/.#classic.toml");
        auto locked = test::run_crtforge("--templates '" + (dir / "overlay") + "' list presets");
        CHECK(locked.exit_code == 0);
        fs::create_symlink("/dev/zero", dir / "overlay/presets/zero.toml");
        auto zero = test::run_crtforge("--templates '" + (dir / "overlay") + "' list presets");
        CHECK(zero.exit_code == 2);
        CHECK_THAT(zero.err, Catch::Contains("zero.toml"));
    }
    SECTION("report merge refuses a golden id that climbs out of the report") {
        auto shard = [&](const std::string& name) {
            REQUIRE(test::run_crtforge("validate --preset classic --target spirv --shard " + name + "/2 --report '" + (dir / ("s" + name)) + "'")
                        .exit_code == 0);
        };
        shard("1");
        shard("2");
        const std::string path = dir / "s1/report.json";
        std::string json = test::slurp(path);
        const size_t id = json.find("\"id\": \"", json.find("\"goldens\""));
        REQUIRE(id != std::string::npos);
        json.insert(id + 7, "../../../outside/");
        overwrite(path, json);
        auto merged = test::run_crtforge("report merge --out '" + (dir / "m") + "' '" + (dir / "s1") + "' '" + (dir / "s2") + "'");
        CHECK(merged.exit_code == 2);
        CHECK_THAT(merged.err, Catch::Contains("is not a plain name"));
        CHECK_FALSE(fs::exists(dir / "m"));
    }
    SECTION("a LUT of another size than the layout its form reads is refused at the LUT's line") {
        test::write_file(dir / "lut/presets/tiny.toml", "name = \"tiny\"\ndoc = \"d\"\n[lut.grade]\nfile = \"tiny.png\"\n[[pass]]\n"
                                                       "alias = \"clean\"\n[pass.textures]\ngrade = \"lut:grade\"\n[pass.stages.color_grade]\n");
        Image one;
        one.width = one.height = 1;
        one.rgba = {0.5f, 0.5f, 0.5f, 1.0f};
        REQUIRE(write_png(dir / "lut/presets/tiny.png", one).ok());
        auto run = test::run_crtforge("--templates '" + (dir / "lut") + "' export --preset tiny --target glsl330 --out '" + (dir / "o") + "'");
        CHECK(run.exit_code == 2);
        CHECK_THAT(run.err, Catch::Contains("tiny.toml:3: error: field 'lut.grade': is 1x1, but form 'lut32' of stage 'color_grade' "
                                            "reads 'grade' as a 1024x32 table"));
        CHECK_FALSE(fs::exists(dir / "o"));
    }
    SECTION("the compile cache: set but empty, or not a folder") {
        check_refused("--cache-dir /dev/null list presets", "'--cache-dir': is not a folder");
        overwrite(dir / "file", "x");
        check_refused("--cache-dir '" + (dir / "file") + "' list presets", "is not a folder");
        auto empty = test::run_crtforge("list presets", "CRTFORGE_CACHE=");
        CHECK(empty.exit_code == 2);
        CHECK_THAT(empty.err, Catch::Contains("field 'CRTFORGE_CACHE': is set but empty"));
    }
}

TEST_CASE("hostile inputs of stop 52: a display taken from a large input, a pass beyond the render budget, an option taken as a value",
          "[hostile][stop52]") {
    test::TempDir dir;
    SECTION("the render budget holds for a display taken from the input and for every pass, not only for --size") {
        // 3100 x 3100 (9.6 Mpx) is a readable picture (under the 16 Mpx image budget) but beyond
        // the 4.1 Mpx a render's source may have and the 9 Mpx a render may draw into.
        Image big = Image::make(3100, 3100);
        std::fill(big.rgba.begin(), big.rgba.end(), 0.5f);
        REQUIRE(write_png(dir / "big.png", big).ok());
        // Refused as an input whatever the display (a 4096x4096 one took a render of classic to
        // 2.04 GB at 64x48), and so as the display it would set.
        for (const std::string size : {"", " --size 64x48"}) {
            auto at_input = test::run_crtforge("render --preset classic --input '" + (dir / "big.png") + "'" + size + " --output '" +
                                               (dir / "o.png") + "'");
            CHECK(at_input.exit_code == 2);
            CHECK_THAT(at_input.err, Catch::Contains("big.png: error: field '--input': the input picture 3100x3100 is 9.6 Mpx, "
                                                                     "beyond the source memory budget") &&
                                         Catch::Contains("scale it down first"));
            CHECK(std::count(at_input.err.begin(), at_input.err.end(), '\n') == 1);
        }
        // A pass at twice a 2000x1500 display: 4000x3000, 12 Mpx, which the image budget (16 Mpx)
        // would let through.
        test::write_file(dir / "overlay/presets/up.toml",
                         "name = \"up\"\ndoc = \"d\"\n[[pass]]\nalias = \"up\"\nscale_type = \"viewport\"\nscale = 2.0\n"
                         "[pass.stages.scanlines]\nscanlineIntensity = 0.5\n[[pass]]\nalias = \"down\"\n");
        auto pass = test::run_crtforge("--templates '" + (dir / "overlay") + "' render --preset up --input pixel_art --size 2000x1500 --output '" +
                                       (dir / "o.png") + "'");
        CHECK(pass.exit_code == 2);
        CHECK_THAT(pass.err, Catch::Contains("presets/up.toml:3") && Catch::Contains("pass.up.scale") && Catch::Contains("4000x3000") &&
                                 Catch::Contains("render memory budget"));
        CHECK_FALSE(fs::exists(dir / "o.png"));
    }
    SECTION("a value that makes a stage's loop run billions of steps per pixel is refused before any render, naming it") {
        // A template set whose ringing stage allows two billion taps, and super-win asking for them.
        test::ScratchTemplates t;
        std::string ringing = t.read("stages/ringing.toml");
        const size_t at = ringing.find("range = [1, 6]");
        REQUIRE(at != std::string::npos);
        ringing.replace(at, 14, "range = [1, 2000000000]");
        t.write("stages/ringing.toml", ringing);
        std::string win = t.read("presets/super-win.toml");
        const size_t taps = win.find("ringTaps = 3");
        REQUIRE(taps != std::string::npos);
        win.replace(taps, 12, "ringTaps = 2000000000");
        t.write("presets/super-win.toml", win);
        const std::string base = "--templates '" + t.dir() + "' ";
        for (const std::string& render : {std::string("render --reference"), std::string("render --target spirv")}) {
            INFO(render);
            auto run = test::run_crtforge(base + render + " --preset super-win --input pixel_art --size 320x240 --output '" + (dir / "w.png") + "'");
            CHECK(run.exit_code == 2);
            CHECK_THAT(run.err, Catch::Contains("presets/super-win.toml:34") && Catch::Contains("field 'pass.ntsc.stages.ringing.ringTaps'") &&
                                    Catch::Contains("whose ringTaps sets 4e+09 loop steps per sample"));
            CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
            CHECK_FALSE(fs::exists(dir / "w.png"));
        }
        // The same preset at its own three taps renders.
        win.replace(taps, 21, "ringTaps = 3");
        t.write("presets/super-win.toml", win);
        auto fine = test::run_crtforge(base + "render --reference --preset super-win --input pixel_art --size 64x48 --output '" + (dir / "w.png") + "'");
        CHECK(fine.exit_code == 0);
    }
    SECTION("an option with its value left out, the next option's name taken as the value, is named") {
        check_refused("generate --preset --target glsl330", "--preset has no value ('--target' is an option of its own)");
        check_refused("render --preset --input pixel_art --output o.png", "--preset has no value ('--input'");
    }
}
