// Step 2 of printing a SPIR-V function as WGSL: what the printer must know before it writes a line.
// From the function and its statement tree (wgsl_structure.hpp) it finds, for every value, how
// often and where it is read, which values are read outside the WGSL scope that defines them (and
// so must become function-scope variables), and where control flow is still uniform (derivatives
// and implicit-LOD samples need it).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "targets/wgsl/spirv_module.hpp"
#include "targets/wgsl/wgsl_structure.hpp"

namespace crtforge::wgsl {

struct FunctionAnalysis {
    std::map<uint32_t, uint32_t> types;  // value id -> SPIR-V type id
    // Reads of each value, counting twice where the WGSL spells an operand twice (mod, shuffles...).
    std::map<uint32_t, int> uses;
    std::map<uint32_t, std::set<uint32_t>> use_blocks;  // blocks reading each value; a phi operand is read on its edge's source
    // Values copied into a phi on an edge that carries several copies: they must be named, so the
    // copies read values, never each other's half-written targets.
    std::set<uint32_t> phi_sources;
    // Values read in a scope outside the one that defines them: declared as function-scope `var`s
    // up front and assigned where SPIR-V defines them.
    std::set<uint32_t> hoisted;
    // Block -> control flow there is uniform: no enclosing if/switch/loop and no earlier early exit.
    std::map<uint32_t, bool> uniform_flow;

    int use_count(uint32_t id) const;
    // Read exactly once, in `block` itself, and not by a parallel copy: it may be inlined there.
    bool local_single_use(uint32_t id, uint32_t block) const;
    bool is_uniform(uint32_t block) const;
    uint32_t type_of(uint32_t id, const SpirvModule& module) const;  // 0 if unknown
};

FunctionAnalysis analyse_function(const SpirvModule& module, const Function& function, const Body& body);

// Operands of an instruction that are value ids (as opposed to literals).
std::vector<uint32_t> value_operands(const Instruction& inst);

}  // namespace crtforge::wgsl
