// crtforge validate end to end: the shipped goldens are current, every preset x target passes,
// and validation can fail — perturbed shaders are caught, with pictures and reasons in the report.
#include <filesystem>
#include <fstream>
#include <functional>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "crtforge/validate/golden.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/validate/validation.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

using test::golden_dir;

std::string replace_once(std::string s, const std::string& from, const std::string& to) {
    const auto pos = s.find(from);
    REQUIRE(pos != std::string::npos);
    return s.replace(pos, from.size(), to);
}

// Validation of a (perturbed) template library against goldens made from it: the reference renders
// the presets' math, not the templates' GLSL, so the goldens are the shipped ones, current for
// this library (a template edit makes the shipped set stale).
ValidationReport validate_with(const TemplateLibrary& lib, std::vector<std::string> presets, std::vector<TargetId> targets,
                               std::vector<std::string> inputs, const std::string& report_dir = {}) {
    static int dirs = 0;
    static test::TempDir root;
    const std::string goldens = root / ("goldens-" + std::to_string(dirs++));
    fs::create_directories(goldens);
    fs::copy_file(golden_dir() + "/plan.toml", goldens + "/plan.toml");
    for (const std::string& preset : presets)
        for (const std::string& input : inputs) {
            auto made = update_goldens(lib, goldens, preset + "." + input + ".");
            if (!made.ok()) FAIL(made.error().str());
        }
    ValidateRequest request;
    request.presets = std::move(presets);
    request.targets = std::move(targets);
    request.inputs = std::move(inputs);
    request.golden_dir = goldens;
    request.report_dir = report_dir;
    request.vulkan.validation = true;  // any Vulkan validation message fails the render
    auto report = run_validation(lib, request, Cache());
    if (!report.ok()) FAIL(report.error().str());
    return report.value();
}

}  // namespace

TEST_CASE("the shipped goldens are current: the reference renders them bit for bit", "[validate][golden]") {
    const TemplateLibrary& lib = test::validation_library();
    auto manifest = load_golden_manifest(golden_dir());
    REQUIRE(manifest.ok());
    const auto plan = test::golden_plan_or_fail(lib, golden_dir());
    REQUIRE(manifest.value().size() == plan.size());
    for (size_t i = 0; i < plan.size(); ++i) CHECK(manifest.value()[i].id == plan[i].id);
    // Every golden was made of today's presets, templates and oracle.
    for (const GoldenEntry& e : manifest.value()) {
        INFO(e.id << " is stale: run 'crtforge golden update'");
        auto inputs = golden_inputs_hash(lib, e);
        REQUIRE(inputs.ok());
        CHECK(inputs.value() == e.inputs_hash);
    }
    // Re-rendering every golden takes a while on 2 cores; a spread sample of the stored ones covers
    // each preset (the ones rendered at validation check their hash there).
    size_t checked = 0;
    for (size_t i = 0; i < plan.size(); ++i) {
        const GoldenEntry& e = manifest.value()[i];
        if (!e.stored || checked++ % 3 != 0) continue;
        INFO(e.id << " is stale: run 'crtforge golden update'");
        auto stored = read_image(golden_dir() + "/" + e.file());
        REQUIRE(stored.ok());
        // The file holds what was hashed, and the reference renders those very values today
        // (16-bit codes for PNG, half floats for EXR).
        CHECK(golden_hash(stored.value(), e.hdr) == e.hash);
        auto fresh = render_golden_reference(lib, e);
        REQUIRE(fresh.ok());
        CHECK(golden_hash(fresh.value(), e.hdr) == e.hash);
    }
}

