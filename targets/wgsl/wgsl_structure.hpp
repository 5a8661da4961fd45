// Step 1 of printing a SPIR-V function as WGSL: its control-flow graph, read through the merge
// instructions, as a tree of structured statements (if/else, switch, loop with continuing and
// `break if`, break, continue, return, discard), with the phi copies each edge carries. No WGSL
// text is made here; wgsl_analysis walks this tree for scopes and uses, then wgsl_printer prints it.
#pragma once

#include <cstdint>
#include <vector>

#include "targets/wgsl/spirv_module.hpp"

namespace crtforge::wgsl {

struct Statement;
using Body = std::vector<Statement>;

enum class StatementKind {
    Block,      // the instructions of SPIR-V block `block` (not its terminator)
    PhiCopies,  // the phi assignments of the edge block -> target, as one parallel copy
    If,         // if (value) { then_body } else { else_body }; either arm may print empty
    Switch,     // switch (value) { cases }
    Loop,       // loop { header body continuing { continuing } }
    Break,
    Continue,
    BreakIf,    // the back edge at the end of a continuing: `break if value` (or `!value`)
    Return,     // return value (0: none)
    Discard,    // discard, then the function ends on this path
};

struct SwitchCase {
    std::vector<uint32_t> literals;
    bool is_default = false;
    Body body;
};

struct Statement {
    StatementKind kind = StatementKind::Block;
    uint32_t block = 0;      // Block: the block; PhiCopies: the edge's source; If/Switch/BreakIf/Return: the
                             // block whose terminator it comes from
    uint32_t target = 0;     // PhiCopies: the edge's target block
    uint32_t value = 0;      // If / BreakIf: the condition; Switch: the selector; Return: the value (0: none)
    // If: the branch leaves the construct on one way or both (break, continue, or the end of the
    // region), rather than choosing between two arms of a selection.
    bool exits = false;
    // If: both ways leave the construct. BreakIf: true when the condition leaves the loop
    // (`break if c`, else `break if !c`).
    bool flag = false;
    Body then_body, else_body;   // If arms; BreakIf: the copies of the back edge / of leaving the loop
    Body header, body, continuing;  // Loop: the header block's part, the body, the continue construct
    std::vector<SwitchCase> cases;  // Switch, in first-appearance order; the default joins its target's case
};

// The phi assignments an edge carries: (phi, source) for every phi of `to` with an operand from `from`.
struct PhiCopy {
    uint32_t phi = 0, source = 0;
};
std::vector<PhiCopy> edge_copies(const Function& function, uint32_t from, uint32_t to);

// Whether printing the copies writes anything: a copy to another value, or the snapshot a parallel
// copy takes of a phi that is also a source.
bool copies_print(const std::vector<PhiCopy>& copies);

// The function's body. Errors (EmitError) name the construct SPIR-V uses that has no structured
// WGSL form, e.g. a conditional break nested inside a continue construct.
Body structure_function(const Function& function);

}  // namespace crtforge::wgsl
