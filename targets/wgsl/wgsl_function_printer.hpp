// The WGSL printer's class (step 3 of printing a SPIR-V function, see wgsl_printer.cpp): shared by
// wgsl_printer.cpp (statements, values, the core instructions) and wgsl_printer_builtins.cpp (the
// GLSL.std.450 extended instructions and the image instructions). Internal to targets/wgsl/.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>

#include "targets/wgsl/wgsl_analysis.hpp"
#include "targets/wgsl/wgsl_context.hpp"
#include "targets/wgsl/wgsl_names.hpp"
#include "targets/wgsl/wgsl_structure.hpp"

namespace crtforge::wgsl {

class FunctionPrinter {
public:
    FunctionPrinter(ModuleEmitter& module, const Function& function, bool is_entry, std::string entry_return,
                    NameScope& names)
        : mod_(module), m_(module.m), f_(function), is_entry_(is_entry), entry_return_(std::move(entry_return)),
          names_(names) {}

    std::string run();

private:
    // ---- statements ----
    void print(const Body& body);
    void statement(const Statement& s);
    void if_statement(const Statement& s);
    void switch_statement(const Statement& s);
    void loop_statement(const Statement& s);
    void break_if(const Statement& s);
    void phi_copies(uint32_t from, uint32_t to);
    void return_statement(uint32_t value);
    // The text `body` prints one level in, without printing it.
    std::string nested(const Body& body);
    void line(const std::string& text) { out_ += std::string(static_cast<size_t>(indent_) * 2, ' ') + text + "\n"; }

    // ---- values ----
    void instruction(const Instruction& inst);
    void ext_instruction(const Instruction& inst);
    // The name of the module helper that inverts an n x n f32 matrix (declared on first use).
    std::string matrix_inverse_helper(uint32_t n);
    void image_instruction(const Instruction& inst);
    Expr value(uint32_t id);
    std::string ref(uint32_t pointer_id);
    std::string typed(uint32_t id, uint32_t wanted_type);  // operand as `wanted_type` (bitcast for signedness)
    // The one path every value-producing instruction takes: a value hoisted to a function-scope
    // variable is assigned; a pure value read once, nearby, is inlined when short (always, with
    // `always_inline`, for reads of immutable data); a dead pure value is dropped; a value with a
    // side effect that nobody reads is kept as `_ = ...`; anything else gets a `let`.
    void define(const Instruction& inst, const Expr& expr, bool pure, bool always_inline = false);
    // The same for a value built in steps: `init`, then `update(name)` statements that modify it
    // (composite inserts). It lives in a `var` (or its hoisted variable); dead, it is dropped.
    void define_built(const Instruction& inst, const std::string& init,
                      const std::function<std::string(const std::string&)>& update);
    std::string temp_name(uint32_t id);
    // ".x", ".member", "[2]" for the literal indices operands[first..] into a value of `type`.
    std::string composite_path(uint32_t type, const std::vector<uint32_t>& operands, size_t first);
    const Type& pointer_type(uint32_t pointer_id) const;
    uint32_t type_of(uint32_t id) const { return analysis_.type_of(id, m_); }
    void needs_uniform_flow() {
        if (!analysis_.is_uniform(current_block_)) mod_.needs_derivative_uniformity_off = true;
    }

    ModuleEmitter& mod_;
    const SpirvModule& m_;
    const Function& f_;
    bool is_entry_;
    std::string entry_return_;
    NameScope& names_;
    FunctionAnalysis analysis_;

    std::map<uint32_t, Expr> values_;
    std::map<uint32_t, std::string> refs_;
    std::map<uint32_t, std::pair<std::string, std::string>> images_;  // (texture, sampler)
    std::map<uint32_t, uint32_t> pointer_types_;                        // local pointer id -> pointer type
    std::map<uint32_t, std::string> phi_vars_;
    std::map<uint32_t, std::string> pointer_params_;  // ptr parameter id -> its name
    std::string out_;
    int indent_ = 1;
    uint32_t current_block_ = 0;
};

}  // namespace crtforge::wgsl