TEST_CASE("every shipped preset passes on every target against every golden", "[validate][full]") {
    const TemplateLibrary& lib = test::validation_library();
    ValidateRequest request;
    request.golden_dir = golden_dir();
    request.vulkan.validation = true;  // any Vulkan validation message fails the render
    request.jobs = 2;
    // The Vulkan-rendered targets also on SwiftShader (installed by scripts/setup.sh).
    auto devices = list_vulkan_devices();
    REQUIRE(devices.ok());
    for (const DeviceInfo& d : devices.value())
        if (d.name.find("SwiftShader") != std::string::npos) {
            request.second_vulkan = EngineOptions{d.name, true};
            request.second_label = "swiftshader";
        }
    INFO("SwiftShader's Vulkan driver is missing: run scripts/setup.sh (Debian package chromium-common)");
    REQUIRE(request.second_vulkan);
    auto report = run_validation(lib, request, Cache());
    REQUIRE(report.ok());
    // Per target: one compile check per shader file and pass (and on Godot an inspector check per
    // pass), one render per golden of the main
    // matrix that the target judges; the Vulkan-rendered targets (spirv, hlsl50, hlsl60)
    // render theirs again on SwiftShader.
    std::vector<GoldenEntry> main_goldens;
    for (const GoldenEntry& g : test::golden_plan_or_fail(lib, golden_dir()))
        if (!g.full_matrix) main_goldens.push_back(g);
    REQUIRE(report.value().goldens.size() == main_goldens.size());
    size_t passes = 0, expected = 0;
    for (const Preset& p : lib.presets()) passes += p.passes.size();
    for (const TargetInfo& t : all_targets()) {
        size_t judged = 0;
        for (const GoldenEntry& g : main_goldens) judged += g.judged_by(t.name);
        const bool vulkan = t.id == TargetId::Spirv || t.id == TargetId::Hlsl50 || t.id == TargetId::Hlsl60;
        const bool godot = t.id == TargetId::Godot4 || t.id == TargetId::Godot3;  // an inspector check per pass
        expected += (t.shader_roles.size() + (godot ? 1 : 0)) * passes + judged * (vulkan ? 2 : 1);
    }
    CHECK(report.value().checks.size() == expected);
    for (const auto& c : report.value().checks) {
        INFO(c.preset << " " << c.target << " " << c.check << ": " << c.message);
        CHECK(c.passed);
    }
    // The GLSL targets were rendered by the OpenGL driver itself, not re-compiled to SPIR-V.
    for (const auto& [target, consumer] : report.value().consumers)
        if (target.rfind("glsl", 0) == 0) CHECK_THAT(consumer, Catch::Contains("Mesa"));
}

TEST_CASE("validate catches a scanline period off by 5%", "[validate][perturbed]") {
    test::ScratchTemplates t;
    t.write("stages/scanlines.glsl",
            replace_once(t.read("stages/scanlines.glsl"), "(2.0 * PI / scanlinePeriodPx)", "(2.0 * PI / (scanlinePeriodPx * 1.05))"));
    auto lib = t.load();
    REQUIRE(lib.ok());
    test::TempDir report_dir;
    ValidationReport r = validate_with(*lib.value(), {"webgpu-post"}, {TargetId::Spirv}, {"color_bars"}, report_dir.path());
    size_t render_failures = 0;
    for (const auto& c : r.checks) {
        if (c.check.rfind("render:", 0) != 0) continue;
        CHECK_FALSE(c.passed);
        CHECK_THAT(c.message, Catch::Contains("RMSE"));
        ++render_failures;
        CHECK(fs::exists(report_dir / ("images/" + c.golden_id + "/spirv.diff.png")));
        CHECK(fs::exists(report_dir / ("images/" + c.golden_id + "/spirv.png")));
        CHECK(fs::exists(report_dir / ("images/" + c.golden_id + "/golden.png")));
    }
    CHECK(render_failures == 1);  // color_bars has one golden per preset (320x240)
    REQUIRE(write_report(r, report_dir.path()).ok());
    auto json = nlohmann::json::parse(std::ifstream(report_dir / "report.json"));
    CHECK(json["summary"]["failed"].get<int>() == static_cast<int>(render_failures));
}

TEST_CASE("validate catches a swapped mask channel", "[validate][perturbed]") {
    test::ScratchTemplates t;
    t.write("stages/mask.glsl", replace_once(t.read("stages/mask.glsl"), "if (col == 0) mask = vec3(1.0, maskDim, maskDim);",
                                             "if (col == 0) mask = vec3(maskDim, 1.0, maskDim);"));
    auto lib = t.load();
    REQUIRE(lib.ok());
    ValidationReport r = validate_with(*lib.value(), {"quiet-frame"}, {TargetId::Spirv, TargetId::Glsl330}, {"color_bars"});
    size_t failed_renders = 0;
    for (const auto& c : r.checks)
        if (c.check.rfind("render:", 0) == 0 && !c.passed) ++failed_renders;
    CHECK(failed_renders == 2);
}

