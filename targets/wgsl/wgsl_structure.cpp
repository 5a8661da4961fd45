// The structuriser: SPIR-V merge instructions -> a statement tree (see wgsl_structure.hpp).
#include "targets/wgsl/wgsl_structure.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "targets/wgsl/wgsl_context.hpp"

namespace crtforge::wgsl {

namespace {

struct LoopContext {
    uint32_t header = 0, merge = 0, cont = 0;
    bool in_continuing = false;
};

class Structuriser {
public:
    explicit Structuriser(const Function& f) : f_(f) {}

    // The blocks from `start` until `stop` (exclusive), or until the region leaves the enclosing
    // loop. `continuing_top`: the region is the top level of a loop's continue construct, where a
    // back edge becomes `break if`.
    Body region(uint32_t start, uint32_t stop, const LoopContext* loop, bool continuing_top = false);

private:
    const Block& block(uint32_t label) const {
        auto it = f_.block_index.find(label);
        if (it == f_.block_index.end()) fail(fmt::format("branch to a missing block %{}", label));
        return f_.blocks[it->second];
    }
    bool has_block(uint32_t label) const { return f_.block_index.count(label) != 0; }
    Statement copies(uint32_t from, uint32_t to) const {
        Statement s;
        s.kind = StatementKind::PhiCopies;
        s.block = from;
        s.target = to;
        return s;
    }
    static Statement simple(StatementKind kind) {
        Statement s;
        s.kind = kind;
        return s;
    }
    bool is_exit(uint32_t target, uint32_t stop, const LoopContext* loop) const;
    Body exit_arm(uint32_t from, uint32_t target, uint32_t stop, const LoopContext* loop) const;
    Body arm(uint32_t from, uint32_t target, uint32_t merge, const LoopContext* loop);
    // A conditional branch without a merge instruction; returns the block the region continues at,
    // or 0 when the branch ended the region.
    uint32_t conditional_exit(const Block& b, uint32_t stop, const LoopContext* loop, bool continuing_top, Body& out);
    Statement loop_construct(uint32_t header);
    // Whether reaching `target` leaves the innermost switch (the inliner wraps a function with
    // early returns in a one-case switch; each return becomes a branch to its merge: `break`).
    // Only from the switch's own loop level: a loop inside the case cannot break out of both.
    bool breaks_switch(uint32_t target, const LoopContext* loop) const {
        return !switches_.empty() && switches_.back().merge == target && switches_.back().loop == loop;
    }

