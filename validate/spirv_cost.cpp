// Static cost of a SPIR-V module, read with the WGSL emitter's SPIR-V reader (see
// crtforge/validate/bench.hpp).
#include "crtforge/validate/bench.hpp"

#include <spirv_cross/GLSL.std.450.h>

#include "targets/wgsl/spirv_module.hpp"

namespace crtforge {

namespace {

bool is_texture_read(spv::Op op) { return op >= spv::OpImageSampleImplicitLod && op <= spv::OpImageDrefGather; }

// GLSL.std.450's trigonometric, hyperbolic, exponential and logarithmic functions and pow (not
// sqrt, which GPUs run at the cost of a multiply or two).
bool is_transcendental(uint32_t instruction) { return instruction >= GLSLstd450Sin && instruction <= GLSLstd450Log2; }

}  // namespace

ShaderCost spirv_cost(const std::vector<uint32_t>& words) {
    ShaderCost cost;
    auto module = wgsl::parse_spirv(words);
    if (!module.ok()) return cost;  // not a module crtforge made: nothing to count
    const auto& imports = module.value().ext_imports;
    auto count = [&](const wgsl::Instruction& i) {
        ++cost.instructions;
        if (is_texture_read(i.op)) ++cost.samples;
        if (i.op == spv::OpExtInst) {
            auto set = imports.find(i.operand(0));
            if (set != imports.end() && set->second == "GLSL.std.450" && is_transcendental(i.operand(1))) ++cost.transcendentals;
        }
    };
    for (const wgsl::Function& f : module.value().functions) {
        for (const wgsl::Instruction& v : f.variables) count(v);
        for (const wgsl::Block& b : f.blocks) {
            for (const wgsl::Instruction& i : b.phis) count(i);
            for (const wgsl::Instruction& i : b.body) count(i);
            if (b.merge) count(*b.merge);
            count(b.terminator);
        }
    }
    return cost;
}

}  // namespace crtforge
