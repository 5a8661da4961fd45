// Snapshot tests of emitted text: shaders in, reference text out. The snapshot template library
// (tests/snapshots/templates: small stages, one construct family each) exported to every target
// must equal tests/snapshots/expected/ byte for byte, and crtforge's WGSL emitter must turn each
// raw GLSL case in tests/snapshots/wgsl/ into exactly the .wgsl files beside it. A mismatch names
// the file, the first differing line and both lines; expected files change only through
// scripts/update-snapshots.sh and a reviewed diff (tests/snapshots/README.md).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "crtforge/files.hpp"
#include "targets/wgsl/wgsl_emitter.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace crtforge;

const char* const kUpdateCommand = "scripts/update-snapshots.sh [BUILD_DIR]";

// Failures name files relative to the source root, as the update command and git do.
const std::string kSnapshots = "tests/snapshots";
std::string snapshot_dir() { return std::string(CRTFORGE_SOURCE_DIR) + "/" + kSnapshots; }

// Loaded through an absolute path (from the build tree, CTest's working directory) while the CLI
// that wrote the expected files ran with a relative one: a path leaking into any output shows up
// as a mismatch.
const TemplateLibrary& snapshot_library() {
    static std::shared_ptr<TemplateLibrary> lib = [] {
        auto loaded = TemplateLibrary::load(snapshot_dir() + "/templates");
        if (!loaded.ok()) FAIL("snapshot templates do not load: " << loaded.error().str());
        return loaded.value();
    }();
    return *lib;
}

// Every regular file below dir, keyed by its path relative to dir.
std::map<std::string, std::string> read_tree(const std::string& dir) {
    std::map<std::string, std::string> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        auto text = read_text_file(entry.path().string());
        REQUIRE(text.ok());
        files[fs::relative(entry.path(), dir).generic_string()] = std::move(text.value());
    }
    return files;
}

// The 1-based line `line` of text, without its newline.
std::string line_at(const std::string& text, size_t line) {
    size_t begin = 0;
    for (size_t n = 1; n < line && begin != std::string::npos; ++n) {
        begin = text.find('\n', begin);
        if (begin != std::string::npos) ++begin;
    }
    if (begin == std::string::npos || begin >= text.size()) return "<end of file>";
    const size_t end = text.find('\n', begin);
    return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// Where two versions of a file first differ: line and both lines for text, the byte offset for
// binary files (SPIR-V).
std::string describe_difference(const std::string& expected, const std::string& actual) {
    const size_t common = std::min(expected.size(), actual.size());
    size_t at = 0;
    while (at < common && expected[at] == actual[at]) ++at;
    const bool binary = expected.find('\0') != std::string::npos || actual.find('\0') != std::string::npos;
    if (binary)
        return "first difference at byte " + std::to_string(at) + " (expected " + std::to_string(expected.size()) +
               " bytes, got " + std::to_string(actual.size()) + ")";
    const size_t line = 1 + static_cast<size_t>(std::count(expected.begin(), expected.begin() + static_cast<long>(at), '\n'));
    return "first difference at line " + std::to_string(line) + "\n  expected: " + line_at(expected, line) +
           "\n  actual:   " + line_at(actual, line);
}

// Compares every produced file with its expected twin, and the reverse, without stopping at the
// first mismatch; `hint` closes each failure. Returns the number of problems.
size_t compare_with_expected(const std::map<std::string, std::string>& actual,
                             const std::map<std::string, std::string>& expected, const std::string& expected_dir,
                             const std::string& hint = std::string("update with: ") + kUpdateCommand) {
    size_t problems = 0;
    for (const auto& [path, data] : actual) {
        auto it = expected.find(path);
        if (it == expected.end()) {
            FAIL_CHECK("new output with no expected file: " << expected_dir << "/" << path << "\n  " << hint);
            ++problems;
        } else if (it->second != data) {
            FAIL_CHECK("snapshot mismatch: " << expected_dir << "/" << path << "\n  "
                       << describe_difference(it->second, data) << "\n  " << hint);
            ++problems;
        }
    }
    for (const auto& [path, data] : expected) {
        if (actual.count(path)) continue;
        FAIL_CHECK("expected file with no output: " << expected_dir << "/" << path << "\n  " << hint);
        ++problems;
    }
    return problems;
}

// Every preset to every target with default options, as `crtforge --no-cache export` does.
std::map<std::string, std::string> export_snapshots(const TemplateLibrary& library) {
    auto result = run_export(library, ExportRequest{}, Cache());
    INFO((result.ok() ? std::string() : result.error().str()));
    REQUIRE(result.ok());
    return result.value().files;
}

// The raw WGSL cases: <case>.frag compiled with and without spirv-opt, emitted with the
// full-screen vertex shader of the snapshot library's passthrough preset.
std::map<std::string, std::string> emit_wgsl_cases(const std::string& dir) {
    auto frags = list_files(dir, ".frag");
    REQUIRE(frags.ok());
    REQUIRE(!frags.value().empty());
    static const SpirvBinary vertex = test::compile_or_fail(snapshot_library(), "passthrough").vertex;
    std::map<std::string, std::string> out;
    for (const std::string& path : frags.value()) {
        const std::string name = file_stem(path);
        auto source = read_text_file(path);
        REQUIRE(source.ok());
        for (bool optimize : {true, false}) {
            const std::string output = name + (optimize ? ".opt.wgsl" : ".noopt.wgsl");
            CompileOptions options;
            options.optimize = optimize;
            options.source_name = name + ".frag";  // no directory: diagnostics stay machine-independent
            auto fragment = compile_to_spirv(source.value(), options);
            if (!fragment.ok()) {
                FAIL_CHECK(output << ": " << fragment.error().str());
                continue;
            }
            auto module = wgsl::emit_wgsl({{&vertex, "vs_main"}, {&fragment.value(), "fs_main"}}, {});
            if (!module.ok()) {
                FAIL_CHECK(output << ": " << module.error().str());
                continue;
            }
            out[output] = module.value().text;
        }
    }
    return out;
}

bool update_requested() {
    const char* env = std::getenv("CRTFORGE_UPDATE_SNAPSHOTS");
    return env && std::string(env) == "1";
}

}  // namespace