TEST_CASE("shard reports merge back into the unsharded report", "[validate]") {
    const TemplateLibrary& lib = test::shipped_library();
    test::TempDir a, b, whole, merged;
    ValidateRequest request;
    request.presets = {"classic", "webgpu-post"};
    request.targets = {TargetId::Spirv, TargetId::Glsl450};
    request.inputs = {"hdr"};
    request.golden_dir = golden_dir();
    request.vulkan.validation = true;
    auto full = run_validation(lib, request, Cache());
    REQUIRE(full.ok());
    REQUIRE(write_report(full.value(), whole.path()).ok());
    for (unsigned i : {1u, 2u}) {
        request.shard = Shard{i, 2};
        auto part = run_validation(lib, request, Cache());
        REQUIRE(part.ok());
        REQUIRE(write_report(part.value(), i == 1 ? a.path() : b.path()).ok());
    }
    auto m = merge_reports({a.path(), b.path()});
    REQUIRE(m.ok());
    REQUIRE(write_report(m.value(), merged.path()).ok());
    auto slurp = [](const std::string& p) {
        std::ifstream in(p);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    CHECK(slurp(merged / "report.json") == slurp(whole / "report.json"));
    CHECK(slurp(merged / "junit.xml") == slurp(whole / "junit.xml"));
}

TEST_CASE("a golden whose inputs changed is stale: validate fails it and names the fix", "[validate][golden][stale]") {
    test::ScratchTemplates t;
    test::TempDir golden;
    fs::copy_file(std::string(CRTFORGE_SOURCE_DIR) + "/golden/plan.toml", golden / "plan.toml");
    const std::string templates = "--templates '" + t.dir() + "' ";
    auto update = test::run_crtforge(templates + "golden update --dir '" + golden.path() + "' --filter classic.color_bars");
    INFO(update.err);
    REQUIRE(update.exit_code == 0);
    const std::string validate = templates + "validate --golden-dir '" + golden.path() + "' --preset classic --input color_bars --target spirv";
    auto fresh = test::run_crtforge(validate);
    INFO(fresh.out << fresh.err);
    CHECK(fresh.exit_code == 0);

    SECTION("a preset value moved by a little") {
        std::string preset = t.read("presets/classic.toml");
        preset += "\n";  // the same text with one value nudged: 10% on a subtle param
        const size_t at = preset.find("vignetteStrength");
        REQUIRE(at != std::string::npos);
        const size_t eq = preset.find('=', at), end = preset.find('\n', eq);
        const double value = std::stod(preset.substr(eq + 1, end - eq - 1));
        preset = preset.substr(0, eq + 1) + " " + std::to_string(value * 1.1) + preset.substr(end);
        t.write("presets/classic.toml", preset);
    }
    SECTION("a stage's snippet edited") {
        t.write("stages/vignette.glsl", t.read("stages/vignette.glsl") + "\n// an edit\n");
    }
    auto stale = test::run_crtforge(validate);
    CHECK(stale.exit_code == 1);
    CHECK_THAT(stale.out, Catch::Contains("classic.color_bars.320x240.f0 is stale"));
    CHECK_THAT(stale.out, Catch::Contains("crtforge golden update"));
}

TEST_CASE("the judge catches errors confined to a row or a patch, small global gains and a channel swap", "[validate][judge]") {
    // A real render that passes (Vulkan, classic over pixel art), then damaged the ways a wrong
    // shader damages a frame: each must fail the shipped golden's tolerance.
    const TemplateLibrary& lib = test::shipped_library();
    auto manifest = load_golden_manifest(golden_dir());
    REQUIRE(manifest.ok());
    const GoldenEntry* entry = nullptr;
    for (const GoldenEntry& e : manifest.value())
        if (e.id == "classic.pixel_art.320x240.f0") entry = &e;
    REQUIRE(entry != nullptr);
    auto golden = load_golden_image(lib, *entry, golden_dir());
    REQUIRE(golden.ok());
    const Preset& preset = *lib.find_preset("classic");
    auto compiled = compile_scene(lib, preset, {}, Cache());
    REQUIRE(compiled.ok());
    TargetRenderer renderer;
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &compiled.value();
    r.source = [entry](int frame) { return golden_input(*entry, frame); };
    r.width = entry->width;
    r.height = entry->height;
    r.frames = {0};
    auto rendered = renderer.render_scene(r);
    REQUIRE(rendered.ok());
    const Image good = rendered.value().front();
    auto baseline = judge(good, golden.value(), entry->tolerance);
    REQUIRE(baseline.ok());
    INFO(baseline.value().reason);
    REQUIRE(baseline.value().passed);

    auto fails = [&](const char* what, const std::function<void(Image&)>& damage) {
        Image bad = good;
        damage(bad);
        auto verdict = judge(bad, golden.value(), entry->tolerance);
        REQUIRE(verdict.ok());
        INFO(what << ": RMSE " << verdict.value().metrics.rmse << ", tile " << verdict.value().max_tile_rmse << ", outliers "
                  << verdict.value().outlier_fraction);
        CHECK_FALSE(verdict.value().passed);
    };
    fails("a black row", [](Image& im) {
        for (int x = 0; x < im.width; ++x) im.set_pixel(x, im.height / 2, {0, 0, 0, 1});
    });
    fails("a 16x16 patch 0.09 too bright", [](Image& im) {
        for (int y = 100; y < 116; ++y)
            for (int x = 100; x < 116; ++x)
                for (int c = 0; c < 3; ++c) im.at(x, y)[c] += 0.09f;
    });
    fails("a global gain of 1%", [](Image& im) {
        for (size_t i = 0; i < im.rgba.size(); ++i)
            if (i % 4 != 3) im.rgba[i] *= 1.01f;
    });
    fails("one column off by 0.05", [](Image& im) {
        for (int y = 0; y < im.height; ++y) im.at(7, y)[1] += 0.05f;
    });
    fails("red and blue swapped", [](Image& im) {
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) std::swap(im.at(x, y)[0], im.at(x, y)[2]);
    });
}

