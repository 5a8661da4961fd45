// A SPIR-V module read into the pieces the WGSL emitter walks: types, constants, global variables,
// names and decorations by id, and functions as lists of basic blocks. Debug OpLine instructions
// are kept on the instruction they precede, so an error can name the template line.
//
// Only the logical-addressing shader subset glslang and spirv-opt produce is modelled; anything
// else is left for the emitter to reject by opcode.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <spirv_cross/spirv.hpp>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"

namespace crtforge::wgsl {

struct SourceLine {
    std::string file;
    int line = 0;
};

struct Instruction {
    spv::Op op = spv::OpNop;
    uint32_t type = 0;              // result type id, 0 if none
    uint32_t result = 0;            // result id, 0 if none
    std::vector<uint32_t> operands; // the words after the result type and id
    SourceLine line;                // from the closest preceding OpLine in the function, if any

    uint32_t operand(size_t i) const { return i < operands.size() ? operands[i] : 0; }
};

struct Type {
    spv::Op op = spv::OpNop;        // OpTypeFloat, OpTypeVector, OpTypePointer, ...
    uint32_t width = 0;             // scalars
    bool is_signed = false;         // OpTypeInt
    uint32_t element = 0;           // vector/matrix/array element, pointer pointee, image sampled type
    uint32_t count = 0;             // vector/matrix columns; array length (resolved constant)
    std::vector<uint32_t> members;  // struct members; function: return type then params
    spv::StorageClass storage = spv::StorageClassMax;  // pointers
    spv::Dim dim = spv::DimMax;     // images
    bool depth = false, arrayed = false, multisampled = false;
};

struct Constant {
    uint32_t type = 0;
    spv::Op op = spv::OpNop;         // OpConstant, OpConstantComposite, OpConstantTrue/False/Null
    std::vector<uint32_t> words;     // scalar bits or constituent ids
};

struct Decorations {
    std::optional<uint32_t> binding, set, location, offset, array_stride;
    std::optional<spv::BuiltIn> builtin;
    bool block = false, flat = false, no_perspective = false, centroid = false, sample = false;
};

struct Block {
    uint32_t label = 0;
    std::vector<Instruction> phis;
    std::vector<Instruction> body;
    std::optional<Instruction> merge;  // OpSelectionMerge / OpLoopMerge
    Instruction terminator;
};

struct Function {
    uint32_t id = 0, return_type = 0, function_type = 0;
    std::vector<Instruction> params;      // OpFunctionParameter
    std::vector<Instruction> variables;   // OpVariable (Function storage) of the first block
    std::vector<Block> blocks;            // in module order; blocks[0] is the entry
    std::map<uint32_t, size_t> block_index;
    const Block& block(uint32_t label) const { return blocks.at(block_index.at(label)); }
};

struct EntryPoint {
    spv::ExecutionModel model = spv::ExecutionModelMax;
    uint32_t function = 0;
    std::string name;
    std::vector<uint32_t> interface;
};

struct SpirvModule {
    std::map<uint32_t, Type> types;
    std::map<uint32_t, Constant> constants;
    std::map<uint32_t, Instruction> globals;       // module-scope OpVariable
    std::map<uint32_t, std::string> names;
    std::map<std::pair<uint32_t, uint32_t>, std::string> member_names;
    std::map<uint32_t, Decorations> decorations;
    std::map<std::pair<uint32_t, uint32_t>, Decorations> member_decorations;
    std::set<uint32_t> relaxed_precision;
    std::map<uint32_t, std::string> ext_imports;   // id -> "GLSL.std.450"
    std::vector<Function> functions;
    std::vector<EntryPoint> entry_points;
    std::set<spv::ExecutionMode> execution_modes;

    const Type& type(uint32_t id) const;
    const Function* function(uint32_t id) const;
    std::string name(uint32_t id) const;  // "" when unnamed
};

// A SPIR-V operand word as an enum of spirv.hpp or GLSL.std.450.h. A word beyond the enum's range
// (malformed input) is undefined behaviour as that enum, so it becomes `max`, which names nothing
// the emitter supports.
template <typename Enum>
Enum operand_enum(uint32_t word, Enum max) {
    return word <= static_cast<uint32_t>(max) ? static_cast<Enum>(word) : max;
}

// Reads a module. Malformed binaries (bad magic, truncated instructions, an instruction outside
// the places the SPIR-V layout allows) are Validation errors: the generator produced the module.
Result<SpirvModule> parse_spirv(const SpirvBinary& words);

// "OpIAddCarry" for an opcode number.
std::string opcode_name(spv::Op op);

}  // namespace crtforge::wgsl
