// A user's own stage, which the reference renderer has no model of: golden update lists its goldens
// as needing approval, `golden approve` stores reviewed Vulkan renders marked approved, validate
// judges every target against them and against this run's Vulkan render (agree: checks), and an
// edit of the stage makes the approved goldens stale.
#include <filesystem>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "crtforge/files.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/validate/validation.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

// A posterising stage of the user's: no model of it in reference/.
constexpr const char* kStageSpec = R"(name = "user_posterize"
doc = "The user's own stage: posterise each channel to a number of levels"
order = 45

[[param]]
name = "posterLevels"
type = "float"
range = [2.0, 16.0]
default = 5.0
doc = "Levels per channel"
runtime = true

[[form]]
name = "levels"
doc = "floor(color * levels) / (levels - 1), clamped"
params = ["posterLevels"]
color = "user_posterize"
)";

constexpr const char* kStageGlsl = R"(vec3 user_posterize(vec3 color, CrtFrag frag) {
    return clamp(floor(color * posterLevels) / (posterLevels - 1.0), 0.0, 1.0);
}
)";

constexpr const char* kPreset = R"(name = "my-poster"
doc = "A user's preset: scanlines and the user's posteriser"

[stages.scanlines]
scanlineIntensity = 0.4

[stages.user_posterize]
posterLevels = 4.0
)";

constexpr const char* kPlan = R"([[golden]]
why = "the user's preset on a ramp"
presets = ["my-poster"]
inputs = ["grey_ramp", "color_bars"]
size = [160, 120]
)";

}  // namespace

TEST_CASE("a user's own stage: golden approve, cross-target agreement, stale on edit", "[validate][user-stage]") {
    test::ScratchTemplates templates;
    templates.write("stages/user_posterize.toml", kStageSpec);
    templates.write("stages/user_posterize.glsl", kStageGlsl);
    templates.write("presets/my-poster.toml", kPreset);
    auto loaded = templates.load();
    REQUIRE(loaded.ok());
    const TemplateLibrary& lib = *loaded.value();
    test::TempDir goldens;
    REQUIRE(write_file_atomic(goldens / "plan.toml", kPlan).ok());

    // The reference cannot make these goldens: update renders none and names them.
    auto updated = update_goldens(lib, goldens.path(), "");
    REQUIRE(updated.ok());
    CHECK(updated.value().written == 0);
    CHECK(updated.value().unmodelled.size() == 2);
    CHECK_THAT(updated.value().unmodelled_reason, Catch::Contains("user_posterize"));

    // Validate without approved goldens fails them, naming the fix.
    ValidateRequest request;
    request.golden_dir = goldens.path();
    request.targets = {TargetId::Spirv, TargetId::Glsl330, TargetId::Wgsl};
    {
        auto report = run_validation(lib, request, Cache());
        REQUIRE(report.ok());
        CHECK(report.value().failed() == 2 * 3);
    }

    // A filter that also takes goldens the reference renders is refused, and writes nothing.
    {
        test::TempDir mixed;
        REQUIRE(write_file_atomic(mixed / "plan.toml", std::string(kPlan) + "\n[[golden]]\nwhy = \"a shipped preset\"\n"
                                                        "presets = [\"classic\"]\ninputs = [\"grey_ramp\"]\nsize = [160, 120]\n").ok());
        auto refused = approve_goldens(lib, mixed.path(), "grey_ramp");
        REQUIRE_FALSE(refused.ok());
        CHECK_THAT(refused.error().message, Catch::Contains("rendered by the reference"));
        CHECK(fs::directory_iterator(mixed.path()) != fs::directory_iterator());
        CHECK_FALSE(fs::exists(mixed / "manifest.json"));
    }

    // Approve: Vulkan renders stored as goldens marked approved.
    auto approved = approve_goldens(lib, goldens.path(), "my-poster.");
    REQUIRE(approved.ok());
    CHECK(approved.value().written == 2);
    auto manifest = load_golden_manifest(goldens.path());
    REQUIRE(manifest.ok());
    for (const GoldenEntry& e : manifest.value()) {
        CHECK(e.approved);
        CHECK(fs::exists(goldens / e.file()));
    }
    auto json = nlohmann::json::parse(read_text_file(goldens / "manifest.json").value());
    CHECK(json["goldens"][0]["origin"] == "approved");

    // Every target against the approved golden, and every target but spirv against this run's
    // Vulkan render: 2 renders per target, plus 2 agreements per non-spirv target.
    auto report = run_validation(lib, request, Cache());
    REQUIRE(report.ok());
    size_t agreements = 0;
    for (const CheckResult& c : report.value().checks) {
        INFO(c.target << " " << c.check << ": " << c.message);
        CHECK(c.passed);
        agreements += c.check.rfind("agree:", 0) == 0;
    }
    CHECK(agreements == 2 * 2);

    // A later golden update keeps the approved goldens (the reference still has no model).
    auto again = update_goldens(lib, goldens.path(), "");
    REQUIRE(again.ok());
    CHECK(again.value().unmodelled.empty());
    REQUIRE(load_golden_manifest(goldens.path()).value().front().approved);

    // Editing the stage makes the approved goldens stale, and the message says to approve again.
    templates.write("stages/user_posterize.glsl", std::string(kStageGlsl) + "// edited\n");
    auto edited = templates.load();
    REQUIRE(edited.ok());
    request.targets = {TargetId::Spirv};
    auto stale = run_validation(*edited.value(), request, Cache());
    REQUIRE(stale.ok());
    CHECK(stale.value().failed() == 2);
    for (const CheckResult& c : stale.value().checks) {
        INFO(c.check << ": " << c.message);
        if (c.check.rfind("render:", 0) == 0) CHECK_THAT(c.message, Catch::Contains("golden approve"));
        else CHECK(c.passed);
    }
}