TEST_CASE("a golden goes stale when a pass's supersample, a declared tier or fullscreen.vert changes", "[validate][golden]") {
    // The hash of one golden of super-win (it declares tiers) in a scratch copy, before and after
    // each edit.
    auto hash_after = [](const std::function<void(const test::ScratchTemplates&)>& edit) {
        test::ScratchTemplates t;
        edit(t);
        auto lib = t.load();
        REQUIRE(lib.ok());
        GoldenEntry e;
        e.id = "super-win.pixel_art.320x240.f0";
        e.preset = "super-win";
        e.input = "pixel_art";
        e.width = 320;
        e.height = 240;
        auto hash = golden_inputs_hash(*lib.value(), e);
        REQUIRE(hash.ok());
        return hash.value();
    };
    const std::string before = hash_after([](const test::ScratchTemplates&) {});
    CHECK(hash_after([](const test::ScratchTemplates&) {}) == before);
    auto replaced = [](const test::ScratchTemplates& t, const std::string& file, const std::string& find, const std::string& replace) {
        std::string text = t.read(file);
        const size_t at = text.find(find);
        REQUIRE(at != std::string::npos);
        t.write(file, text.replace(at, find.size(), replace));
    };
    CHECK(hash_after([&](const test::ScratchTemplates& t) { t.write("fullscreen.vert", t.read("fullscreen.vert") + "\n// edited\n"); }) != before);
    const std::string preset = test::ScratchTemplates().read("presets/super-win.toml");
    REQUIRE(preset.find("[tiers.") != std::string::npos);
    const size_t scale = preset.find("scale = ", preset.find("[tiers."));
    REQUIRE(scale != std::string::npos);
    const std::string old_line = preset.substr(scale, preset.find('\n', scale) - scale);
    INFO(old_line);
    CHECK(hash_after([&](const test::ScratchTemplates& t) { replaced(t, "presets/super-win.toml", old_line, "scale = 0.3"); }) != before);
}
