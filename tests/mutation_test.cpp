// The mutation suite: every entry of tests/mutations.toml — a wrong constant in a shader, a
// changed preset or spec, a fault in the oracle — must make `validate` fail. Each runs on its
// preset's goldens of the listed inputs, on Vulkan (lavapipe): the judge's power, not the
// consumers', is what is measured here (the consumers agree with each other to the floor).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <toml++/toml.h>

#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/validate/validation.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
namespace fs = std::filesystem;

struct Mutation {
    std::string id, file, find, replace, reference, preset, caught_by;
    std::vector<std::string> inputs;
};

std::vector<Mutation> catalogue() {
    const std::string path = std::string(CRTFORGE_SOURCE_DIR) + "/tests/mutations.toml";
    toml::table root;
    try {
        root = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        FAIL(path << ": " << e.description());
    }
    std::vector<Mutation> out;
    const toml::array* list = root["mutation"].as_array();
    REQUIRE(list != nullptr);
    for (const toml::node& node : *list) {
        const toml::table& t = *node.as_table();
        Mutation m;
        m.id = t["id"].value_or(std::string());
        m.file = t["file"].value_or(std::string());
        m.find = t["find"].value_or(std::string());
        m.replace = t["replace"].value_or(std::string());
        m.reference = t["reference"].value_or(std::string());
        m.preset = t["preset"].value_or(std::string());
        m.caught_by = t["caught_by"].value_or(std::string());
        if (const toml::array* inputs = t["inputs"].as_array())
            for (const toml::node& i : *inputs) m.inputs.push_back(i.value_or(std::string()));
        out.push_back(std::move(m));
    }
    return out;
}

size_t occurrences(const std::string& text, const std::string& needle) {
    size_t count = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
    return count;
}

// Clears the oracle's fault whatever happens to the test.
struct FaultGuard {
    ~FaultGuard() { (void)set_reference_fault(""); }
};

// Runs one mutation: "caught", or what went wrong (a survivor, or a catalogue entry that no
// longer fits the templates).
std::string run_mutation(const Mutation& m, const std::string& shipped_goldens) {
    if (m.caught_by != "render" && m.caught_by != "stale") return "caught_by must be render or stale";
    if (m.inputs.empty()) return "no inputs";
    test::ScratchTemplates t;
    if (!m.file.empty()) {
        const std::string text = t.read(m.file);
        if (occurrences(text, m.find) != 1) return "'find' does not occur exactly once in " + m.file;
        t.write(m.file, text.substr(0, text.find(m.find)) + m.replace + text.substr(text.find(m.find) + m.find.size()));
    }
    auto lib = t.load();
    if (!lib.ok()) return "the mutated templates do not load: " + lib.error().str();
    // The stage-isolation presets too: a form no shipped preset uses is caught on its own.
    if (auto s = lib.value()->add_test_presets(shipped_goldens + "/stages"); !s.ok()) return s.error().str();
    FaultGuard guard;
    if (auto s = set_reference_fault(m.reference); !s.ok()) return s.error().str();

    test::TempDir goldens;
    ValidateRequest request;
    request.presets = {m.preset};
    request.targets = {TargetId::Spirv};
    request.inputs = m.inputs;
    if (m.caught_by == "stale") {
        request.golden_dir = shipped_goldens;
    } else {
        // Goldens as `golden update` makes them for the mutated templates (or by the faulty oracle).
        fs::copy_file(shipped_goldens + "/plan.toml", goldens / "plan.toml");
        for (const std::string& input : m.inputs) {
            auto made = update_goldens(*lib.value(), goldens.path(), m.preset + "." + input + ".");
            if (!made.ok()) return "golden update failed: " + made.error().str();
        }
        request.golden_dir = goldens.path();
    }
    auto report = run_validation(*lib.value(), request, Cache());
    if (!report.ok()) return "validate failed to run: " + report.error().str();
    for (const CheckResult& c : report.value().checks) {
        if (c.passed || c.golden_id.empty()) continue;
        const bool stale = c.message.find("stale") != std::string::npos;
        if (stale == (m.caught_by == "stale")) return "caught";
    }
    return "survived: every render check passed" + std::string(m.caught_by == "stale" ? " (no golden was found stale)" : "");
}

}  // namespace

TEST_CASE("the mutation catalogue: validate catches every mutation", "[validate][mutation]") {
    const std::vector<Mutation> mutations = catalogue();
    CHECK(mutations.size() >= 40);
    const std::string shipped_goldens = std::string(CRTFORGE_SOURCE_DIR) + "/golden";
    size_t caught = 0;
    for (const Mutation& m : mutations) {
        const std::string outcome = run_mutation(m, shipped_goldens);
        INFO("mutation " << m.id << ": " << outcome);
        CHECK(outcome == "caught");
        if (outcome == "caught") ++caught;
    }
    WARN("mutation catalogue: " << caught << " of " << mutations.size() << " caught");
}
