// Step 3 of printing a SPIR-V function as WGSL: the printer. It walks the statement tree
// (wgsl_structure.hpp) with the analysis (wgsl_analysis.hpp) in hand and writes WGSL: phis as
// function-scope variables assigned on each edge, every SSA value through one path (define) that
// inlines it into a single nearby pure use, names it with a `let`, builds it in a `var`, or assigns
// the function-scope variable it was hoisted to; and every instruction mapped with GLSL's semantics
// kept where WGSL's differ (see targets/wgsl/README.md).
#include <algorithm>
#include <cstring>
#include <functional>
#include <bit>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "targets/wgsl/wgsl_function_printer.hpp"

namespace crtforge::wgsl {

namespace {

constexpr size_t kInlineLimit = 64;  // longer single-use expressions still get their own `let`

const char* swizzle_letter(uint32_t i) {
    static const char* letters[] = {"x", "y", "z", "w"};
    return i < 4 ? letters[i] : "?";
}

}  // namespace


// ---------------------------------------------------------------------------------------------
// Statements

std::string FunctionPrinter::nested(const Body& body) {
    std::string saved;
    std::swap(saved, out_);
    ++indent_;
    print(body);
    --indent_;
    std::swap(saved, out_);
    return saved;
}

void FunctionPrinter::print(const Body& body) {
    for (const Statement& s : body) statement(s);
}

void FunctionPrinter::statement(const Statement& s) {
    switch (s.kind) {
        case StatementKind::Block:
            current_block_ = s.block;
            for (const Instruction& inst : f_.block(s.block).body) instruction(inst);
            return;
        case StatementKind::PhiCopies: phi_copies(s.block, s.target); return;
        case StatementKind::If: if_statement(s); return;
        case StatementKind::Switch: switch_statement(s); return;
        case StatementKind::Loop: loop_statement(s); return;
        case StatementKind::Break: line("break;"); return;
        case StatementKind::Continue: line("continue;"); return;
        case StatementKind::BreakIf: break_if(s); return;
        case StatementKind::Return: return_statement(s.value); return;
        case StatementKind::Discard:
            line("discard;");
            // WGSL's discard demotes the invocation and carries on: end the path as SPIR-V does.
            if (m_.type(f_.return_type).op != spv::OpTypeVoid || (is_entry_ && !entry_return_.empty())) return_statement(0);
            return;
    }
}

void FunctionPrinter::if_statement(const Statement& s) {
    const Expr cond = value(s.value);
    const std::string then_text = nested(s.then_body), else_text = nested(s.else_body);
    if (then_text.empty() && !else_text.empty()) {
        line("if (!" + cond.operand() + ") {");
        out_ += else_text;
        line("}");
    } else if (!then_text.empty()) {
        line("if (" + cond.text + ") {");
        out_ += then_text;
        if (!else_text.empty()) {
            line("} else {");
            out_ += else_text;
        }
        line("}");
    }
}

void FunctionPrinter::switch_statement(const Statement& s) {
    const Expr selector = value(s.value);
    const bool is_signed = m_.type(type_of(s.value)).is_signed;
    line("switch (" + selector.text + ") {");
    ++indent_;
    for (const SwitchCase& c : s.cases) {
        std::string head;
        for (size_t i = 0; i < c.literals.size(); ++i)
            head += (i ? ", " : "") + (is_signed ? i32_literal(static_cast<int32_t>(c.literals[i])) : u32_literal(c.literals[i]));
        if (c.is_default) head += c.literals.empty() ? "default" : ", default";
        line((c.literals.empty() ? "" : "case ") + head + ": {");
        out_ += nested(c.body);
        line("}");
    }
    --indent_;
    line("}");
}

void FunctionPrinter::loop_statement(const Statement& s) {
    line("loop {");
    ++indent_;
    print(s.header);
    print(s.body);
    const std::string continuing = nested(s.continuing);
    if (!continuing.empty()) {
        line("continuing {");
        out_ += continuing;
        line("}");
    }
    --indent_;
    line("}");
}

void FunctionPrinter::break_if(const Statement& s) {
    Expr cond = value(s.value);
    const std::string to_header = nested(s.then_body), to_merge = nested(s.else_body);
    if (!to_header.empty() || !to_merge.empty()) {
        if (cond.kind != Expr::Kind::Primary) {  // read twice below
            const std::string name = temp_name(s.value);
            line("let " + name + " = " + cond.text + ";");
            cond = Expr::name(name);
        }
        line("if (" + cond.text + ") {");
        out_ += s.flag ? to_merge : to_header;
        line("} else {");
        out_ += s.flag ? to_header : to_merge;
        line("}");
    }
    line(s.flag ? "break if " + cond.text + ";" : "break if !" + cond.operand() + ";");
}

void FunctionPrinter::phi_copies(uint32_t from, uint32_t to) {
    const std::vector<PhiCopy> copies = edge_copies(f_, from, to);
    // Parallel copy: a source that is itself a phi of this block is read before any is written.
    std::set<uint32_t> targets;
    for (const PhiCopy& c : copies) targets.insert(c.phi);
    std::map<uint32_t, std::string> snapshot;
    if (copies.size() > 1)
        for (const PhiCopy& c : copies)
            if (targets.count(c.source) && !snapshot.count(c.source)) {
                const std::string name = unique_identifier(phi_vars_.at(c.source) + "_prev", names_);
                line("let " + name + " = " + phi_vars_.at(c.source) + ";");
                snapshot[c.source] = name;
            }
    for (const PhiCopy& c : copies) {
        if (c.phi == c.source) continue;
        const std::string text = snapshot.count(c.source) ? snapshot[c.source] : value(c.source).text;
        line(phi_vars_.at(c.phi) + " = " + text + ";");
    }
}

void FunctionPrinter::return_statement(uint32_t returned) {
    if (returned) {
        line("return " + value(returned).text + ";");
    } else if (is_entry_ && !entry_return_.empty()) {
        line("return " + entry_return_ + ";");
    } else if (!is_entry_ && m_.type(f_.return_type).op != spv::OpTypeVoid) {
        line("return " + mod_.type_name(f_.return_type) + "();");
    } else {
        line("return;");
    }
}

// ---------------------------------------------------------------------------------------------
// Values

// The OpTypePointer of a pointer value: a local (variable, access chain, parameter) or a global.
const Type& FunctionPrinter::pointer_type(uint32_t pointer_id) const {
    if (auto it = pointer_types_.find(pointer_id); it != pointer_types_.end()) return m_.type(it->second);
    if (auto g = m_.globals.find(pointer_id); g != m_.globals.end()) return m_.type(g->second.type);
    return m_.type(0);
}

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
            const auto& members = mod_.struct_member_names[type];
            if (operands[i] >= members.size() || operands[i] >= t.members.size()) fail("a member index past the struct's end");
            path += "." + members[operands[i]];
            type = t.members[operands[i]];
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

void FunctionPrinter::define(const Instruction& inst, const Expr& expr, bool pure, bool always_inline) {
    const uint32_t id = inst.result;
    const int uses = analysis_.use_count(id);
    if (uses == 0 && pure) return;  // dead code stays out
    if (analysis_.hoisted.count(id)) {
        line(values_.at(id).text + " = " + expr.text + ";");
        return;
    }
    const bool local = analysis_.local_single_use(id, current_block_);
    if (pure && (always_inline || (local && expr.text.size() <= kInlineLimit))) {
        values_[id] = expr;
        return;
    }
    if (uses == 0) {  // a call nobody reads: keep the side effect
        line("_ = " + expr.text + ";");
        return;
    }
    const std::string name = temp_name(id);
    line("let " + name + " = " + expr.text + ";");
    values_[id] = Expr::name(name);
}

void FunctionPrinter::define_built(const Instruction& inst, const std::string& init,
                                   const std::function<std::string(const std::string&)>& update) {
    const uint32_t id = inst.result;
    if (analysis_.use_count(id) == 0) return;
    std::string name;
    if (analysis_.hoisted.count(id)) {
        name = values_.at(id).text;
        line(name + " = " + init + ";");
    } else {
        name = temp_name(id);
        line("var " + name + " = " + init + ";");
        values_[id] = Expr::name(name);
    }
    line(update(name) + ";");
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

// ---------------------------------------------------------------------------------------------

std::string FunctionPrinter::run() {
    const Body body = structure_function(f_);
    analysis_ = analyse_function(m_, f_, body);

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
            values_[p.result] = Expr::name(name);
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
            values_[phi.result] = Expr::name(name);
            declare("var " + name + ": " + mod_.type_name(phi.type) + ";");
        }
    for (const Block& b : f_.blocks)
        for (const Instruction& inst : b.body)
            if (analysis_.hoisted.count(inst.result)) {
                const std::string name = temp_name(inst.result);
                values_[inst.result] = Expr::name(name);
                declare("var " + name + ": " + mod_.type_name(inst.type) + ";");
            }

    print(body);
    std::string text = decls + out_;
    if (is_entry_) return text;
    std::string signature = "fn " + mod_.function_names.at(f_.id) + "(" + join_list(params) + ")";
    if (m_.type(f_.return_type).op != spv::OpTypeVoid) signature += " -> " + mod_.type_name(f_.return_type);
    return signature + " {\n" + text + "}\n";
}

// ---------------------------------------------------------------------------------------------
// Instructions

void FunctionPrinter::instruction(const Instruction& inst) {
    const auto& o = inst.operands;
    auto v = [&](size_t i) {
        if (i >= o.size()) unsupported(inst, "an operand is missing");
        return value(o[i]);
    };
    auto operand_id = [&](size_t i) {
        if (i >= o.size()) unsupported(inst, "an operand is missing");
        return o[i];
    };
    auto binary = [&](const char* op) {
        // Integer operands may differ in signedness from the result in SPIR-V, never in WGSL.
        const bool integer = m_.type(mod_.scalar_of(inst.type)).op == spv::OpTypeInt;
        const std::string a = integer ? typed(operand_id(0), inst.type) : v(0).operand();
        const std::string b = integer ? typed(operand_id(1), inst.type) : v(1).operand();
        define(inst, Expr::binary(a + " " + op + " " + b), true);
    };
    // Comparisons: operands converted to the first operand's type.
    auto compare = [&](const char* op) { define(inst, Expr::binary(v(0).operand() + " " + op + " " + v(1).operand()), true); };
    auto int_compare = [&](const char* op, bool want_signed) {
        auto cast = [&](size_t i) {
            const Expr e = v(i);
            const uint32_t ty = type_of(o[i]);
            if (m_.type(mod_.scalar_of(ty)).is_signed == want_signed) return e.operand();
            const uint32_t n = mod_.component_count(ty);
            const char* scalar = want_signed ? "i32" : "u32";
            const std::string target = n == 1 ? std::string(scalar) : fmt::format("vec{}<{}>", n, scalar);
            return "bitcast<" + target + ">(" + e.text + ")";
        };
        define(inst, Expr::binary(cast(0) + " " + op + " " + cast(1)), true);
    };
    auto call = [&](const std::string& name, std::initializer_list<size_t> args) {
        std::vector<std::string> texts;
        for (size_t i : args) texts.push_back(v(i).text);
        define(inst, Expr::primary(name + "(" + join_list(texts) + ")"), true);
    };
    const bool vector_bool = mod_.component_count(inst.type) > 1;

    switch (inst.op) {
        case spv::OpNop: case spv::OpLine: case spv::OpNoLine: return;
        case spv::OpUndef: define(inst, Expr::primary(mod_.type_name(inst.type) + "()"), true, true); return;

        // -- memory --
        case spv::OpLoad: {
            const uint32_t pointer = operand_id(0);
            const spv::StorageClass storage = pointer_type(pointer).storage;
            const uint32_t t = m_.type(inst.type).op;
            if (t == spv::OpTypeSampledImage) {
                const std::string texture = ref(pointer);
                auto sampler = mod_.sampler_names.find(pointer);
                if (sampler == mod_.sampler_names.end()) unsupported(inst, "a combined image sampler that is not a module variable");
                images_[inst.result] = {texture, sampler->second};
                return;
            }
            if (t == spv::OpTypeImage || t == spv::OpTypeSampler) {
                images_[inst.result] = {t == spv::OpTypeImage ? ref(pointer) : "", t == spv::OpTypeSampler ? ref(pointer) : ""};
                return;
            }
            const bool immutable = storage == spv::StorageClassUniform || storage == spv::StorageClassInput ||
                                   storage == spv::StorageClassUniformConstant;
            // Reads of the uniform block and the stage inputs are immutable: always inline them.
            define(inst, Expr::primary(ref(pointer)), immutable, immutable);
            return;
        }
        case spv::OpStore:
            line(ref(operand_id(0)) + " = " + v(1).text + ";");
            return;
        case spv::OpCopyMemory:
            line(ref(operand_id(0)) + " = " + ref(operand_id(1)) + ";");
            return;
        case spv::OpAccessChain:
        case spv::OpInBoundsAccessChain: {
            const uint32_t base = operand_id(0);
            std::string text;
            uint32_t current = pointer_type(base).element;
            size_t first = 1;
            auto literal = [&](size_t i) {
                auto c = m_.constants.find(operand_id(i));
                if (c == m_.constants.end() || c->second.words.empty()) unsupported(inst, "a struct member index that is not a constant");
                return c->second.words[0];
            };
            auto member_type = [&](uint32_t type, uint32_t member) {
                const Type& t = m_.type(type);
                if (member >= t.members.size()) unsupported(inst, "a member index past the struct's end");
                return t.members[member];
            };
            // gl_PerVertex-style output blocks are split into one local per member.
            bool handled = false;
            for (const auto& out : mod_.interface.outputs)
                if (out.variable == base && !out.block_members.empty()) {
                    const uint32_t member = literal(1);
                    auto it = out.block_members.find(member);
                    if (it == out.block_members.end())
                        unsupported(inst, "writing gl_PointSize, gl_ClipDistance or gl_CullDistance, which WGSL lacks");
                    text = it->second;
                    current = member_type(current, member);
                    first = 2;
                    handled = true;
                }
            if (!handled) text = ref(base);
            for (size_t i = first; i < o.size(); ++i) {
                const Type& t = m_.type(current);
                if (t.op == spv::OpTypeStruct) {
                    const uint32_t member = literal(i);
                    const uint32_t struct_type = current;
                    current = member_type(current, member);
                    mod_.struct_name(struct_type);
                    text += "." + mod_.struct_member_names[struct_type].at(member);
                } else if (t.op == spv::OpTypeVector && mod_.is_constant(o[i])) {
                    text += std::string(".") + swizzle_letter(literal(i));
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
        case spv::OpCopyObject: {
            const uint32_t source = operand_id(0);
            if (refs_.count(source)) refs_[inst.result] = refs_[source];
            else if (images_.count(source)) images_[inst.result] = images_[source];
            else define(inst, value(source), true, value(source).named);
            return;
        }

        // -- composites --
        case spv::OpCompositeConstruct: {
            std::vector<std::string> parts;
            for (uint32_t id : o) parts.push_back(value(id).text);
            define(inst, Expr::primary(mod_.type_name(inst.type) + "(" + join_list(parts) + ")"), true);
            return;
        }
        case spv::OpCompositeExtract: {
            if (!type_of(operand_id(0))) unsupported(inst, "the composite's type is unknown");
            const Expr base = v(0);
            // Member reads of a named value are free to repeat; of an expression, they get a let.
            define(inst, Expr::primary(base.operand() + composite_path(type_of(o[0]), o, 1)), true,
                   base.text.find('(') == std::string::npos);
            return;
        }
        case spv::OpCompositeInsert: {
            const std::string object = v(0).text, init = v(1).text;
            const std::string path = composite_path(inst.type, o, 2);
            define_built(inst, init, [&](const std::string& name) { return name + path + " = " + object; });
            return;
        }
        case spv::OpVectorShuffle: {
            const Expr a = v(0), b = v(1);
            const uint32_t a_count = mod_.component_count(type_of(o[0]));
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
                define(inst, Expr::primary((all_a ? a : b).operand() + "." + swizzle), true);
            } else {
                std::vector<std::string> parts;
                for (size_t i = 2; i < o.size(); ++i)
                    parts.push_back((o[i] < a_count ? a : b).operand() + "." + component(o[i]));
                define(inst, Expr::primary(mod_.type_name(inst.type) + "(" + join_list(parts) + ")"), true);
            }
            return;
        }
        case spv::OpVectorExtractDynamic:
            define(inst, Expr::primary(v(0).operand() + "[" + v(1).text + "]"), true);
            return;
        case spv::OpVectorInsertDynamic: {
            const std::string init = v(0).text, component = v(1).text, index = v(2).text;
            define_built(inst, init, [&](const std::string& name) { return name + "[" + index + "] = " + component; });
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
            define(inst, Expr::binary(x + " - " + y + " * floor(" + x + " / " + y + ")"), true);
            return;
        }
        case spv::OpSMod: {
            if (analysis_.use_count(inst.result) == 0) return;  // dead, and pure
            // Remainder with the sign of the divisor, from WGSL's truncating %.
            const std::string x = typed(operand_id(0), inst.type), y = typed(operand_id(1), inst.type);
            const std::string r = temp_name(inst.result) + "_rem";
            line("let " + r + " = " + x + " % " + y + ";");
            const std::string zero = mod_.type_name(inst.type) + "()";
            define(inst, Expr::primary("select(" + r + ", " + r + " + " + y + ", (" + r + " != " + zero + ") & ((" + r + " < " +
                                       zero + ") != (" + y + " < " + zero + ")))"),
                   true);
            return;
        }
        case spv::OpFNegate: case spv::OpSNegate: define(inst, Expr::unary("-" + v(0).operand()), true); return;
        case spv::OpDot: call("dot", {0, 1}); return;
        case spv::OpTranspose: call("transpose", {0}); return;

        // -- bits --
        case spv::OpBitwiseAnd: binary("&"); return;
        case spv::OpBitwiseOr: binary("|"); return;
        case spv::OpBitwiseXor: binary("^"); return;
        case spv::OpNot: define(inst, Expr::unary("~" + v(0).operand()), true); return;
        case spv::OpShiftLeftLogical:
        case spv::OpShiftRightLogical:
        case spv::OpShiftRightArithmetic: {
            const uint32_t n = mod_.component_count(inst.type);
            const std::string u = n == 1 ? "u32" : fmt::format("vec{}<u32>", n);
            const std::string si = n == 1 ? "i32" : fmt::format("vec{}<i32>", n);
            // WGSL wants an unsigned shift count; the shifted value's signedness picks the shift kind.
            std::string amount = "bitcast<" + u + ">(" + v(1).text + ")";
            if (auto c = m_.constants.find(operand_id(1)); n == 1 && c != m_.constants.end() && c->second.op == spv::OpConstant &&
                                                           !c->second.words.empty())
                amount = u32_literal(c->second.words[0]);
            const bool result_signed = m_.type(mod_.scalar_of(inst.type)).is_signed;
            if (inst.op == spv::OpShiftLeftLogical) {
                define(inst, Expr::binary(typed(o[0], inst.type) + " << " + amount), true);
            } else {
                const std::string kind = inst.op == spv::OpShiftRightLogical ? u : si;
                const std::string text = "bitcast<" + kind + ">(" + v(0).text + ") >> " + amount;
                if ((kind == si) != result_signed)
                    define(inst, Expr::primary("bitcast<" + mod_.type_name(inst.type) + ">(" + text + ")"), true);
                else
                    define(inst, Expr::binary(text), true);
            }
            return;
        }
        case spv::OpBitCount: call("countOneBits", {0}); return;
        case spv::OpBitReverse: call("reverseBits", {0}); return;

        // -- conversions --
        case spv::OpConvertFToS: case spv::OpConvertFToU: case spv::OpConvertSToF: case spv::OpConvertUToF:
        case spv::OpFConvert:
            call(mod_.type_name(inst.type), {0});
            return;
        case spv::OpBitcast: case spv::OpSConvert: case spv::OpUConvert:
            call("bitcast<" + mod_.type_name(inst.type) + ">", {0});
            return;
        case spv::OpQuantizeToF16: call("quantizeToF16", {0}); return;

        // -- relational and logical --
        case spv::OpFOrdEqual: case spv::OpLogicalEqual: compare("=="); return;
        case spv::OpFUnordNotEqual: case spv::OpLogicalNotEqual: compare("!="); return;
        case spv::OpFOrdLessThan: compare("<"); return;
        case spv::OpFOrdGreaterThan: compare(">"); return;
        case spv::OpFOrdLessThanEqual: compare("<="); return;
        case spv::OpFOrdGreaterThanEqual: compare(">="); return;
        // Unordered comparisons are true when an operand is NaN: the negated opposite ordered test.
        case spv::OpFUnordLessThan: define(inst, Expr::unary("!(" + v(0).operand() + " >= " + v(1).operand() + ")"), true); return;
        case spv::OpFUnordGreaterThan: define(inst, Expr::unary("!(" + v(0).operand() + " <= " + v(1).operand() + ")"), true); return;
        case spv::OpFUnordLessThanEqual: define(inst, Expr::unary("!(" + v(0).operand() + " > " + v(1).operand() + ")"), true); return;
        case spv::OpFUnordGreaterThanEqual: define(inst, Expr::unary("!(" + v(0).operand() + " < " + v(1).operand() + ")"), true); return;
        case spv::OpFOrdNotEqual: {
            // Ordered: false for NaN, which WGSL's != (true for NaN) is not.
            const char* join = vector_bool ? " | " : " || ";
            define(inst, Expr::binary("(" + v(0).operand() + " < " + v(1).operand() + ")" + join + "(" + v(0).operand() + " > " +
                                      v(1).operand() + ")"),
                   true);
            return;
        }
        case spv::OpFUnordEqual: {
            const char* join = vector_bool ? " | " : " || ";
            define(inst, Expr::unary("!((" + v(0).operand() + " < " + v(1).operand() + ")" + join + "(" + v(0).operand() + " > " +
                                     v(1).operand() + "))"),
                   true);
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
        case spv::OpLogicalNot: define(inst, Expr::unary("!" + v(0).operand()), true); return;
        case spv::OpAny: call("any", {0}); return;
        case spv::OpAll: call("all", {0}); return;
        case spv::OpIsNan:
        case spv::OpIsInf: {
            // By the bits: WGSL lets compilers assume there are no NaNs or infinities in float maths.
            const uint32_t n = mod_.component_count(inst.type);
            const std::string u = n == 1 ? "u32" : fmt::format("vec{}<u32>", n);
            auto splat = [&](const char* c) { return n == 1 ? std::string(c) : u + "(" + c + ")"; };
            define(inst, Expr::binary("(bitcast<" + u + ">(" + v(0).text + ") & " + splat("0x7fffffffu") + ") " +
                                      (inst.op == spv::OpIsNan ? "> " : "== ") + splat("0x7f800000u")),
                   true);
            return;
        }
        case spv::OpSelect: call("select", {2, 1, 0}); return;  // select(false_value, true_value, condition)

        // -- derivatives --
        case spv::OpDPdx: case spv::OpDPdy: case spv::OpFwidth: case spv::OpDPdxFine: case spv::OpDPdyFine:
        case spv::OpFwidthFine: case spv::OpDPdxCoarse: case spv::OpDPdyCoarse: case spv::OpFwidthCoarse: {
            static const std::map<spv::Op, const char*> names = {
                {spv::OpDPdx, "dpdx"}, {spv::OpDPdy, "dpdy"}, {spv::OpFwidth, "fwidth"},
                {spv::OpDPdxFine, "dpdxFine"}, {spv::OpDPdyFine, "dpdyFine"}, {spv::OpFwidthFine, "fwidthFine"},
                {spv::OpDPdxCoarse, "dpdxCoarse"}, {spv::OpDPdyCoarse, "dpdyCoarse"}, {spv::OpFwidthCoarse, "fwidthCoarse"}};
            needs_uniform_flow();
            call(names.at(inst.op), {0});
            return;
        }

        case spv::OpExtInst: ext_instruction(inst); return;
        case spv::OpSampledImage: {
            auto t = images_.find(operand_id(0));
            auto smp = images_.find(operand_id(1));
            if (t == images_.end() || smp == images_.end()) unsupported(inst);
            images_[inst.result] = {t->second.first, smp->second.second};
            return;
        }
        case spv::OpImage: {
            auto t = images_.find(operand_id(0));
            if (t == images_.end()) unsupported(inst);
            images_[inst.result] = {t->second.first, ""};
            return;
        }
        case spv::OpImageSampleImplicitLod: case spv::OpImageSampleExplicitLod: case spv::OpImageFetch: case spv::OpImageGather:
        case spv::OpImageQuerySizeLod: case spv::OpImageQuerySize: case spv::OpImageQueryLevels:
            image_instruction(inst);
            return;

        case spv::OpFunctionCall: {
            auto callee = mod_.function_names.find(operand_id(0));
            if (callee == mod_.function_names.end()) unsupported(inst, "a call to a function the module does not define");
            std::vector<std::string> args;
            for (size_t i = 1; i < o.size(); ++i) {
                if (auto p = pointer_params_.find(o[i]); p != pointer_params_.end()) args.push_back(p->second);  // already a pointer
                else if (refs_.count(o[i])) args.push_back("&" + refs_[o[i]]);
                else args.push_back(value(o[i]).text);
            }
            const std::string text = callee->second + "(" + join_list(args) + ")";
            if (m_.type(inst.type).op == spv::OpTypeVoid) line(text + ";");
            else define(inst, Expr::primary(text), false);
            return;
        }
        default:
            unsupported(inst);
    }
}

std::string emit_function_body(ModuleEmitter& module, const Function& function, bool is_entry,
                               const std::string& entry_return, NameScope& local_names) {
    FunctionPrinter printer(module, function, is_entry, entry_return, local_names);
    return printer.run();
}

}  // namespace crtforge::wgsl
