// Static cost of a SPIR-V module, read from its instruction stream (see crtforge/validate/bench.hpp).
#include "crtforge/validate/bench.hpp"

#include <cstring>
#include <set>
#include <string>

namespace crtforge {

namespace {
constexpr uint32_t kOpExtInstImport = 11, kOpExtInst = 12, kOpFunction = 54;
constexpr uint32_t kOpImageSampleFirst = 87, kOpImageGatherLast = 97;  // sample, fetch, gather, dref gather
// GLSL.std.450: Sin .. Atanh (13-24), Atan2, Pow, Exp, Log, Exp2, Log2 (25-30).
bool is_transcendental(uint32_t op) { return op >= 13 && op <= 30; }
}  // namespace

ShaderCost spirv_cost(const std::vector<uint32_t>& words) {
    ShaderCost cost;
    if (words.size() < 5) return cost;
    std::set<uint32_t> glsl_sets;
    bool in_code = false;
    for (size_t at = 5; at < words.size();) {
        const uint32_t count = words[at] >> 16, op = words[at] & 0xFFFFu;
        if (count == 0 || at + count > words.size()) break;  // malformed: stop counting
        if (op == kOpExtInstImport && count >= 3) {
            const char* name = reinterpret_cast<const char*>(&words[at + 2]);
            if (std::string(name, strnlen(name, (count - 2) * 4)) == "GLSL.std.450") glsl_sets.insert(words[at + 1]);
        }
        in_code = in_code || op == kOpFunction;
        if (in_code) {
            ++cost.instructions;
            if (op >= kOpImageSampleFirst && op <= kOpImageGatherLast) ++cost.samples;
            if (op == kOpExtInst && count >= 5 && glsl_sets.count(words[at + 3]) && is_transcendental(words[at + 4])) ++cost.transcendentals;
        }
        at += count;
    }
    return cost;
}

}  // namespace crtforge
