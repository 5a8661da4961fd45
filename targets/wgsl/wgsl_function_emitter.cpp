// One SPIR-V function as WGSL: the structured control flow rebuilt from merge instructions
// (if/else, switch, loop with continuing and `break if`), phis as function-scope variables
// assigned on each incoming edge, SSA values as `let`s (or inlined when used once, nearby and
// free of side effects), and every instruction mapped with GLSL's semantics kept where WGSL's
// differ (see targets/wgsl/README.md).
#include <algorithm>
#include <cstring>
#include <functional>
#include <optional>

#include <fmt/format.h>
#include <spirv_cross/GLSL.std.450.h>

#include "targets/wgsl/wgsl_context.hpp"
#include "targets/wgsl/wgsl_names.hpp"

namespace crtforge::wgsl {

namespace {

constexpr size_t kInlineLimit = 64;  // longer single-use expressions still get their own `let`

struct LoopContext {
    uint32_t header = 0, merge = 0, cont = 0;
    bool in_continuing = false;
    int continuing_scope = -1;
};

const char* swizzle_letter(uint32_t i) {
    static const char* letters[] = {"x", "y", "z", "w"};
    return i < 4 ? letters[i] : "?";
}

// Operands that are value ids (as opposed to literals), per opcode: {first, count} ranges.
std::vector<uint32_t> value_operands(const Instruction& inst) {
    const auto& o = inst.operands;
    switch (inst.op) {
        case spv::OpExtInst: return {o.begin() + std::min<size_t>(2, o.size()), o.end()};
        case spv::OpCompositeExtract: return {o.at(0)};
        case spv::OpCompositeInsert: return {o.at(0), o.at(1)};
        case spv::OpVectorShuffle: return {o.at(0), o.at(1)};
        case spv::OpLoad: return {o.at(0)};
        case spv::OpStore: return {o.at(0), o.at(1)};
        case spv::OpImageSampleImplicitLod: case spv::OpImageSampleExplicitLod: case spv::OpImageFetch: {
            std::vector<uint32_t> ids = {o.at(0), o.at(1)};
            for (size_t i = 3; i < o.size(); ++i) ids.push_back(o[i]);  // after the image-operands mask
            return ids;
        }
        case spv::OpImageQuerySizeLod: case spv::OpImageQuerySize: case spv::OpImageQueryLevels:
            return {o.begin(), o.end()};
        case spv::OpFunctionCall: return {o.begin() + std::min<size_t>(1, o.size()), o.end()};
        case spv::OpVariable: return o.size() > 1 ? std::vector<uint32_t>{o[1]} : std::vector<uint32_t>{};
        case spv::OpBranchConditional: return {o.at(0)};
        case spv::OpSwitch: return {o.at(0)};
        case spv::OpReturnValue: return {o.at(0)};
        case spv::OpBranch: case spv::OpReturn: case spv::OpKill: case spv::OpUnreachable:
        case spv::OpTerminateInvocation: case spv::OpSelectionMerge: case spv::OpLoopMerge:
            return {};
        default: return {o.begin(), o.end()};
    }
}

// Ops whose WGSL spells an operand twice: a non-trivial operand must be a named value.
bool duplicates_operands(const Instruction& inst) {
    switch (inst.op) {
        case spv::OpFMod: case spv::OpSMod: case spv::OpFOrdNotEqual: case spv::OpFUnordEqual:
        case spv::OpVectorShuffle:
            return true;
        case spv::OpExtInst: {
            const auto e = static_cast<GLSLstd450>(inst.operand(1));
            return e == GLSLstd450SmoothStep || e == GLSLstd450FClamp || e == GLSLstd450NMin ||
                   e == GLSLstd450NMax || e == GLSLstd450NClamp;
        }
        default: return false;
    }
}

class FunctionPrinter {
public:
    FunctionPrinter(ModuleEmitter& module, const Function& function, bool is_entry, std::string entry_return,
                    std::set<std::string>& names)
        : mod_(module), m_(module.m), f_(function), is_entry_(is_entry), entry_return_(std::move(entry_return)),
          names_(names) {}

    std::string run();

private:
    // ---- analysis ----
    void count_uses();
    void walk(bool dry_run);

    // ---- structured control flow ----
    void region(uint32_t start, uint32_t stop, const LoopContext* loop);
    void loop_construct(uint32_t header);
    // One arm of an if or switch, in its own scope one level in: the region from `target` to the
    // construct's merge, or just the phi copies when the arm goes straight to the merge.
    void arm(uint32_t from, uint32_t target, uint32_t merge, const LoopContext* loop, int parent_scope) {
        open_scope();
        ++indent_;
        if (target == merge) phi_copies(from, merge);
        else region(target, merge, loop);
        --indent_;
        close_scope(parent_scope);
    }
    void conditional_exit(const Block& b, uint32_t stop, const LoopContext* loop, uint32_t& next, bool& done);
    bool is_exit(uint32_t target, uint32_t stop, const LoopContext* loop) const;
    void exit_statement(uint32_t from, uint32_t target, uint32_t stop, const LoopContext* loop);
    void phi_copies(uint32_t from, uint32_t to);
    void return_statement(const Instruction& term);
    std::string capture(const std::function<void()>& body);
    void open_scope() { scope_parent_.push_back(scope_); scope_ = static_cast<int>(scope_parent_.size()) - 1; }
    void close_scope(int saved) { scope_ = saved; }

    // ---- instructions ----
    void block_instructions(const Block& b);
    void instruction(const Instruction& inst);
    void ext_instruction(const Instruction& inst);
    void image_instruction(const Instruction& inst);
    Expr value(uint32_t id);
    std::string ref(uint32_t pointer_id);
    std::string typed(uint32_t id, uint32_t wanted_type);  // operand as `wanted_type` (bitcast for signedness)
    // Gives an instruction's result its WGSL: inlined into its single nearby use when pure and short
    // (or always, for `always_inline` reads of immutable data), else a `let` (hoisted: a var).
    void define(const Instruction& inst, const std::string& text, bool pure, bool always_inline = false);
    void line(const std::string& text) {
        if (!dry_run_) out_ += std::string(indent_ * 2, ' ') + text + "\n";
    }
    std::string temp_name(uint32_t id);
    // ".x", ".member", "[2]" for the literal indices operands[first..] into a value of `type`.
    std::string composite_path(uint32_t type, const std::vector<uint32_t>& operands, size_t first);
    bool flow_uniform() const { return nesting_ == 0 && !early_exit_; }
    const Type& pointer_type(uint32_t pointer_id) const;

    ModuleEmitter& mod_;
    const SpirvModule& m_;
    const Function& f_;
    bool is_entry_;
    std::string entry_return_;
    std::set<std::string>& names_;

    uint32_t type_of(uint32_t id) const;  // the SPIR-V type of a value id, 0 if unknown

    std::map<uint32_t, uint32_t> types_;  // value id -> type id
    std::map<uint32_t, int> uses_;
    std::map<uint32_t, std::set<uint32_t>> use_blocks_;
    std::map<uint32_t, uint32_t> def_block_;
    std::set<uint32_t> phi_sources_;
    std::map<uint32_t, std::set<int>> use_scopes_;
    std::map<uint32_t, int> block_scope_;
    std::vector<int> scope_parent_;
    int scope_ = -1;
    std::set<uint32_t> hoisted_;