    const Function& f_;
    struct SwitchContext {
        uint32_t merge = 0;
        const LoopContext* loop = nullptr;  // the loop the switch is in (nullptr: none)
    };
    std::vector<SwitchContext> switches_;  // the switches being walked, innermost last
    // The blocks of the region walks in progress, outermost first. Reaching one of them again is a
    // cycle without the OpLoopMerge that would make it a loop (malformed SPIR-V): walking it would
    // never end. A block may still be walked twice by sibling walks (a switch case falling through).
    std::set<uint32_t> open_;
};

// The blocks one region walk added to open_, removed when the walk returns.
class OpenBlocks {
public:
    explicit OpenBlocks(std::set<uint32_t>& open) : open_(open) {}
    ~OpenBlocks() {
        for (uint32_t b : mine_) open_.erase(b);
    }
    OpenBlocks(const OpenBlocks&) = delete;
    OpenBlocks& operator=(const OpenBlocks&) = delete;
    void add(uint32_t b) {
        if (!open_.insert(b).second)
            fail(fmt::format("block %{} is reached again inside its own construct without a loop merge", b));
        mine_.push_back(b);
    }

private:
    std::set<uint32_t>& open_;
    std::vector<uint32_t> mine_;
};

bool Structuriser::is_exit(uint32_t target, uint32_t stop, const LoopContext* loop) const {
    if (target == stop) return true;
    if (breaks_switch(target, loop)) return true;
    if (!loop) return false;
    if (target == loop->merge) return true;
    if (!loop->in_continuing && target == loop->cont) return true;
    if (loop->in_continuing && target == loop->header) return true;
    return false;
}

// Leaving a construct along one edge: its phi copies, then break or continue unless the edge just
// reaches the end of the region.
Body Structuriser::exit_arm(uint32_t from, uint32_t target, uint32_t stop, const LoopContext* loop) const {
    Body out{copies(from, target)};
    if (loop && target == loop->merge && target != stop) out.push_back(simple(StatementKind::Break));
    else if (loop && !loop->in_continuing && target == loop->cont && target != stop) out.push_back(simple(StatementKind::Continue));
    else if (breaks_switch(target, loop) && target != stop) out.push_back(simple(StatementKind::Break));
    return out;
}

// One arm of an if or switch: the phi copies of the edge into it, then the region from `target`
// to the construct's merge. The copies matter where `target` has other predecessors: a switch
// case that the case before it falls into has a phi choosing between the two edges.
Body Structuriser::arm(uint32_t from, uint32_t target, uint32_t merge, const LoopContext* loop) {
    Body out{copies(from, target)};
    if (target == merge) return out;
    Body rest = region(target, merge, loop);
    out.insert(out.end(), std::make_move_iterator(rest.begin()), std::make_move_iterator(rest.end()));
    return out;
}

Body Structuriser::region(uint32_t start, uint32_t stop, const LoopContext* loop, bool continuing_top) {
    Body out;
    OpenBlocks opened(open_);
    uint32_t b = start;
    while (true) {
        if (b == stop) return out;
        if (breaks_switch(b, loop)) {
            out.push_back(simple(StatementKind::Break));
            return out;
        }
        if (loop && b == loop->merge) {
            out.push_back(simple(StatementKind::Break));
            return out;
        }
        if (loop && !loop->in_continuing && b == loop->cont) {
            out.push_back(simple(StatementKind::Continue));
            return out;
        }
        if (loop && loop->in_continuing && b == loop->header) return out;
        opened.add(b);
        const Block& bl = block(b);
        if (bl.merge && bl.merge->op == spv::OpLoopMerge && !(loop && loop->header == b)) {
            out.push_back(loop_construct(b));
            b = bl.merge->operand(0);
            continue;
        }
        Statement instructions;
        instructions.kind = StatementKind::Block;
        instructions.block = b;
        out.push_back(instructions);
        const Instruction& term = bl.terminator;
        switch (term.op) {
            case spv::OpBranch:
                out.push_back(copies(b, term.operand(0)));
                b = term.operand(0);
                continue;
            case spv::OpBranchConditional: {
                const uint32_t t = term.operand(1), f = term.operand(2);
                if (t == f) {
                    out.push_back(copies(b, t));
                    b = t;
                    continue;
                }
                if (bl.merge && bl.merge->op == spv::OpSelectionMerge) {
                    const uint32_t merge = bl.merge->operand(0);
                    Statement s;
                    s.kind = StatementKind::If;
                    s.block = b;
                    s.value = term.operand(0);
                    s.then_body = arm(b, t, merge, loop);
                    s.else_body = arm(b, f, merge, loop);
                    out.push_back(std::move(s));
                    b = merge;
                    continue;
                }
                const uint32_t next = conditional_exit(bl, stop, loop, continuing_top, out);
                if (!next) return out;
                b = next;
                continue;
            }
            case spv::OpSwitch: {
                if (!bl.merge || bl.merge->op != spv::OpSelectionMerge) unsupported(term, "a switch without a merge block");
                const uint32_t merge = bl.merge->operand(0);
                Statement s;
                s.kind = StatementKind::Switch;
                s.block = b;
                s.value = term.operand(0);
                const uint32_t default_target = term.operand(1);
                std::vector<uint32_t> targets;
                for (size_t i = 2; i + 1 < term.operands.size(); i += 2) {
                    const uint32_t literal = term.operands[i], target = term.operands[i + 1];
                    auto found = std::find(targets.begin(), targets.end(), target);
                    if (found == targets.end()) {
                        targets.push_back(target);
                        s.cases.push_back({{literal}, false, {}});
                    } else {
                        s.cases[static_cast<size_t>(found - targets.begin())].literals.push_back(literal);
                    }
                }
                bool default_done = false;
                switches_.push_back({merge, loop});
                for (size_t i = 0; i < s.cases.size(); ++i) {
                    s.cases[i].is_default = targets[i] == default_target;
                    default_done = default_done || s.cases[i].is_default;
                    s.cases[i].body = arm(b, targets[i], merge, loop);
                }
                if (!default_done) s.cases.push_back({{}, true, arm(b, default_target, merge, loop)});
                switches_.pop_back();
                out.push_back(std::move(s));
                b = merge;
                continue;
            }
            case spv::OpReturn:
            case spv::OpReturnValue: {
                Statement s = simple(StatementKind::Return);
                s.block = b;
                s.value = term.op == spv::OpReturnValue ? term.operand(0) : 0;
                out.push_back(s);
                return out;
            }
            case spv::OpKill:
            case spv::OpTerminateInvocation:
                out.push_back(simple(StatementKind::Discard));
                return out;
            case spv::OpUnreachable:
                return out;
            default:
                unsupported(term);
        }
    }
}

uint32_t Structuriser::conditional_exit(const Block& bl, uint32_t stop, const LoopContext* loop, bool continuing_top,
                                        Body& out) {
    const Instruction& term = bl.terminator;
    const uint32_t b = bl.label, t = term.operand(1), f = term.operand(2);
    const bool t_exit = is_exit(t, stop, loop), f_exit = is_exit(f, stop, loop);

    // The back edge of a loop at the top level of its continuing block: `break if`.
    if (loop && loop->in_continuing && continuing_top &&
        ((t == loop->header && f == loop->merge) || (t == loop->merge && f == loop->header))) {
        Statement s;
        s.kind = StatementKind::BreakIf;
        s.block = b;
        s.value = term.operand(0);
        s.flag = t == loop->merge;
        s.then_body = {copies(b, loop->header)};
        s.else_body = {copies(b, loop->merge)};
        out.push_back(std::move(s));
        return 0;
    }
    if (!t_exit && !f_exit)
        unsupported(term, "a conditional branch between two blocks of the same construct without a merge instruction");
    if (loop && loop->in_continuing && (t_exit || f_exit) && (t == loop->merge || f == loop->merge))
        unsupported(term, "a conditional break nested inside a loop's continue construct");
    Statement s;
    s.kind = StatementKind::If;
    s.block = b;
    s.value = term.operand(0);
    s.exits = true;
    if (t_exit && f_exit) {
        s.then_body = exit_arm(b, t, stop, loop);
        s.else_body = exit_arm(b, f, stop, loop);
        s.flag = true;
        out.push_back(std::move(s));
        return 0;
    }
    const uint32_t exit = t_exit ? t : f, stay = t_exit ? f : t;
    (t_exit ? s.then_body : s.else_body) = exit_arm(b, exit, stop, loop);
    out.push_back(std::move(s));
    out.push_back(copies(b, stay));
    return stay;
}

Statement Structuriser::loop_construct(uint32_t header) {
    const Block& h = block(header);
    LoopContext ctx;
    ctx.header = header;
    ctx.merge = h.merge->operand(0);
    ctx.cont = h.merge->operand(1);
    Statement loop;
    loop.kind = StatementKind::Loop;
    loop.block = header;
    Statement instructions;
    instructions.kind = StatementKind::Block;
    instructions.block = header;
    loop.header.push_back(instructions);
    const Instruction& term = h.terminator;

    if (ctx.cont == header) {
        // A one-block loop: the header is its own continue target.
        if (term.op == spv::OpBranchConditional) {
            Statement exit;
            exit.kind = StatementKind::If;
            exit.exits = true;
            exit.block = header;
            exit.value = term.operand(0);
            Body leave{copies(header, ctx.merge), simple(StatementKind::Break)};
            (term.operand(1) == ctx.merge ? exit.then_body : exit.else_body) = std::move(leave);
            loop.header.push_back(std::move(exit));
        } else if (term.op != spv::OpBranch) {
            unsupported(term, "a loop header that ends the function");
        }
        loop.header.push_back(copies(header, header));
        return loop;
    }
    // The header either falls into the body or tests and leaves.
    uint32_t body = 0;
    if (term.op == spv::OpBranch) {
        body = term.operand(0);
        loop.header.push_back(copies(header, body));
    } else if (term.op == spv::OpBranchConditional) {
        body = conditional_exit(h, ctx.cont, &ctx, false, loop.header);
        if (!body) body = ctx.cont;
    } else {
        unsupported(term, "a loop header that ends the function");
    }
    if (body != ctx.cont) loop.body = region(body, ctx.cont, &ctx);
    LoopContext cont_ctx = ctx;
    cont_ctx.in_continuing = true;
    loop.continuing = region(ctx.cont, header, &cont_ctx, true);
    return loop;
}

}  // namespace

std::vector<PhiCopy> edge_copies(const Function& function, uint32_t from, uint32_t to) {
    std::vector<PhiCopy> copies;
    auto it = function.block_index.find(to);
    if (it == function.block_index.end()) return copies;
    for (const Instruction& phi : function.blocks[it->second].phis)
        for (size_t i = 0; i + 1 < phi.operands.size(); i += 2)
            if (phi.operands[i + 1] == from) copies.push_back({phi.result, phi.operands[i]});
    return copies;
}

bool copies_print(const std::vector<PhiCopy>& copies) {
    for (const PhiCopy& c : copies)
        if (c.phi != c.source) return true;
    if (copies.size() < 2) return false;
    for (const PhiCopy& c : copies)
        for (const PhiCopy& d : copies)
            if (c.source == d.phi) return true;
    return false;
}

Body structure_function(const Function& function) {
    if (function.blocks.empty()) fail("a function without blocks");
    return Structuriser(function).region(function.blocks.front().label, 0, nullptr);
}

}  // namespace crtforge::wgsl
