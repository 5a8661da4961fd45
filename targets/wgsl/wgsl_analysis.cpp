// The analysis pass over a structured function (see wgsl_analysis.hpp).
#include "targets/wgsl/wgsl_analysis.hpp"

#include <algorithm>

#include <spirv_cross/GLSL.std.450.h>

namespace crtforge::wgsl {

std::vector<uint32_t> value_operands(const Instruction& inst) {
    const auto& o = inst.operands;
    auto from = [&](size_t first) { return std::vector<uint32_t>(o.begin() + static_cast<long>(std::min(first, o.size())), o.end()); };
    auto first_n = [&](size_t n) { return std::vector<uint32_t>(o.begin(), o.begin() + static_cast<long>(std::min(n, o.size()))); };
    switch (inst.op) {
        case spv::OpExtInst: return from(2);
        case spv::OpCompositeExtract: case spv::OpLoad: case spv::OpBranchConditional: case spv::OpSwitch:
        case spv::OpReturnValue:
            return first_n(1);
        case spv::OpCompositeInsert: case spv::OpVectorShuffle: case spv::OpStore: return first_n(2);
        case spv::OpImageSampleImplicitLod: case spv::OpImageSampleExplicitLod: case spv::OpImageFetch: {
            std::vector<uint32_t> ids = first_n(2);
            for (size_t i = 3; i < o.size(); ++i) ids.push_back(o[i]);  // after the image-operands mask
            return ids;
        }
        case spv::OpFunctionCall: return from(1);
        case spv::OpVariable: return o.size() > 1 ? std::vector<uint32_t>{o[1]} : std::vector<uint32_t>{};
        case spv::OpBranch: case spv::OpReturn: case spv::OpKill: case spv::OpUnreachable:
        case spv::OpTerminateInvocation: case spv::OpSelectionMerge: case spv::OpLoopMerge:
            return {};
        default: return o;
    }
}

namespace {

// Ops whose WGSL spells an operand twice: a non-trivial operand must be a named value.
bool duplicates_operands(const Instruction& inst) {
    switch (inst.op) {
        case spv::OpFMod: case spv::OpSMod: case spv::OpFOrdNotEqual: case spv::OpFUnordEqual:
        case spv::OpVectorShuffle:
            return true;
        case spv::OpExtInst: {
            const auto e = operand_enum(inst.operand(1), GLSLstd450Count);
            return e == GLSLstd450SmoothStep || e == GLSLstd450FClamp;
        }
        default: return false;
    }
}

// Handles to resources are not values a WGSL variable can hold; they are resource names anywhere.
bool holds_value(const SpirvModule& m, uint32_t type) {
    switch (m.type(type).op) {
        case spv::OpTypePointer: case spv::OpTypeImage: case spv::OpTypeSampler: case spv::OpTypeSampledImage:
        case spv::OpTypeVoid:
            return false;
        default: return type != 0;
    }
}

class Analyser {
public:
    Analyser(const SpirvModule& m, const Function& f, FunctionAnalysis& out) : m_(m), f_(f), out_(out) {}

    void count_uses();
    int root_scope() { return open_scope(-1); }
    void walk(const Body& body, int scope);
    void hoist();

private:
    int open_scope(int parent) {
        parents_.push_back(parent);
        return static_cast<int>(parents_.size()) - 1;
    }
    void read(uint32_t id, int scope) { use_scopes_[id].insert(scope); }
    bool arm_prints(const Body& body) const;