    std::map<uint32_t, Expr> values_;
    std::map<uint32_t, std::string> refs_;
    std::map<uint32_t, std::pair<std::string, std::string>> images_;  // (texture, sampler)
    std::map<uint32_t, uint32_t> pointer_types_;                        // local pointer id -> pointer type
    std::map<uint32_t, std::string> phi_vars_;
    std::map<uint32_t, std::string> pointer_params_;  // ptr parameter id -> its name
    std::string out_;
    int indent_ = 1;
    int nesting_ = 0;
    bool early_exit_ = false;
    bool dry_run_ = false;
    uint32_t current_block_ = 0;
};

std::string FunctionPrinter::capture(const std::function<void()>& body) {
    std::string saved;
    std::swap(saved, out_);
    body();
    std::swap(saved, out_);
    return saved;
}

// The OpTypePointer of a pointer value: a local (variable, access chain, parameter) or a global.
const Type& FunctionPrinter::pointer_type(uint32_t pointer_id) const {
    if (auto it = pointer_types_.find(pointer_id); it != pointer_types_.end()) return m_.type(it->second);
    if (auto g = m_.globals.find(pointer_id); g != m_.globals.end()) return m_.type(g->second.type);
    return m_.type(0);
}

uint32_t FunctionPrinter::type_of(uint32_t id) const {
    if (auto it = types_.find(id); it != types_.end()) return it->second;
    if (auto c = m_.constants.find(id); c != m_.constants.end()) return c->second.type;
    return 0;
}

void FunctionPrinter::count_uses() {
    for (const Instruction& p : f_.params) types_[p.result] = p.type;
    auto note = [&](const Instruction& inst, uint32_t block) {
        if (inst.result && inst.type) types_[inst.result] = inst.type;
        const int weight = duplicates_operands(inst) ? 2 : 1;
        for (uint32_t id : value_operands(inst)) {
            uses_[id] += weight;
            use_blocks_[id].insert(block);
        }
        if (inst.result) def_block_[inst.result] = block;
    };
    for (const Block& b : f_.blocks) {
        for (const Instruction& phi : b.phis) {
            def_block_[phi.result] = b.label;
            types_[phi.result] = phi.type;
            for (size_t i = 0; i + 1 < phi.operands.size(); i += 2) {
                uses_[phi.operands[i]] += 1;
                // A value copied into a phi on an edge that carries several copies must be named:
                // the copies then read values, never each other's targets half-written.
                if (b.phis.size() > 1) phi_sources_.insert(phi.operands[i]);
                use_blocks_[phi.operands[i]].insert(phi.operands[i + 1]);
            }
        }
        for (const Instruction& inst : b.body) note(inst, b.label);
        note(b.terminator, b.label);
    }
}

// ---------------------------------------------------------------------------------------------
// Structured control flow

bool FunctionPrinter::is_exit(uint32_t target, uint32_t stop, const LoopContext* loop) const {
    if (target == stop) return true;
    if (!loop) return false;
    if (target == loop->merge) return true;
    if (!loop->in_continuing && target == loop->cont) return true;
    if (loop->in_continuing && target == loop->header) return true;
    return false;
}

void FunctionPrinter::exit_statement(uint32_t from, uint32_t target, uint32_t stop, const LoopContext* loop) {
    phi_copies(from, target);
    if (loop && target == loop->merge && target != stop) line("break;");
    else if (loop && !loop->in_continuing && target == loop->cont && target != stop) line("continue;");
}

void FunctionPrinter::phi_copies(uint32_t from, uint32_t to) {
    auto it = f_.block_index.find(to);
    if (it == f_.block_index.end()) return;
    const Block& target = f_.blocks[it->second];
    std::vector<std::pair<uint32_t, uint32_t>> copies;  // (phi, source)
    for (const Instruction& phi : target.phis)
        for (size_t i = 0; i + 1 < phi.operands.size(); i += 2)
            if (phi.operands[i + 1] == from) copies.push_back({phi.result, phi.operands[i]});
    if (dry_run_) {
        for (auto& [phi, source] : copies) use_scopes_[source].insert(scope_);
        return;
    }
    // Parallel copy: a source that is itself a phi of this block is read before any is written.
    std::set<uint32_t> targets;
    for (auto& c : copies) targets.insert(c.first);
    std::map<uint32_t, std::string> snapshot;
    if (copies.size() > 1)
        for (auto& [phi, source] : copies)
            if (targets.count(source) && !snapshot.count(source)) {
                const std::string name = unique_identifier(phi_vars_.at(source) + "_prev", names_);
                line("let " + name + " = " + phi_vars_.at(source) + ";");
                snapshot[source] = name;
            }
    for (auto& [phi, source] : copies) {
        if (phi == source) continue;
        const std::string text = snapshot.count(source) ? snapshot[source] : value(source).text;
        line(phi_vars_.at(phi) + " = " + text + ";");
    }
}

void FunctionPrinter::return_statement(const Instruction& term) {
    if (dry_run_) {
        if (term.op == spv::OpReturnValue) use_scopes_[term.operand(0)].insert(scope_);
        if (nesting_ > 0) early_exit_ = true;
        return;
    }
    if (term.op == spv::OpReturnValue) {
        line("return " + value(term.operand(0)).text + ";");
    } else if (is_entry_ && !entry_return_.empty()) {
        line("return " + entry_return_ + ";");
    } else if (!is_entry_ && m_.type(f_.return_type).op != spv::OpTypeVoid) {
        line("return " + mod_.type_name(f_.return_type) + "();");
    } else {
        line("return;");
    }
    if (nesting_ > 0) early_exit_ = true;
}

void FunctionPrinter::region(uint32_t start, uint32_t stop, const LoopContext* loop) {
    uint32_t b = start;
    while (true) {
        if (b == stop) return;
        if (loop && b == loop->merge) { line("break;"); return; }
        if (loop && !loop->in_continuing && b == loop->cont) { line("continue;"); return; }
        if (loop && loop->in_continuing && b == loop->header) return;
        auto it = f_.block_index.find(b);
        if (it == f_.block_index.end()) fail(fmt::format("branch to a missing block %{}", b));
        const Block& block = f_.blocks[it->second];

        if (block.merge && block.merge->op == spv::OpLoopMerge && !(loop && loop->header == b)) {
            loop_construct(b);
            b = block.merge->operand(0);
            continue;
        }
        block_scope_[b] = scope_;
        current_block_ = b;
        block_instructions(block);
        const Instruction& term = block.terminator;
        switch (term.op) {
            case spv::OpBranch: {
                const uint32_t target = term.operand(0);
                phi_copies(b, target);
                b = target;
                continue;
            }
            case spv::OpBranchConditional: {
                const uint32_t t = term.operand(1), f = term.operand(2);
                if (t == f) {
                    phi_copies(b, t);
                    b = t;
                    continue;
                }
                if (block.merge && block.merge->op == spv::OpSelectionMerge) {
                    const uint32_t merge = block.merge->operand(0);
                    const std::string cond = dry_run_ ? std::string() : value(term.operand(0)).text;
                    const std::string cond_operand = dry_run_ ? std::string() : value(term.operand(0)).operand();
                    const int saved = scope_;
                    ++nesting_;
                    auto branch = [&](uint32_t target) { return capture([&] { arm(b, target, merge, loop, saved); }); };
                    const std::string then_text = branch(t), else_text = branch(f);
                    --nesting_;
                    if (then_text.empty() && !else_text.empty()) {
                        line("if (!" + cond_operand + ") {");
                        out_ += else_text;
                        line("}");
                    } else if (!then_text.empty()) {
                        line("if (" + cond + ") {");
                        out_ += then_text;
                        if (!else_text.empty()) {
                            line("} else {");
                            out_ += else_text;
                        }
                        line("}");
                    }
                    b = merge;
                    continue;
                }
                uint32_t next = 0;
                bool done = false;
                conditional_exit(block, stop, loop, next, done);
                if (done) return;
                b = next;
                continue;
            }
            case spv::OpSwitch: {
                if (!block.merge || block.merge->op != spv::OpSelectionMerge) unsupported(term, "a switch without a merge block");
                const uint32_t merge = block.merge->operand(0);
                // Cases grouped by target, in first-appearance order; the default joins its target's group.
                std::vector<std::pair<uint32_t, std::vector<uint32_t>>> groups;
                const uint32_t default_target = term.operand(1);
                for (size_t i = 2; i + 1 < term.operands.size(); i += 2) {
                    const uint32_t literal = term.operands[i], target = term.operands[i + 1];
                    auto g = std::find_if(groups.begin(), groups.end(), [&](auto& x) { return x.first == target; });
                    if (g == groups.end()) groups.push_back({target, {literal}});
                    else g->second.push_back(literal);
                }
                const Expr selector = dry_run_ ? Expr{} : value(term.operand(0));
                const bool is_signed = m_.type(type_of(term.operand(0))).is_signed;
                line("switch (" + selector.text + ") {");
                const int saved = scope_;
                ++nesting_;
                ++indent_;
                bool default_done = false;
                auto emit_case = [&](const std::string& head, uint32_t target) {
                    line(head + " {");
                    arm(b, target, merge, loop, saved);
                    line("}");
                };
                for (auto& [target, literals] : groups) {
                    std::string head = "case ";
                    for (size_t i = 0; i < literals.size(); ++i)
                        head += (i ? ", " : "") + (is_signed ? i32_literal(static_cast<int32_t>(literals[i])) : u32_literal(literals[i]));
                    if (target == default_target) {
                        head += ", default";
                        default_done = true;
                    }
                    emit_case(head + ":", target);
                }
                if (!default_done) emit_case("default:", default_target);
                --indent_;
                --nesting_;
                line("}");
                b = merge;
                continue;
            }
            case spv::OpReturn:
            case spv::OpReturnValue:
                return_statement(term);
                return;
            case spv::OpKill:
            case spv::OpTerminateInvocation:
                line("discard;");
                // WGSL's discard demotes the invocation and carries on: end the path as SPIR-V does.
                if (m_.type(f_.return_type).op != spv::OpTypeVoid || (is_entry_ && !entry_return_.empty())) {
                    Instruction plain_return;
                    plain_return.op = spv::OpReturn;
                    return_statement(plain_return);
                }
                early_exit_ = true;
                return;
            case spv::OpUnreachable:
                return;
            default:
                unsupported(term);
        }
    }
}

// A conditional branch without a merge instruction: each target either leaves the construct
// (break, continue, the back edge) or continues the current region.
void FunctionPrinter::conditional_exit(const Block& block, uint32_t stop, const LoopContext* loop, uint32_t& next,
                                       bool& done) {
    const Instruction& term = block.terminator;
    const uint32_t b = block.label, t = term.operand(1), f = term.operand(2);
    const bool t_exit = is_exit(t, stop, loop), f_exit = is_exit(f, stop, loop);

    // The back edge of a loop at the top level of its continuing block: `break if`.
    if (loop && loop->in_continuing && scope_ == loop->continuing_scope &&
        ((t == loop->header && f == loop->merge) || (t == loop->merge && f == loop->header))) {
        Expr cond = dry_run_ ? Expr{} : value(term.operand(0));
        const std::string to_header = capture([&] { ++indent_; phi_copies(b, loop->header); --indent_; });
        const std::string to_merge = capture([&] { ++indent_; phi_copies(b, loop->merge); --indent_; });
        if (!to_header.empty() || !to_merge.empty()) {
            if (!cond.atom) {
                const std::string name = temp_name(term.operand(0));
                line("let " + name + " = " + cond.text + ";");
                cond = {name, true};
            }
            line("if (" + cond.text + ") {");
            out_ += t == loop->header ? to_header : to_merge;
            line("} else {");
            out_ += t == loop->header ? to_merge : to_header;
            line("}");
        }
        line(t == loop->merge ? "break if " + cond.text + ";" : "break if !" + cond.operand() + ";");
        done = true;
        return;
    }
    if (!t_exit && !f_exit)
        unsupported(term, "a conditional branch between two blocks of the same construct without a merge instruction");
    if (loop && loop->in_continuing && (t_exit || f_exit) && (t == loop->merge || f == loop->merge))
        unsupported(term, "a conditional break nested inside a loop's continue construct");
    const Expr cond = dry_run_ ? Expr{} : value(term.operand(0));
    ++nesting_;
    const int saved = scope_;
    auto branch = [&](uint32_t target) {
        return capture([&] {
            open_scope();
            ++indent_;
            exit_statement(b, target, stop, loop);
            --indent_;
            close_scope(saved);
        });
    };
    if (t_exit && f_exit) {
        const std::string then_text = branch(t), else_text = branch(f);
        --nesting_;
        line("if (" + cond.text + ") {");
        out_ += then_text;
        line("} else {");
        out_ += else_text;
        line("}");
        early_exit_ = true;
        done = true;
        return;
    }
    const uint32_t exit = t_exit ? t : f, stay = t_exit ? f : t;
    const std::string exit_text = branch(exit);
    --nesting_;
    if (!exit_text.empty()) {
        line(t_exit ? "if (" + cond.text + ") {" : "if (!" + cond.operand() + ") {");
        out_ += exit_text;
        line("}");
        early_exit_ = true;
    }
    phi_copies(b, stay);
    next = stay;
    done = false;
}

void FunctionPrinter::loop_construct(uint32_t header) {
    const Block& h = f_.block(header);
    LoopContext ctx;
    ctx.header = header;
    ctx.merge = h.merge->operand(0);
    ctx.cont = h.merge->operand(1);
    const int saved = scope_;
    line("loop {");
    ++indent_;
    ++nesting_;
    open_scope();
    const int loop_scope = scope_;
    block_scope_[header] = scope_;
    current_block_ = header;
    block_instructions(h);

    if (ctx.cont == header) {
        // A one-block loop: the header is its own continue target.
        const Instruction& term = h.terminator;
        if (term.op == spv::OpBranch) {
            phi_copies(header, header);
        } else if (term.op == spv::OpBranchConditional) {
            const Expr cond = dry_run_ ? Expr{} : value(term.operand(0));
            const bool exit_on_true = term.operand(1) == ctx.merge;
            const std::string exit_text = capture([&] { ++indent_; phi_copies(header, ctx.merge); line("break;"); --indent_; });
            line(exit_on_true ? "if (" + cond.text + ") {" : "if (!" + cond.operand() + ") {");
            out_ += exit_text;
            line("}");
            phi_copies(header, header);
        } else {
            unsupported(term, "a loop header that ends the function");
        }
    } else {
        // Header: either falls into the body or tests and breaks.
        uint32_t body = 0;
        const Instruction& term = h.terminator;
        LoopContext body_ctx = ctx;
        if (term.op == spv::OpBranch) {
            body = term.operand(0);
            phi_copies(header, body);
        } else if (term.op == spv::OpBranchConditional) {
            bool done = false;
            conditional_exit(h, ctx.cont, &body_ctx, body, done);
            if (done) body = ctx.cont;
        } else {
            unsupported(term, "a loop header that ends the function");
        }
        if (body != ctx.cont) {
            open_scope();
            region(body, ctx.cont, &body_ctx);
            close_scope(loop_scope);
        }
        // The continue construct, unless it is an empty block that just branches back.
        LoopContext cont_ctx = ctx;
        cont_ctx.in_continuing = true;
        const std::string continuing = capture([&] {
            ++indent_;
            open_scope();
            cont_ctx.continuing_scope = scope_;
            region(ctx.cont, header, &cont_ctx);
            close_scope(loop_scope);
            --indent_;
        });
        if (!continuing.empty()) {
            line("continuing {");
            out_ += continuing;
            line("}");
        }
    }
    --nesting_;
    --indent_;
    close_scope(saved);
    line("}");
}

// ---------------------------------------------------------------------------------------------
// Values

std::string FunctionPrinter::temp_name(uint32_t id) {
    const std::string wanted = m_.name(id);
    return unique_identifier(wanted.empty() ? fmt::format("_{}", id) : wanted, names_);
}

std::string FunctionPrinter::composite_path(uint32_t type, const std::vector<uint32_t>& operands, size_t first) {
    std::string path;
    for (size_t i = first; i < operands.size(); ++i) {
        const Type& t = m_.type(type);
        if (t.op == spv::OpTypeVector) {
            path += std::string(".") + swizzle_letter(operands[i]);
            type = t.element;
        } else if (t.op == spv::OpTypeStruct) {
            mod_.struct_name(type);
            path += "." + mod_.struct_member_names.at(type).at(operands[i]);
            type = t.members.at(operands[i]);
        } else {
            path += fmt::format("[{}]", operands[i]);
            type = t.element;
        }
    }
    return path;
}

Expr FunctionPrinter::value(uint32_t id) {
    if (auto it = values_.find(id); it != values_.end()) return it->second;
    if (mod_.is_constant(id)) return mod_.constant(id);
    fail(fmt::format("value %{} is used before the emitter defined it", id));
}

std::string FunctionPrinter::typed(uint32_t id, uint32_t wanted_type) {
    const Expr e = value(id);
    const uint32_t actual = type_of(id);
    if (!actual || actual == wanted_type) return e.operand();
    const Type& a = m_.type(mod_.scalar_of(actual));
    const Type& w = m_.type(mod_.scalar_of(wanted_type));
    if (a.op == spv::OpTypeInt && w.op == spv::OpTypeInt && a.is_signed != w.is_signed)
        return "bitcast<" + mod_.type_name(wanted_type) + ">(" + e.text + ")";
    return e.operand();
}

// True when `text` needs no parentheses as an operand: a name, literal, member access or call.
bool is_atom(const std::string& text) {
    if (text.empty() || text[0] == '-' || text[0] == '!' || text[0] == '~') return false;
    int depth = 0;
    for (char c : text) {
        if (c == '(' || c == '[') ++depth;
        else if (c == ')' || c == ']') --depth;
        else if (depth == 0 && c == ' ') return false;
    }
    return true;
}

void FunctionPrinter::define(const Instruction& inst, const std::string& text, bool pure, bool always_inline) {
    const uint32_t id = inst.result;
    if (dry_run_) return;
    const int uses = uses_.count(id) ? uses_[id] : 0;
    if (uses == 0 && pure) return;  // dead code stays out
    if (hoisted_.count(id)) {
        const std::string name = values_.count(id) ? values_[id].text : temp_name(id);
        line(name + " = " + text + ";");
        values_[id] = {name, true};
        return;
    }
    const auto& blocks = use_blocks_[id];
    const bool local_single_use = uses == 1 && blocks.size() == 1 && *blocks.begin() == current_block_ && !phi_sources_.count(id);
    if (pure && (always_inline || (local_single_use && text.size() <= kInlineLimit))) {
        values_[id] = {text, is_atom(text)};
        return;
    }
    if (uses == 0) {  // a call or store-like value nobody reads: keep the side effect
        line("_ = " + text + ";");
        return;
    }
    const std::string name = temp_name(id);
    line("let " + name + " = " + text + ";");
    values_[id] = {name, true};
}

std::string FunctionPrinter::ref(uint32_t pointer) {
    if (auto it = refs_.find(pointer); it != refs_.end()) return it->second;
    if (auto it = mod_.resource_names.find(pointer); it != mod_.resource_names.end()) return it->second;
    for (const auto& in : mod_.interface.inputs)
        if (in.variable == pointer) return in.read;
    for (const auto& out : mod_.interface.outputs)
        if (out.variable == pointer && !out.local.empty()) return out.local;
    fail(fmt::format("pointer %{} does not name a variable the emitter knows", pointer));
}

void FunctionPrinter::block_instructions(const Block& b) {
    if (dry_run_) {
        for (const Instruction& inst : b.body) {
            if (inst.result) def_block_[inst.result] = b.label;
            for (uint32_t id : value_operands(inst)) use_scopes_[id].insert(scope_);
        }
        // The terminator's operands (conditions, selectors, return values) are read in the block's scope.
        for (uint32_t id : value_operands(b.terminator)) use_scopes_[id].insert(scope_);
        return;
    }
    for (const Instruction& inst : b.body) instruction(inst);
}

// ---------------------------------------------------------------------------------------------

void FunctionPrinter::walk(bool dry_run) {
    dry_run_ = dry_run;
    scope_parent_.clear();
    scope_parent_.push_back(-1);
    scope_ = 0;
    nesting_ = 0;
    early_exit_ = false;
    region(f_.blocks.front().label, 0, nullptr);
}

std::string FunctionPrinter::run() {
    count_uses();

    // Parameters and locals first: their names are fixed for the whole body.
    std::vector<std::string> params;
    for (const Instruction& p : f_.params) {
        const std::string name = temp_name(p.result);
        const Type& t = m_.type(p.type);
        if (t.op == spv::OpTypePointer) {
            if (t.storage != spv::StorageClassFunction && t.storage != spv::StorageClassPrivate)
                fail("a pointer parameter to anything but a function or private variable");
            params.push_back(name + ": ptr<" + (t.storage == spv::StorageClassFunction ? "function" : "private") + ", " +
                             mod_.type_name(t.element) + ">");
            refs_[p.result] = "(*" + name + ")";
            pointer_types_[p.result] = p.type;
            pointer_params_[p.result] = name;
        } else if (t.op == spv::OpTypeSampledImage || t.op == spv::OpTypeImage || t.op == spv::OpTypeSampler) {
            fail("texture or sampler function parameters are not supported (crtforge inlines every function)");
        } else {
            params.push_back(name + ": " + mod_.type_name(p.type));
            values_[p.result] = {name, true};
        }
    }

    // Dry run: which scope every block and use lands in, so values used outside the scope that
    // defines them can be hoisted to function-scope variables.
    walk(true);
    for (const auto& [id, scopes] : use_scopes_) {
        auto d = def_block_.find(id);
        if (d == def_block_.end() || !block_scope_.count(d->second)) continue;
        const int def_scope = block_scope_[d->second];
        for (int s : scopes) {
            int x = s;
            while (x != -1 && x != def_scope) x = scope_parent_[static_cast<size_t>(x)];
            if (x == -1) { hoisted_.insert(id); break; }
        }
    }

    std::string decls;
    auto declare = [&](const std::string& text) { decls += std::string(2, ' ') + text + "\n"; };
    for (const Instruction& v : f_.variables) {
        const std::string name = temp_name(v.result);
        const uint32_t value_type = m_.type(v.type).element;
        std::string text = "var " + name + ": " + mod_.type_name(value_type);
        if (v.operands.size() > 1) text += " = " + mod_.constant(v.operands[1]).text;
        declare(text + ";");
        refs_[v.result] = name;
        pointer_types_[v.result] = v.type;
    }
    for (const Block& b : f_.blocks)
        for (const Instruction& phi : b.phis) {
            const std::string name = temp_name(phi.result);
            phi_vars_[phi.result] = name;
            values_[phi.result] = {name, true};
            declare("var " + name + ": " + mod_.type_name(phi.type) + ";");
        }
    for (const Block& b : f_.blocks)
        for (const Instruction& inst : b.body)
            if (hoisted_.count(inst.result) && inst.type && m_.type(inst.type).op != spv::OpTypePointer) {
                const std::string name = temp_name(inst.result);
                values_[inst.result] = {name, true};
                declare("var " + name + ": " + mod_.type_name(inst.type) + ";");
            }

    walk(false);
    std::string body = decls + out_;
    if (is_entry_) return body;
    std::string signature = "fn " + mod_.function_names.at(f_.id) + "(" + join_list(params) + ")";
    if (m_.type(f_.return_type).op != spv::OpTypeVoid) signature += " -> " + mod_.type_name(f_.return_type);
    return signature + " {\n" + body + "}\n";
}

// ---------------------------------------------------------------------------------------------
// Instructions

void FunctionPrinter::instruction(const Instruction& inst) {
    const auto& o = inst.operands;
    auto v = [&](size_t i) { return value(o.at(i)); };
    auto binary = [&](const char* op) {
        // Integer operands may differ in signedness from the result in SPIR-V, never in WGSL.
        const bool integer = m_.type(mod_.scalar_of(inst.type)).op == spv::OpTypeInt;
        const std::string a = integer ? typed(o.at(0), inst.type) : v(0).operand();
        const std::string b = integer ? typed(o.at(1), inst.type) : v(1).operand();
        define(inst, a + " " + op + " " + b, true);
    };
    // Comparisons: operands converted to the first operand's type.
    auto compare = [&](const char* op) {
        define(inst, v(0).operand() + " " + op + " " + v(1).operand(), true);
    };
    auto int_compare = [&](const char* op, bool want_signed) {
        auto cast = [&](size_t i) {
            const Expr e = v(i);
            const uint32_t ty = type_of(o.at(i));
            if (m_.type(mod_.scalar_of(ty)).is_signed == want_signed) return e.operand();
            const uint32_t n = mod_.component_count(ty);
            const char* scalar = want_signed ? "i32" : "u32";
            const std::string target = n == 1 ? std::string(scalar) : fmt::format("vec{}<{}>", n, scalar);
            return "bitcast<" + target + ">(" + e.text + ")";
        };
        define(inst, cast(0) + " " + op + " " + cast(1), true);
    };
    const bool vector_bool = mod_.component_count(inst.type) > 1;

    switch (inst.op) {
        case spv::OpNop: case spv::OpLine: case spv::OpNoLine: return;
        case spv::OpUndef: define(inst, mod_.type_name(inst.type) + "()", true, true); return;

        // -- memory --
        case spv::OpLoad: {
            const uint32_t pointer = o.at(0);
            const spv::StorageClass storage = pointer_type(pointer).storage;
            const uint32_t t = m_.type(inst.type).op;
            if (t == spv::OpTypeSampledImage) {
                const std::string texture = ref(pointer);
                auto s = mod_.sampler_names.find(pointer);
                if (s == mod_.sampler_names.end()) unsupported(inst, "a combined image sampler that is not a module variable");
                images_[inst.result] = {texture, s->second};
                return;
            }
            if (t == spv::OpTypeImage || t == spv::OpTypeSampler) {
                images_[inst.result] = {t == spv::OpTypeImage ? ref(pointer) : "", t == spv::OpTypeSampler ? ref(pointer) : ""};
                return;
            }
            const bool pure = storage == spv::StorageClassUniform || storage == spv::StorageClassInput ||
                              storage == spv::StorageClassUniformConstant;
            // Reads of the uniform block and the stage inputs are immutable: always inline them.
            define(inst, ref(pointer), pure, pure);
            return;
        }
        case spv::OpStore:
            line(ref(o.at(0)) + " = " + value(o.at(1)).text + ";");
            return;
        case spv::OpCopyMemory:
            line(ref(o.at(0)) + " = " + ref(o.at(1)) + ";");
            return;
        case spv::OpAccessChain:
        case spv::OpInBoundsAccessChain: {
            const uint32_t base = o.at(0);
            std::string text;
            uint32_t current = pointer_type(base).element;
            size_t first = 1;
            // gl_PerVertex-style output blocks are split into one local per member.
            bool handled = false;
            for (const auto& out : mod_.interface.outputs)
                if (out.variable == base && !out.block_members.empty()) {
                    const uint32_t member = m_.constants.at(o.at(1)).words.at(0);
                    auto it = out.block_members.find(member);
                    if (it == out.block_members.end())
                        unsupported(inst, "writing gl_PointSize, gl_ClipDistance or gl_CullDistance, which WGSL lacks");
                    text = it->second;
                    current = m_.type(current).members.at(member);
                    first = 2;
                    handled = true;
                }
            if (!handled) text = ref(base);
            for (size_t i = first; i < o.size(); ++i) {
                const Type& t = m_.type(current);
                const bool constant = mod_.is_constant(o[i]);
                if (t.op == spv::OpTypeStruct) {
                    const uint32_t member = m_.constants.at(o[i]).words.at(0);
                    mod_.struct_name(current);
                    text += "." + mod_.struct_member_names.at(current).at(member);
                    current = t.members.at(member);
                } else if (t.op == spv::OpTypeVector && constant) {
                    text += std::string(".") + swizzle_letter(m_.constants.at(o[i]).words.at(0));
                    current = t.element;
                } else {
                    text += "[" + value(o[i]).text + "]";
                    current = t.element;
                }
            }
            refs_[inst.result] = text;
            pointer_types_[inst.result] = inst.type;
            return;
        }
        case spv::OpCopyObject:
            if (refs_.count(o.at(0))) refs_[inst.result] = refs_[o.at(0)];
            else if (images_.count(o.at(0))) images_[inst.result] = images_[o.at(0)];
            else values_[inst.result] = value(o.at(0));
            return;

        // -- composites --
        case spv::OpCompositeConstruct: {
            std::vector<std::string> parts;
            for (uint32_t id : o) parts.push_back(value(id).text);
            define(inst, mod_.type_name(inst.type) + "(" + join_list(parts) + ")", true);
            return;
        }
        case spv::OpCompositeExtract: {
            if (!type_of(o.at(0))) unsupported(inst, "the composite's type is unknown");
            const Expr base = v(0);
            // Member reads of a named value are free to repeat; of an expression, they get a let.
            define(inst, base.operand() + composite_path(type_of(o.at(0)), o, 1), true,
                   base.text.find('(') == std::string::npos);
            return;
        }
        case spv::OpCompositeInsert: {
            const std::string name = temp_name(inst.result);
            line("var " + name + " = " + value(o.at(1)).text + ";");
            line(name + composite_path(inst.type, o, 2) + " = " + value(o.at(0)).text + ";");
            values_[inst.result] = {name, true};
            return;
        }
        case spv::OpVectorShuffle: {
            const Expr a = v(0), b = v(1);
            const uint32_t a_count = mod_.component_count(type_of(o.at(0)));
            bool all_a = true, all_b = true;
            for (size_t i = 2; i < o.size(); ++i) {
                if (o[i] == 0xffffffffu) continue;
                (o[i] < a_count ? all_b : all_a) = false;
            }
            auto component = [&](uint32_t c) {
                if (c == 0xffffffffu) c = 0;  // undefined component: any value is allowed
                return c < a_count ? swizzle_letter(c) : swizzle_letter(c - a_count);
            };
            if (all_a || all_b) {
                std::string swizzle;
                for (size_t i = 2; i < o.size(); ++i) swizzle += component(o[i]);
                define(inst, (all_a ? a : b).operand() + "." + swizzle, true);
            } else {
                std::vector<std::string> parts;
                for (size_t i = 2; i < o.size(); ++i)
                    parts.push_back((o[i] < a_count ? a : b).operand() + "." + component(o[i]));
                define(inst, mod_.type_name(inst.type) + "(" + join_list(parts) + ")", true);
            }
            return;
        }
        case spv::OpVectorExtractDynamic:
            define(inst, v(0).operand() + "[" + v(1).text + "]", true);
            return;
        case spv::OpVectorInsertDynamic: {
            const std::string name = temp_name(inst.result);
            line("var " + name + " = " + v(0).text + ";");
            line(name + "[" + v(2).text + "] = " + v(1).text + ";");
            values_[inst.result] = {name, true};
            return;
        }

        // -- arithmetic --
        case spv::OpFAdd: case spv::OpIAdd: binary("+"); return;
        case spv::OpFSub: case spv::OpISub: binary("-"); return;
        case spv::OpFMul: case spv::OpIMul: case spv::OpVectorTimesScalar: case spv::OpMatrixTimesScalar:
        case spv::OpMatrixTimesVector: case spv::OpVectorTimesMatrix: case spv::OpMatrixTimesMatrix:
            binary("*");
            return;
        case spv::OpFDiv: case spv::OpSDiv: case spv::OpUDiv: binary("/"); return;
        // WGSL's % truncates: exactly SPIR-V's FRem, SRem and UMod.
        case spv::OpFRem: case spv::OpSRem: case spv::OpUMod: binary("%"); return;
        case spv::OpFMod: {
            // GLSL mod(): x - y * floor(x / y), the sign of y; WGSL's % would take the sign of x.
            const std::string x = v(0).operand(), y = v(1).operand();
            define(inst, x + " - " + y + " * floor(" + x + " / " + y + ")", true);
            return;
        }
        case spv::OpSMod: {
            // Remainder with the sign of the divisor, from WGSL's truncating %.
            const std::string x = typed(o.at(0), inst.type), y = typed(o.at(1), inst.type);
            const std::string r = temp_name(inst.result) + "_rem";
            line("let " + r + " = " + x + " % " + y + ";");
            const std::string zero = mod_.type_name(inst.type) + "()";
            define(inst, "select(" + r + ", " + r + " + " + y + ", (" + r + " != " + zero + ") & ((" + r + " < " + zero +
                             ") != (" + y + " < " + zero + ")))",
                   true);
            return;
        }
        case spv::OpFNegate: case spv::OpSNegate: define(inst, "-" + v(0).operand(), true); return;
        case spv::OpDot: define(inst, "dot(" + v(0).text + ", " + v(1).text + ")", true); return;
        case spv::OpTranspose: define(inst, "transpose(" + v(0).text + ")", true); return;

        // -- bits --
        case spv::OpBitwiseAnd: binary("&"); return;
        case spv::OpBitwiseOr: binary("|"); return;
        case spv::OpBitwiseXor: binary("^"); return;
        case spv::OpNot: define(inst, "~" + v(0).operand(), true); return;
        case spv::OpShiftLeftLogical:
        case spv::OpShiftRightLogical:
        case spv::OpShiftRightArithmetic: {
            const uint32_t n = mod_.component_count(inst.type);
            const std::string u = n == 1 ? "u32" : fmt::format("vec{}<u32>", n);
            const std::string s = n == 1 ? "i32" : fmt::format("vec{}<i32>", n);
            // WGSL wants an unsigned shift count; the shifted value's signedness picks the shift kind.
            std::string amount = "bitcast<" + u + ">(" + v(1).text + ")";
            if (n == 1 && mod_.is_constant(o.at(1)) && m_.constants.at(o.at(1)).op == spv::OpConstant)
                amount = u32_literal(m_.constants.at(o.at(1)).words.at(0));
            const bool result_signed = m_.type(mod_.scalar_of(inst.type)).is_signed;
            if (inst.op == spv::OpShiftLeftLogical) {
                define(inst, typed(o.at(0), inst.type) + " << " + amount, true);
            } else {
                const std::string kind = inst.op == spv::OpShiftRightLogical ? u : s;
                std::string text = "bitcast<" + kind + ">(" + v(0).text + ") >> " + amount;
                if ((kind == s) != result_signed) text = "bitcast<" + mod_.type_name(inst.type) + ">(" + text + ")";
                define(inst, text, true);
            }
            return;
        }
        case spv::OpBitCount: define(inst, "countOneBits(" + v(0).text + ")", true); return;
        case spv::OpBitReverse: define(inst, "reverseBits(" + v(0).text + ")", true); return;

        // -- conversions --
        case spv::OpConvertFToS: case spv::OpConvertFToU: case spv::OpConvertSToF: case spv::OpConvertUToF:
        case spv::OpFConvert:
            define(inst, mod_.type_name(inst.type) + "(" + v(0).text + ")", true);
            return;
        case spv::OpBitcast: case spv::OpSConvert: case spv::OpUConvert:
            define(inst, "bitcast<" + mod_.type_name(inst.type) + ">(" + v(0).text + ")", true);
            return;
        case spv::OpQuantizeToF16: define(inst, "quantizeToF16(" + v(0).text + ")", true); return;

        // -- relational and logical --
        case spv::OpFOrdEqual: case spv::OpLogicalEqual: compare("=="); return;
        case spv::OpFUnordNotEqual: case spv::OpLogicalNotEqual: compare("!="); return;
        case spv::OpFOrdLessThan: compare("<"); return;
        case spv::OpFOrdGreaterThan: compare(">"); return;
        case spv::OpFOrdLessThanEqual: compare("<="); return;
        case spv::OpFOrdGreaterThanEqual: compare(">="); return;
        // Unordered comparisons are true when an operand is NaN: the negated opposite ordered test.
        case spv::OpFUnordLessThan: define(inst, "!(" + v(0).operand() + " >= " + v(1).operand() + ")", true); return;
        case spv::OpFUnordGreaterThan: define(inst, "!(" + v(0).operand() + " <= " + v(1).operand() + ")", true); return;
        case spv::OpFUnordLessThanEqual: define(inst, "!(" + v(0).operand() + " > " + v(1).operand() + ")", true); return;
        case spv::OpFUnordGreaterThanEqual: define(inst, "!(" + v(0).operand() + " < " + v(1).operand() + ")", true); return;
        case spv::OpFOrdNotEqual: {
            // Ordered: false for NaN, which WGSL's != (true for NaN) is not.
            const char* join = vector_bool ? " | " : " || ";
            define(inst, "(" + v(0).operand() + " < " + v(1).operand() + ")" + join + "(" + v(0).operand() + " > " +
                             v(1).operand() + ")", true);
            return;
        }
        case spv::OpFUnordEqual: {
            const char* join = vector_bool ? " | " : " || ";
            define(inst, "!((" + v(0).operand() + " < " + v(1).operand() + ")" + join + "(" + v(0).operand() + " > " +
                             v(1).operand() + "))", true);
            return;
        }
        case spv::OpIEqual: int_compare("==", true); return;
        case spv::OpINotEqual: int_compare("!=", true); return;
        case spv::OpSLessThan: int_compare("<", true); return;
        case spv::OpSGreaterThan: int_compare(">", true); return;
        case spv::OpSLessThanEqual: int_compare("<=", true); return;
        case spv::OpSGreaterThanEqual: int_compare(">=", true); return;
        case spv::OpULessThan: int_compare("<", false); return;
        case spv::OpUGreaterThan: int_compare(">", false); return;
        case spv::OpULessThanEqual: int_compare("<=", false); return;
        case spv::OpUGreaterThanEqual: int_compare(">=", false); return;
        case spv::OpLogicalAnd: compare(vector_bool ? "&" : "&&"); return;
        case spv::OpLogicalOr: compare(vector_bool ? "|" : "||"); return;
        case spv::OpLogicalNot: define(inst, "!" + v(0).operand(), true); return;
        case spv::OpAny: define(inst, "any(" + v(0).text + ")", true); return;
        case spv::OpAll: define(inst, "all(" + v(0).text + ")", true); return;
        case spv::OpIsNan:
        case spv::OpIsInf: {
            // By the bits: WGSL lets compilers assume there are no NaNs or infinities in float maths.
            const uint32_t n = mod_.component_count(inst.type);
            const std::string u = n == 1 ? "u32" : fmt::format("vec{}<u32>", n);
            auto splat = [&](const char* c) { return n == 1 ? std::string(c) : u + "(" + c + ")"; };
            define(inst, "(bitcast<" + u + ">(" + v(0).text + ") & " + splat("0x7fffffffu") + ") " +
                             (inst.op == spv::OpIsNan ? "> " : "== ") + splat("0x7f800000u"), true);
            return;
        }
        case spv::OpSelect:
            // select(false_value, true_value, condition): SPIR-V's order reversed.
            define(inst, "select(" + v(2).text + ", " + v(1).text + ", " + v(0).text + ")", true);
            return;

        // -- derivatives --
        case spv::OpDPdx: case spv::OpDPdy: case spv::OpFwidth: case spv::OpDPdxFine: case spv::OpDPdyFine:
        case spv::OpFwidthFine: case spv::OpDPdxCoarse: case spv::OpDPdyCoarse: case spv::OpFwidthCoarse: {
            static const std::map<spv::Op, const char*> names = {
                {spv::OpDPdx, "dpdx"}, {spv::OpDPdy, "dpdy"}, {spv::OpFwidth, "fwidth"},
                {spv::OpDPdxFine, "dpdxFine"}, {spv::OpDPdyFine, "dpdyFine"}, {spv::OpFwidthFine, "fwidthFine"},
                {spv::OpDPdxCoarse, "dpdxCoarse"}, {spv::OpDPdyCoarse, "dpdyCoarse"}, {spv::OpFwidthCoarse, "fwidthCoarse"}};
            if (!flow_uniform()) mod_.needs_derivative_uniformity_off = true;
            define(inst, std::string(names.at(inst.op)) + "(" + v(0).text + ")", true);
            return;
        }

        case spv::OpExtInst: ext_instruction(inst); return;
        case spv::OpSampledImage: {
            auto t = images_.find(o.at(0));
            auto s = images_.find(o.at(1));
            if (t == images_.end() || s == images_.end()) unsupported(inst);
            images_[inst.result] = {t->second.first, s->second.second};
            return;
        }
        case spv::OpImage: {
            auto t = images_.find(o.at(0));
            if (t == images_.end()) unsupported(inst);
            images_[inst.result] = {t->second.first, ""};
            return;
        }
        case spv::OpImageSampleImplicitLod: case spv::OpImageSampleExplicitLod: case spv::OpImageFetch:
        case spv::OpImageQuerySizeLod: case spv::OpImageQuerySize: case spv::OpImageQueryLevels:
            image_instruction(inst);
            return;

        case spv::OpFunctionCall: {
            std::vector<std::string> args;
            for (size_t i = 1; i < o.size(); ++i) {
                if (auto p = pointer_params_.find(o[i]); p != pointer_params_.end()) args.push_back(p->second);  // already a pointer
                else if (refs_.count(o[i])) args.push_back("&" + refs_[o[i]]);
                else args.push_back(value(o[i]).text);
            }
            const std::string call = mod_.function_names.at(o.at(0)) + "(" + join_list(args) + ")";
            if (m_.type(inst.type).op == spv::OpTypeVoid) line(call + ";");
            else define(inst, call, false);
            return;
        }
        default:
            unsupported(inst);
    }
}

void FunctionPrinter::ext_instruction(const Instruction& inst) {
    const auto& o = inst.operands;
    if (m_.ext_imports.count(o.at(0)) == 0 || m_.ext_imports.at(o.at(0)) != "GLSL.std.450")
        unsupported(inst, "an extended instruction set other than GLSL.std.450");
    const auto e = static_cast<GLSLstd450>(o.at(1));
    std::vector<Expr> args;
    for (size_t i = 2; i < o.size(); ++i) args.push_back(value(o[i]));
    auto call = [&](const std::string& name) {
        std::vector<std::string> texts;
        for (const Expr& a : args) texts.push_back(a.text);
        define(inst, name + "(" + join_list(texts) + ")", true);
    };
    // Integer builtins: operands in the result's signedness.
    auto int_call = [&](const std::string& name) {
        std::vector<std::string> texts;
        for (size_t i = 2; i < o.size(); ++i) texts.push_back(typed(o[i], inst.type));
        define(inst, name + "(" + join_list(texts) + ")", true);
    };
    auto constant_floats = [&](size_t i) -> std::optional<std::vector<float>> {
        auto c = m_.constants.find(o.at(i));
        if (c == m_.constants.end()) return std::nullopt;
        std::vector<uint32_t> bits;
        if (c->second.op == spv::OpConstant) bits = c->second.words;
        else if (c->second.op == spv::OpConstantComposite)
            for (uint32_t part : c->second.words) bits.push_back(m_.constants.at(part).words.at(0));
        else if (c->second.op == spv::OpConstantNull) bits.assign(mod_.component_count(c->second.type), 0u);
        else return std::nullopt;
        std::vector<float> out;
        for (uint32_t b : bits) { float f; std::memcpy(&f, &b, 4); out.push_back(f); }
        return out;
    };
    // True when two constant operands are in the order WGSL's const-evaluation rejects.
    auto reversed = [&](size_t lo, size_t hi, bool allow_equal) {
        auto a = constant_floats(lo), b = constant_floats(hi);
        if (!a || !b) return false;
        for (size_t i = 0; i < std::max(a->size(), b->size()); ++i) {
            const float x = (*a)[std::min(i, a->size() - 1)], y = (*b)[std::min(i, b->size() - 1)];
            if (allow_equal ? x > y : x >= y) return true;
        }
        return false;
    };
    switch (e) {
        case GLSLstd450Round: case GLSLstd450RoundEven: call("round"); return;  // WGSL rounds half to even: a valid GLSL round()
        case GLSLstd450Trunc: call("trunc"); return;
        case GLSLstd450FAbs: call("abs"); return;
        case GLSLstd450SAbs: int_call("abs"); return;
        case GLSLstd450FSign: call("sign"); return;
        case GLSLstd450SSign: int_call("sign"); return;
        case GLSLstd450Floor: call("floor"); return;
        case GLSLstd450Ceil: call("ceil"); return;
        case GLSLstd450Fract: call("fract"); return;
        case GLSLstd450Radians: call("radians"); return;
        case GLSLstd450Degrees: call("degrees"); return;
        case GLSLstd450Sin: call("sin"); return;
        case GLSLstd450Cos: call("cos"); return;
        case GLSLstd450Tan: call("tan"); return;
        case GLSLstd450Asin: call("asin"); return;
        case GLSLstd450Acos: call("acos"); return;
        case GLSLstd450Atan: call("atan"); return;
        case GLSLstd450Sinh: call("sinh"); return;
        case GLSLstd450Cosh: call("cosh"); return;
        case GLSLstd450Tanh: call("tanh"); return;
        case GLSLstd450Asinh: call("asinh"); return;
        case GLSLstd450Acosh: call("acosh"); return;
        case GLSLstd450Atanh: call("atanh"); return;
        case GLSLstd450Atan2: call("atan2"); return;
        case GLSLstd450Pow: call("pow"); return;
        case GLSLstd450Exp: call("exp"); return;
        case GLSLstd450Log: call("log"); return;
        case GLSLstd450Exp2: call("exp2"); return;
        case GLSLstd450Log2: call("log2"); return;
        case GLSLstd450Sqrt: call("sqrt"); return;
        case GLSLstd450InverseSqrt: call("inverseSqrt"); return;
        case GLSLstd450Determinant: call("determinant"); return;
        case GLSLstd450FMin: call("min"); return;
        case GLSLstd450FMax: call("max"); return;
        case GLSLstd450UMin: case GLSLstd450SMin: int_call("min"); return;
        case GLSLstd450UMax: case GLSLstd450SMax: int_call("max"); return;
        case GLSLstd450FClamp:
            // WGSL rejects clamp() whose constant low > high; GLSL defines clamp as min(max(x, lo), hi).
            if (reversed(3, 4, true)) define(inst, "min(max(" + args[0].text + ", " + args[1].text + "), " + args[2].text + ")", true);
            else call("clamp");
            return;
        case GLSLstd450UClamp: case GLSLstd450SClamp: int_call("clamp"); return;
        case GLSLstd450FMix: call("mix"); return;
        case GLSLstd450Step: call("step"); return;
        case GLSLstd450SmoothStep:
            // smoothstep(e0, e1, x) with constant e0 >= e1 is a WGSL error but a valid GLSL expression
            // (Quiet Frame's vignette writes one): spell out the Hermite curve GLSL defines.
            if (reversed(2, 3, false)) {
                const std::string t = "clamp((" + args[2].text + " - " + args[0].operand() + ") / (" + args[1].operand() +
                                      " - " + args[0].operand() + "), " + mod_.type_name(inst.type) + "(0.0), " +
                                      mod_.type_name(inst.type) + "(1.0))";
                const std::string name = temp_name(inst.result) + "_t";
                line("let " + name + " = " + t + ";");
                define(inst, name + " * " + name + " * (3.0 - 2.0 * " + name + ")", true);
            } else {
                call("smoothstep");
            }
            return;
        case GLSLstd450Fma: call("fma"); return;
        case GLSLstd450Ldexp: {
            const uint32_t n = mod_.component_count(inst.type);
            const std::string exp_type = n == 1 ? "i32" : fmt::format("vec{}<i32>", n);
            define(inst, "ldexp(" + args[0].text + ", bitcast<" + exp_type + ">(" + args[1].text + "))", true);
            return;
        }
        case GLSLstd450PackSnorm4x8: call("pack4x8snorm"); return;
        case GLSLstd450PackUnorm4x8: call("pack4x8unorm"); return;
        case GLSLstd450PackSnorm2x16: call("pack2x16snorm"); return;
        case GLSLstd450PackUnorm2x16: call("pack2x16unorm"); return;
        case GLSLstd450PackHalf2x16: call("pack2x16float"); return;
        case GLSLstd450UnpackSnorm2x16: call("unpack2x16snorm"); return;
        case GLSLstd450UnpackUnorm2x16: call("unpack2x16unorm"); return;
        case GLSLstd450UnpackHalf2x16: call("unpack2x16float"); return;
        case GLSLstd450UnpackSnorm4x8: call("unpack4x8snorm"); return;
        case GLSLstd450UnpackUnorm4x8: call("unpack4x8unorm"); return;
        case GLSLstd450Length: call("length"); return;
        case GLSLstd450Distance: call("distance"); return;
        case GLSLstd450Cross: call("cross"); return;
        case GLSLstd450Normalize: call("normalize"); return;
        case GLSLstd450FaceForward: call("faceForward"); return;
        case GLSLstd450Reflect: call("reflect"); return;
        case GLSLstd450Refract: call("refract"); return;
        case GLSLstd450FindILsb: case GLSLstd450FindSMsb: case GLSLstd450FindUMsb: {
            const char* name = e == GLSLstd450FindILsb ? "firstTrailingBit" : "firstLeadingBit";
            const bool want_signed = e == GLSLstd450FindSMsb;
            const uint32_t n = mod_.component_count(inst.type);
            const std::string operand_type = n == 1 ? (want_signed ? "i32" : "u32") : fmt::format("vec{}<{}>", n, want_signed ? "i32" : "u32");
            std::string text = std::string(name) + "(bitcast<" + operand_type + ">(" + args[0].text + "))";
            if (m_.type(mod_.scalar_of(inst.type)).is_signed != want_signed)
                text = "bitcast<" + mod_.type_name(inst.type) + ">(" + text + ")";
            define(inst, text, true);
            return;
        }
        default: {
            static const std::map<GLSLstd450, const char*> names = {
                {GLSLstd450MatrixInverse, "MatrixInverse"}, {GLSLstd450Modf, "Modf"}, {GLSLstd450ModfStruct, "ModfStruct"},
                {GLSLstd450Frexp, "Frexp"}, {GLSLstd450FrexpStruct, "FrexpStruct"},
                {GLSLstd450InterpolateAtCentroid, "InterpolateAtCentroid"}, {GLSLstd450InterpolateAtSample, "InterpolateAtSample"},
                {GLSLstd450InterpolateAtOffset, "InterpolateAtOffset"}, {GLSLstd450NMin, "NMin"}, {GLSLstd450NMax, "NMax"},
                {GLSLstd450NClamp, "NClamp"}, {GLSLstd450PackDouble2x32, "PackDouble2x32"},
                {GLSLstd450UnpackDouble2x32, "UnpackDouble2x32"}};
            auto it = names.find(e);
            fail(fmt::format("cannot translate OpExtInst GLSL.std.450 {} to WGSL",
                             it != names.end() ? it->second : std::to_string(static_cast<int>(e)).c_str()),
                 inst.line);
        }
    }
}

void FunctionPrinter::image_instruction(const Instruction& inst) {
    const auto& o = inst.operands;
    auto image = images_.find(o.at(0));
    if (image == images_.end()) unsupported(inst, "the image does not come from a module variable");
    const auto& [texture, sampler] = image->second;
    switch (inst.op) {
        case spv::OpImageQuerySizeLod: case spv::OpImageQuerySize: {
            std::string text = "textureDimensions(" + texture + (inst.op == spv::OpImageQuerySizeLod ? ", " + value(o.at(1)).text : "") + ")";
            if (m_.type(mod_.scalar_of(inst.type)).is_signed) text = mod_.type_name(inst.type) + "(" + text + ")";
            define(inst, text, true);
            return;
        }
        case spv::OpImageQueryLevels: {
            std::string text = "textureNumLevels(" + texture + ")";
            if (m_.type(inst.type).is_signed) text = "i32(" + text + ")";
            define(inst, text, true);
            return;
        }
        default: break;
    }
    const std::string coord = value(o.at(1)).text;
    const uint32_t mask = o.size() > 2 ? o[2] : 0;
    std::map<uint32_t, std::string> operands;  // image-operand bit -> text
    size_t next = 3;
    for (uint32_t bit : {spv::ImageOperandsBiasMask, spv::ImageOperandsLodMask, spv::ImageOperandsGradMask,
                         spv::ImageOperandsConstOffsetMask, spv::ImageOperandsOffsetMask, spv::ImageOperandsConstOffsetsMask,
                         spv::ImageOperandsSampleMask, spv::ImageOperandsMinLodMask}) {
        if (!(mask & bit)) continue;
        if (bit == spv::ImageOperandsGradMask) {
            operands[bit] = value(o.at(next)).text + ", " + value(o.at(next + 1)).text;
            next += 2;
        } else {
            operands[bit] = value(o.at(next)).text;
            ++next;
        }
    }
    const uint32_t known = spv::ImageOperandsBiasMask | spv::ImageOperandsLodMask | spv::ImageOperandsGradMask |
                           spv::ImageOperandsConstOffsetMask;
    if (mask & ~known) unsupported(inst, "image operands other than Bias, Lod, Grad and ConstOffset");
    const std::string offset = operands.count(spv::ImageOperandsConstOffsetMask) ? ", " + operands[spv::ImageOperandsConstOffsetMask] : "";
    std::string text;
    if (inst.op == spv::OpImageFetch) {
        const std::string lod = operands.count(spv::ImageOperandsLodMask) ? operands[spv::ImageOperandsLodMask] : "0";
        text = "textureLoad(" + texture + ", " + coord + ", " + lod + ")";
    } else if (inst.op == spv::OpImageSampleImplicitLod) {
        if (!flow_uniform()) mod_.needs_derivative_uniformity_off = true;
        if (operands.count(spv::ImageOperandsBiasMask))
            text = "textureSampleBias(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsBiasMask] + offset + ")";
        else
            text = "textureSample(" + texture + ", " + sampler + ", " + coord + offset + ")";
    } else if (operands.count(spv::ImageOperandsLodMask)) {
        text = "textureSampleLevel(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsLodMask] + offset + ")";
    } else if (operands.count(spv::ImageOperandsGradMask)) {
        text = "textureSampleGrad(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsGradMask] + offset + ")";
    } else {
        unsupported(inst, "an explicit-LOD sample without Lod or Grad");
    }
    define(inst, text, true);
}

}  // namespace

std::string emit_function_body(ModuleEmitter& module, const Function& function, bool is_entry,
                               const std::string& entry_return, std::set<std::string>& local_names) {
    FunctionPrinter printer(module, function, is_entry, entry_return, local_names);
    return printer.run();
}

}  // namespace crtforge::wgsl