TEST_CASE("snapshot: every preset x target export equals tests/snapshots/expected", "[snapshot]") {
    const auto actual = export_snapshots(snapshot_library());
    // Every snapshot preset reaches every target.
    for (const Preset& preset : snapshot_library().presets())
        for (const TargetInfo& target : all_targets()) {
            const std::string prefix = std::string(target.name) + "/";
            const bool found = std::any_of(actual.begin(), actual.end(), [&](const auto& file) {
                return file.first.rfind(prefix, 0) == 0 && file.first.find(preset.name) != std::string::npos;
            });
            if (!found) FAIL_CHECK("no " << target.name << " output for preset " << preset.name);
        }
    const auto expected = read_tree(snapshot_dir() + "/expected");
    REQUIRE(!expected.empty());
    CHECK(compare_with_expected(actual, expected, kSnapshots + "/expected") == 0);
}

TEST_CASE("snapshot: exported text names no template path and repeats byte for byte", "[snapshot]") {
    const auto first = export_snapshots(snapshot_library());
    // Loaded again through a "./"-prefixed relative path: other #line names in the assembled GLSL
    // than the first load's, so the in-process compile memo misses and everything is compiled afresh.
    const std::string relative = "./" + fs::relative(snapshot_dir() + "/templates", fs::current_path()).string();
    auto again = TemplateLibrary::load(relative);
    REQUIRE(again.ok());
    CHECK(compare_with_expected(export_snapshots(*again.value()), first, "<first export>",
                                "the export is not deterministic or depends on the template path") == 0);
    for (const auto& [path, data] : first) {
        INFO(path);
        CHECK(data.find(CRTFORGE_SOURCE_DIR) == std::string::npos);
        CHECK(data.find("snapshots/templates") == std::string::npos);
    }
}

// CRTFORGE_UPDATE_SNAPSHOTS=1 (scripts/update-snapshots.sh) writes the .wgsl files instead of
// comparing, and removes those whose .frag is gone.
TEST_CASE("snapshot: WGSL emitter output for the raw GLSL cases equals tests/snapshots/wgsl", "[snapshot][wgsl]") {
    const std::string dir = snapshot_dir() + "/wgsl";
    const auto actual = emit_wgsl_cases(dir);
    std::map<std::string, std::string> expected;
    for (auto& [path, data] : read_tree(dir))
        if (path.size() > 5 && path.compare(path.size() - 5, 5, ".wgsl") == 0) expected.emplace(path, std::move(data));
    if (update_requested()) {
        // Only files whose case is gone; a case that failed to emit keeps its old files.
        for (const auto& [path, data] : expected)
            if (!fs::exists(dir + "/" + path.substr(0, path.find('.')) + ".frag")) fs::remove(dir + "/" + path);
        for (const auto& [path, data] : actual) {
            auto it = expected.find(path);
            if (it != expected.end() && it->second == data) continue;
            auto written = write_file_atomic(dir + "/" + path, data);
            INFO((written.ok() ? std::string() : written.error().str()));
            CHECK(written.ok());
        }
        WARN("CRTFORGE_UPDATE_SNAPSHOTS=1: " << actual.size() << " .wgsl files written to " << dir);
        return;
    }
    CHECK(compare_with_expected(actual, expected, kSnapshots + "/wgsl") == 0);
}
