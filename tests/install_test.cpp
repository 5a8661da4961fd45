// crtforge as a library other projects find: `cmake --install` into a prefix, the prefix moved
// elsewhere, then a separate CMake project (examples/find-package) finds it with find_package,
// builds against it and exports a preset — byte-identical to the build tree's export.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using namespace crtforge;

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

using test::slurp;

void require_ok(const test::CommandResult& r, const std::string& what) {
    INFO(what << "\nstdout: " << r.out << "\nstderr: " << r.err);
    REQUIRE(r.exit_code == 0);
}

// The in-process export of one preset and target, as the build tree makes it.
std::map<std::string, std::string> build_tree_export(const std::string& preset, TargetId target) {
    ExportRequest request;
    request.presets = {preset};
    request.targets = {target};
    auto exported = run_export(test::shipped_library(), request, Cache());
    REQUIRE(exported.ok());
    return exported.value().files;
}

void require_same_files(const fs::path& dir, const std::map<std::string, std::string>& expected) {
    size_t found = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        const std::string rel = fs::relative(entry.path(), dir).string();
        INFO(rel);
        if (rel == ".crtforge-export") {  // the export's index of what it wrote: every file, one a line
            const std::string index = slurp(entry.path());
            for (const auto& [path, data] : expected) CHECK(index.find("\n" + path + "\n") != std::string::npos);
            continue;
        }
        auto it = expected.find(rel);
        REQUIRE(it != expected.end());
        CHECK(slurp(entry.path()) == it->second);
        ++found;
    }
    CHECK(found == expected.size());
}

}  // namespace

TEST_CASE("an installed, then moved crtforge is found by find_package and exports like the build tree", "[install]") {
    test::TempDir scratch;
    const fs::path tmp = scratch.path();
    const fs::path first = tmp / "prefix", moved = tmp / "moved";
    for (const char* component : {"Runtime", "Development"})
        require_ok(test::run_command(quoted(CRTFORGE_CMAKE_COMMAND) + " --install " + quoted(CRTFORGE_BUILD_DIR) +
                                     " --prefix " + quoted(first.string()) + " --component " + component),
                   std::string("cmake --install, component ") + component);
    // Relocatable: nothing installed names the place it was installed to, the build or the sources.
    fs::rename(first, moved);
    for (const auto& entry : fs::recursive_directory_iterator(moved)) {
        if (!entry.is_regular_file()) continue;
        const std::string data = slurp(entry.path());
        INFO(entry.path().string());
        CHECK(data.find(first.string()) == std::string::npos);
        CHECK(data.find(CRTFORGE_SOURCE_DIR) == std::string::npos);
        CHECK(data.find(CRTFORGE_BUILD_DIR) == std::string::npos);
    }

    SECTION("the installed CLI finds its templates and module beside itself") {
        const std::string cli = quoted((moved / "bin" / "crtforge").string());
        auto list = test::run_command(cli + " list presets");
        require_ok(list, "installed crtforge list presets");
        CHECK(list.out.find("classic\n") != std::string::npos);
        const fs::path out = tmp / "cli-export";
        require_ok(test::run_command(cli + " --no-cache export --preset classic --target glsl330 --out " + quoted(out.string())),
                   "installed crtforge export");
        require_same_files(out, build_tree_export("classic", TargetId::Glsl330));
        // The image I/O module is found in <prefix>/lib/crtforge.
        require_ok(test::run_command(cli + " render --preset classic --input color_bars --size 64x48 --reference --output " +
                                     quoted((tmp / "ref.png").string())),
                   "installed crtforge render --reference");
        CHECK(fs::file_size(tmp / "ref.png") > 0);
    }

    SECTION("a separate CMake project builds against it with find_package and exports a preset") {
        const fs::path build = tmp / "consumer-build";
        require_ok(test::run_command(quoted(CRTFORGE_CMAKE_COMMAND) + " -S " +
                                     quoted(std::string(CRTFORGE_SOURCE_DIR) + "/examples/find-package") + " -B " +
                                     quoted(build.string()) + " -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=" +
                                     quoted(moved.string())),
                   "configure the consumer");
        require_ok(test::run_command(quoted(CRTFORGE_CMAKE_COMMAND) + " --build " + quoted(build.string())),
                   "build the consumer");
        const fs::path out = tmp / "consumer-export";
        auto run = test::run_command(quoted((build / "export_preset").string()) + " quiet-frame wgsl " + quoted(out.string()));
        require_ok(run, "run the consumer");
        require_same_files(out, build_tree_export("quiet-frame", TargetId::Wgsl));
    }
}