TEST_CASE("an approved golden's agreement check catches a target that disagrees with Vulkan", "[validate][user-stage]") {
    // The agreement is judged like a golden: a render one level off on a patch fails it.
    Image vulkan = Image::make(64, 64, {0.5f, 0.5f, 0.5f, 1.0f});
    Image other = vulkan;
    for (int y = 10; y < 26; ++y)
        for (int x = 10; x < 26; ++x) other.at(x, y)[1] += 1.0f / 3.0f;
    const Tolerance tolerance = test::golden_plan_or_fail(test::shipped_library(), std::string(CRTFORGE_SOURCE_DIR) + "/golden")
                                    .front()
                                    .tolerance;
    auto verdict = judge(other, vulkan, tolerance);
    REQUIRE(verdict.ok());
    CHECK_FALSE(verdict.value().passed);
}

TEST_CASE("an overlay folder adds a studio's stages and presets on top of the shipped templates", "[user-stage][overlay]") {
    test::TempDir overlay;
    REQUIRE(write_file_atomic(overlay / "stages/user_posterize.toml", kStageSpec).ok());
    REQUIRE(write_file_atomic(overlay / "stages/user_posterize.glsl", kStageGlsl).ok());
    REQUIRE(write_file_atomic(overlay / "presets/my-poster.toml", kPreset).ok());
    // A studio's own take on a shipped preset replaces it; presets based on it follow.
    REQUIRE(write_file_atomic(overlay / "presets/classic.toml",
                              "name = \"classic\"\ndoc = \"The studio's classic\"\nbase = \"atari-crt\"\n\n[stages.scanlines]\n"
                              "scanlineIntensity = 0.25\n")
                .ok());
    auto loaded = TemplateLibrary::load(overlay.path());
    REQUIRE(loaded.ok());
    const TemplateLibrary& lib = *loaded.value();
    CHECK(lib.overlay());
    CHECK(lib.presets().size() == test::shipped_library().presets().size() + 1);
    REQUIRE(lib.find_stage("user_posterize"));
    REQUIRE(lib.find_preset("my-poster"));
    CHECK(lib.find_preset("classic")->doc == "The studio's classic");
    CHECK(lib.find_preset("crt-pulse")->doc == test::shipped_library().find_preset("crt-pulse")->doc);

    test::TempDir out;
    auto exported = test::run_crtforge("--templates " + overlay.path() + " export -q --preset my-poster,classic --target glsl330 --out " + out.path());
    CHECK(exported.exit_code == 0);
    CHECK(fs::exists(out / "glsl330/my-poster.frag"));

    // An overlay stage whose order a shipped stage holds: refused at the overlay's file.
    std::string clash = kStageSpec;
    clash.replace(clash.find("order = 45"), 10, "order = " + std::to_string(test::shipped_library().stages().front().order));
    REQUIRE(write_file_atomic(overlay / "stages/user_posterize.toml", clash).ok());
    auto refused = TemplateLibrary::load(overlay.path());
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().str(), Catch::Contains("order"));
    // A folder that is neither a template set nor an overlay.
    test::TempDir empty;
    auto neither = TemplateLibrary::load(empty.path());
    REQUIRE_FALSE(neither.ok());
    CHECK_THAT(neither.error().message, Catch::Contains("overlay"));
}
