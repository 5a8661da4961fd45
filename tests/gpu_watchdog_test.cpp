// A draw that never finishes does not hang crtforge: past --gpu-timeout the run stops with one
// line naming the preset, pass and frame (exit code 3), leaving no output and none of its staging
// folders or temporary files; a corpus sweep gives that preset a "timeout" row and goes on.
// SwiftShader runs a shader's loops as written (lavapipe stops each invocation after 65535 loop
// iterations), so it is the driver such a shader hangs.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "crtforge/exit_cleanup.hpp"
#include "crtforge/runtime/gpu_watchdog.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

// A pass whose loops run 10^10 times per pixel: hours on SwiftShader. The bound comes from a
// parameter, so no compiler folds the loop away.
std::string endless_pass() {
    return test::slang_program({"float Rounds; ", "#pragma parameter Rounds \"rounds\" 100000.0 1.0 100000.0 1.0\n#pragma name heavy\n", "", "",
                                "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                "void main() {\n"
                                "    vec4 sum = vec4(0.0);\n"
                                "    for (int i = 0; i < int(params.Rounds); ++i)\n"
                                "        for (int j = 0; j < int(params.Rounds); ++j)\n"
                                "            sum += texture(Source, vTexCoord + vec2(float(i & 7), float(j & 7)) * 1e-3);\n"
                                "    FragColor = sum * 1e-10;\n"
                                "}\n"});
}

std::string plain_pass() {
    return test::slang_program({"", "", "", "", "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
                                                "void main() { FragColor = texture(Source, vTexCoord); }\n"});
}

}  // namespace

TEST_CASE("a process stopped at once removes the paths registered for it, and only while they are registered", "[watchdog]") {
    test::TempDir dir;
    fs::create_directories(dir / "staging/images");
    test::write_file(dir / "staging/images/a.png", "x");
    test::write_file(dir / "out.png.tmp-1", "half");
    test::write_file(dir / "kept", "y");
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        const ExitCleanup staging(dir / "staging");
        const ExitCleanup tmp(dir / "out.png.tmp-1");
        { const ExitCleanup done(dir / "kept"); }  // unregistered again: stays
        exit_after_cleanup("stopping", kExitGpuTimeout);
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == kExitGpuTimeout);
    CHECK_FALSE(fs::exists(dir / "staging"));
    CHECK_FALSE(fs::exists(dir / "out.png.tmp-1"));
    CHECK(fs::exists(dir / "kept"));
}

TEST_CASE("a draw past --gpu-timeout stops render with one line naming the pass, and a corpus sweep gives it a timeout row and goes on",
          "[watchdog][cli]") {
    test::TempDir dir;
    test::write_file(dir / "lib/heavy.slang", endless_pass());
    test::write_file(dir / "lib/plain.slang", plain_pass());
    test::write_file(dir / "lib/endless.slangp", "shaders = 2\nshader0 = plain.slang\nshader1 = heavy.slang\n");
    test::write_file(dir / "lib/plain.slangp", "shaders = 1\nshader0 = plain.slang\n");

    SECTION("render") {
        auto run = test::run_crtforge("--gpu-timeout 2 render --device swiftshader --preset '" + (dir / "lib/endless.slangp") +
                                      "' --input color_bars --size 64x48 --output '" + (dir / "out/picture.png") + "'");
        INFO(run.err);
        CHECK(run.exit_code == kExitGpuTimeout);
        CHECK_THAT(run.err, Catch::Contains("error: preset 'endless', pass 1 'heavy', frame 0: the GPU has not finished it in 2 s (--gpu-timeout)"));
        CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(dir / "out/picture.png"));
        // The limit is the user's: 0 waits for ever, and a value that is not a number of seconds is refused.
        for (const char* bad : {"-1", "nan", "inf", "soon"}) {
            auto refused = test::run_crtforge(std::string("--gpu-timeout ") + bad + " list");
            CHECK(refused.exit_code == 2);
            CHECK_THAT(refused.err, Catch::Contains("--gpu-timeout: a number of seconds"));
        }
    }
    SECTION("corpus") {
        auto run = test::run_crtforge("--gpu-timeout 2 corpus '" + (dir / "lib") + "' --vulkan-only --device swiftshader --report '" +
                                      (dir / "report") + "'");
        INFO(run.err);
        REQUIRE(run.exit_code == 0);
        std::ifstream in(dir / "report/corpus.json");
        const auto report = nlohmann::json::parse(in);
        REQUIRE(report.at("rows").size() == 2);
        for (const auto& row : report.at("rows")) {
            INFO(row.dump());
            const auto& spirv = row.at("targets").at("spirv");
            if (row.at("preset") == "endless.slangp") {
                CHECK(spirv.at("status") == "timeout");
                CHECK_THAT(spirv.at("reason").get<std::string>(), Catch::Contains("a draw ran past 2 s on the GPU (--gpu-timeout)"));
            } else {
                CHECK(spirv.at("status") != "timeout");
                CHECK(spirv.at("status") != "crashed");
            }
        }
    }
}