    const SpirvModule& m_;
    const Function& f_;
    FunctionAnalysis& out_;
    std::map<uint32_t, uint32_t> def_block_;
    std::map<uint32_t, int> block_scope_;
    std::map<uint32_t, std::set<int>> use_scopes_;
    std::vector<int> parents_;
    int nesting_ = 0;
    bool early_exit_ = false;
};

void Analyser::count_uses() {
    for (const Instruction& p : f_.params) out_.types[p.result] = p.type;
    auto note = [&](const Instruction& inst, uint32_t block) {
        if (inst.result && inst.type) out_.types[inst.result] = inst.type;
        const int weight = duplicates_operands(inst) ? 2 : 1;
        for (uint32_t id : value_operands(inst)) {
            out_.uses[id] += weight;
            out_.use_blocks[id].insert(block);
        }
        if (inst.result) def_block_[inst.result] = block;
    };
    for (const Block& b : f_.blocks) {
        for (const Instruction& phi : b.phis) {
            out_.types[phi.result] = phi.type;
            for (size_t i = 0; i + 1 < phi.operands.size(); i += 2) {
                out_.uses[phi.operands[i]] += 1;
                if (b.phis.size() > 1) out_.phi_sources.insert(phi.operands[i]);
                out_.use_blocks[phi.operands[i]].insert(phi.operands[i + 1]);
            }
        }
        for (const Instruction& inst : b.body) note(inst, b.label);
        note(b.terminator, b.label);
    }
}

// Whether an exit arm writes anything: a break or continue, or copies that print.
bool Analyser::arm_prints(const Body& body) const {
    for (const Statement& s : body) {
        if (s.kind == StatementKind::PhiCopies) {
            if (copies_print(edge_copies(f_, s.block, s.target))) return true;
        } else {
            return true;
        }
    }
    return false;
}

// Scopes follow the WGSL braces: each arm, case, loop, loop body and continuing is one. Reads are
// recorded in the scope they are printed in; a block's terminator operands (conditions, selectors,
// returned values) in the block's own scope.
void Analyser::walk(const Body& body, int scope) {
    for (const Statement& s : body) {
        switch (s.kind) {
            case StatementKind::Block: {
                const Block& b = f_.block(s.block);
                block_scope_[s.block] = scope;
                out_.uniform_flow[s.block] = nesting_ == 0 && !early_exit_;
                for (const Instruction& inst : b.body)
                    for (uint32_t id : value_operands(inst)) read(id, scope);
                for (uint32_t id : value_operands(b.terminator)) read(id, scope);
                break;
            }
            case StatementKind::PhiCopies:
                for (const PhiCopy& c : edge_copies(f_, s.block, s.target)) read(c.source, scope);
                break;
            case StatementKind::If:
                ++nesting_;
                walk(s.then_body, open_scope(scope));
                walk(s.else_body, open_scope(scope));
                --nesting_;
                if (s.exits && (s.flag || arm_prints(s.then_body) || arm_prints(s.else_body))) early_exit_ = true;
                break;
            case StatementKind::Switch:
                ++nesting_;
                for (const SwitchCase& c : s.cases) walk(c.body, open_scope(scope));
                --nesting_;
                break;
            case StatementKind::Loop: {
                ++nesting_;
                const int loop_scope = open_scope(scope);
                walk(s.header, loop_scope);
                walk(s.body, open_scope(loop_scope));
                walk(s.continuing, open_scope(loop_scope));
                --nesting_;
                break;
            }
            case StatementKind::BreakIf:
                walk(s.then_body, scope);
                walk(s.else_body, scope);
                break;
            case StatementKind::Return:
                if (nesting_ > 0) early_exit_ = true;
                break;
            case StatementKind::Discard:
                early_exit_ = true;
                break;
            case StatementKind::Break:
            case StatementKind::Continue:
                break;
        }
    }
}

void Analyser::hoist() {
    for (const Block& b : f_.blocks)
        for (const Instruction& inst : b.body) {
            if (!inst.result || !holds_value(m_, inst.type)) continue;
            auto reads = use_scopes_.find(inst.result);
            auto def = block_scope_.find(b.label);
            if (reads == use_scopes_.end() || def == block_scope_.end()) continue;
            for (int s : reads->second) {
                int x = s;
                while (x != -1 && x != def->second) x = parents_[static_cast<size_t>(x)];
                if (x == -1) {
                    out_.hoisted.insert(inst.result);
                    break;
                }
            }
        }
}

}  // namespace

int FunctionAnalysis::use_count(uint32_t id) const {
    auto it = uses.find(id);
    return it == uses.end() ? 0 : it->second;
}

bool FunctionAnalysis::local_single_use(uint32_t id, uint32_t block) const {
    auto blocks = use_blocks.find(id);
    return use_count(id) == 1 && blocks != use_blocks.end() && blocks->second.size() == 1 &&
           *blocks->second.begin() == block && !phi_sources.count(id);
}

bool FunctionAnalysis::is_uniform(uint32_t block) const {
    auto it = uniform_flow.find(block);
    return it != uniform_flow.end() && it->second;
}

uint32_t FunctionAnalysis::type_of(uint32_t id, const SpirvModule& module) const {
    if (auto it = types.find(id); it != types.end()) return it->second;
    if (auto c = module.constants.find(id); c != module.constants.end()) return c->second.type;
    return 0;
}

FunctionAnalysis analyse_function(const SpirvModule& module, const Function& function, const Body& body) {
    FunctionAnalysis out;
    Analyser a(module, function, out);
    a.count_uses();
    a.walk(body, a.root_scope());
    a.hoist();
    return out;
}

}  // namespace crtforge::wgsl
