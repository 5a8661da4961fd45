// The fuzz targets' committed inputs (docs/fuzzing.md), replayed through the same bodies the
// libFuzzer executables run: fuzz/corpus/<target>/ (the seeds) and fuzz/regressions/<target>/
// (every input that once crashed a target, kept as its regression test). This build has no
// sanitizers, so it catches crashes and escaping exceptions; scripts/fuzz.sh replays the same
// files under AddressSanitizer and UndefinedBehaviorSanitizer.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fuzz/fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;

using Body = int (*)(const uint8_t*, size_t);

std::vector<fs::path> files_in(const fs::path& dir) {
    std::vector<fs::path> out;
    if (!fs::is_directory(dir)) return out;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file()) out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

void replay(const std::string& target, Body body) {
    const fs::path fuzz = fs::path(CRTFORGE_SOURCE_DIR) / "fuzz";
    const std::vector<fs::path> corpus = files_in(fuzz / "corpus" / target);
    REQUIRE_FALSE(corpus.empty());  // a target's seeds went missing
    std::vector<fs::path> inputs = corpus;
    const std::vector<fs::path> regressions = files_in(fuzz / "regressions" / target);
    inputs.insert(inputs.end(), regressions.begin(), regressions.end());
    for (const fs::path& path : inputs) {
        std::ifstream in(path, std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        INFO(path.string());
        CHECK_NOTHROW(body(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    }
}

}  // namespace

TEST_CASE("fuzz inputs of stage_spec replay cleanly", "[fuzz]") { replay("stage_spec", crtforge_fuzz_stage_spec); }
TEST_CASE("fuzz inputs of preset replay cleanly", "[fuzz]") { replay("preset", crtforge_fuzz_preset); }
TEST_CASE("fuzz inputs of wgsl_emitter replay cleanly", "[fuzz]") { replay("wgsl_emitter", crtforge_fuzz_wgsl_emitter); }
TEST_CASE("fuzz inputs of wgsl_valid replay cleanly", "[fuzz]") { replay("wgsl_valid", crtforge_fuzz_wgsl_valid); }
TEST_CASE("fuzz inputs of image_reader replay cleanly", "[fuzz]") { replay("image_reader", crtforge_fuzz_image_reader); }
