// Module-level WGSL: types and struct layouts, constants, resources (combined image samplers split
// into a texture and a sampler), the stage interface, the entry point, and the merge of several
// stages into one module.
#include <algorithm>
#include <cstring>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include <spirv_cross/spirv_cross_error_handling.hpp>

#include "targets/spirv_split_io_structs.hpp"
#include "targets/wgsl/wgsl_context.hpp"
#include "targets/wgsl/wgsl_names.hpp"

namespace crtforge::wgsl {

void fail(const std::string& message, const SourceLine& line) { throw EmitError{message, line}; }

void unsupported(const Instruction& inst, const std::string& why) {
    fail("cannot translate " + opcode_name(inst.op) + " to WGSL" + (why.empty() ? "" : ": " + why), inst.line);
}

namespace {

uint32_t round_up(uint32_t align, uint32_t value) { return (value + align - 1) / align * align; }

const char* storage_class_name(spv::StorageClass s) {
    switch (s) {
        case spv::StorageClassUniformConstant: return "UniformConstant";
        case spv::StorageClassInput: return "Input";
        case spv::StorageClassUniform: return "Uniform";
        case spv::StorageClassOutput: return "Output";
        case spv::StorageClassWorkgroup: return "Workgroup";
        case spv::StorageClassPrivate: return "Private";
        case spv::StorageClassFunction: return "Function";
        case spv::StorageClassPushConstant: return "PushConstant";
        case spv::StorageClassStorageBuffer: return "StorageBuffer";
        default: return "another storage class";
    }
}

}  // namespace

ModuleEmitter::ModuleEmitter(const SpirvModule& module, const EmitOptions& opts, NameScope& names, SharedResources& shared,
                             const std::string& stage, const std::string& entry)
    : m(module), options(opts), stage_name(stage), entry_name(entry), global_names(names), shared_resources(shared) {}

std::string ModuleEmitter::helper(const std::string& wanted, const std::string& definition_after_name) {
    auto named = shared_resources.helper_names.find(wanted);
    const std::string name = named != shared_resources.helper_names.end() ? named->second : module_scope_name(wanted);
    shared_resources.helper_names[wanted] = name;
    helpers[name] = "fn " + name + definition_after_name;
    return name;
}

std::string ModuleEmitter::module_scope_name(const std::string& wanted) {
    NameScope both = global_names;
    both.insert(stage_names);
    const std::string name = unique_identifier(wanted, both);
    global_names.insert(name);
    stage_names.insert(name);
    return name;
}

uint32_t ModuleEmitter::scalar_of(uint32_t type_id) const {
    const Type& t = type(type_id);
    return t.op == spv::OpTypeVector ? t.element : type_id;
}

uint32_t ModuleEmitter::component_count(uint32_t type_id) const {
    const Type& t = type(type_id);
    return t.op == spv::OpTypeVector ? t.count : 1;
}

std::string ModuleEmitter::type_name(uint32_t id) {
    const Type& t = type(id);
    switch (t.op) {
        case spv::OpTypeBool: return "bool";
        case spv::OpTypeFloat:
            if (t.width != 32) fail(fmt::format("{}-bit floats have no WGSL type here (only f32)", t.width));
            return "f32";
        case spv::OpTypeInt:
            if (t.width != 32) fail(fmt::format("{}-bit integers have no WGSL type (only 32-bit)", t.width));
            return t.is_signed ? "i32" : "u32";
        case spv::OpTypeVector: return fmt::format("vec{}<{}>", t.count, type_name(t.element));
        case spv::OpTypeMatrix: {
            const Type& column = type(t.element);
            return fmt::format("mat{}x{}<{}>", t.count, column.count, type_name(column.element));
        }
        case spv::OpTypeArray: return fmt::format("array<{}, {}>", type_name(t.element), t.count);
        case spv::OpTypeStruct: return struct_name(id);
        case spv::OpTypeSampler: return "sampler";
        case spv::OpTypeImage: {
            if (t.depth) fail("depth textures are not supported by crtforge's WGSL emitter");
            const std::string sampled = type_name(t.element);
            if (t.multisampled) return "texture_multisampled_2d<" + sampled + ">";
            switch (t.dim) {
                case spv::Dim1D: return "texture_1d<" + sampled + ">";
                case spv::Dim2D: return (t.arrayed ? "texture_2d_array<" : "texture_2d<") + sampled + ">";
                case spv::Dim3D: return "texture_3d<" + sampled + ">";
                case spv::DimCube: return (t.arrayed ? "texture_cube_array<" : "texture_cube<") + sampled + ">";
                default: fail("image dimensionality has no WGSL texture type");
            }
        }
        case spv::OpTypeVoid: return "";
        default: fail(fmt::format("type {} has no WGSL equivalent", opcode_name(t.op)));
    }
}

std::string ModuleEmitter::struct_name(uint32_t id) {
    auto it = struct_names_.find(id);
    if (it != struct_names_.end()) return it->second;
    return declare_struct(id);
}

// WGSL's uniform-address-space alignment and size of a type (std140 rules where they agree).
namespace {
struct Layout {
    uint32_t align = 4, size = 4;
};
}  // namespace

std::string ModuleEmitter::declare_struct(uint32_t id) {
    const Type& t = type(id);
    std::string wanted = m.name(id);
    if (wanted.empty()) wanted = "Struct";
    const std::string name = module_scope_name(wanted);
    struct_names_[id] = name;

    // Layout, computed the way WGSL computes it, then checked against the SPIR-V Offsets.
    std::function<Layout(uint32_t)> layout = [&](uint32_t type_id) -> Layout {
        const Type& ty = type(type_id);
        switch (ty.op) {
            case spv::OpTypeVector: {
                Layout e = layout(ty.element);
                const uint32_t n = ty.count == 3 ? 4 : ty.count;
                return {e.size * n, e.size * ty.count};
            }
            case spv::OpTypeMatrix: {
                Layout column = layout(ty.element);
                return {column.align, ty.count * round_up(column.align, column.size)};
            }
            case spv::OpTypeArray: {
                Layout e = layout(ty.element);
                return {e.align, ty.count * round_up(e.align, e.size)};
            }
            case spv::OpTypeStruct: {
                Layout s{1, 0};
                for (size_t i = 0; i < ty.members.size(); ++i) {
                    Layout member = layout(ty.members[i]);
                    s.align = std::max(s.align, member.align);
                    auto d = m.member_decorations.find({type_id, static_cast<uint32_t>(i)});
                    const uint32_t offset = d != m.member_decorations.end() && d->second.offset
                                                ? *d->second.offset : round_up(member.align, s.size);
                    s.size = offset + member.size;
                }
                s.align = round_up(16, s.align);
                s.size = round_up(s.align, s.size);
                return s;
            }
            default: return {4, 4};
        }
    };

    struct Member {
        std::string name, type;
        std::optional<uint32_t> offset;
        uint32_t size_attribute = 0;  // @size(n) when the next member starts later than WGSL would put it
    };
    NameScope member_names;
    std::vector<Member> members;
    uint32_t end = 0;
    for (size_t i = 0; i < t.members.size(); ++i) {
        const uint32_t member_type = t.members[i];
        auto mn = m.member_names.find({id, static_cast<uint32_t>(i)});
        Member member{unique_identifier(mn != m.member_names.end() ? mn->second : fmt::format("m{}", i), member_names),
                      type_name(member_type), std::nullopt, 0};
        auto d = m.member_decorations.find({id, static_cast<uint32_t>(i)});
        if (d != m.member_decorations.end() && d->second.offset) {
            const Layout l = layout(member_type);
            const uint32_t offset = *d->second.offset;
            const uint32_t natural = round_up(l.align, end);
            if (offset < natural || (i == 0 && offset != 0))
                fail(fmt::format("member {} of {} is at byte {}, where WGSL's layout puts it at {}", member.name, name,
                                 offset, natural));
            if (offset > natural) members.back().size_attribute = offset - *members.back().offset;
            const Type& mt = type(member_type);
            if (mt.op == spv::OpTypeArray) {
                auto stride = m.decorations.find(member_type);
                const uint32_t s = stride != m.decorations.end() && stride->second.array_stride ? *stride->second.array_stride : 0;
                const Layout e = layout(mt.element);
                if (s % 16 != 0 || s != round_up(e.align, e.size))
                    fail(fmt::format("array member {} of {} has stride {}; WGSL uniform arrays need the element's own "
                                     "stride, a multiple of 16", member.name, name, s));
            }
            member.offset = offset;
            end = offset + l.size;
            struct_layouts[id].push_back({member.name, member.type, offset, l.size});
        }
        members.push_back(member);
    }
    for (const Member& member : members) struct_member_names[id].push_back(member.name);
    struct_sizes[id] = layout(id).size;
    std::string decl = "struct " + name + " {\n";
    for (const Member& member : members) {
        decl += "  ";
        if (member.size_attribute) decl += fmt::format("@size({}) ", member.size_attribute);
        decl += member.name + ": " + member.type + ",";
        if (member.offset) decl += fmt::format("  // offset {}", *member.offset);
        decl += "\n";
    }
    decl += "}\n";
    struct_decls[name] = decl;
    struct_order.push_back(name);
    return name;
}

Expr ModuleEmitter::constant(uint32_t id) {
    const Constant& c = m.constants.at(id);
    const Type& t = type(c.type);
    auto zero = [&]() -> Expr { return Expr::name(type_name(c.type) + "()"); };
    switch (c.op) {
        case spv::OpConstantTrue: return Expr::name("true");
        case spv::OpConstantFalse: return Expr::name("false");
        case spv::OpConstantNull:
        case spv::OpUndef: return zero();
        case spv::OpConstant: {
            const uint32_t bits = c.words.empty() ? 0 : c.words[0];
            if (t.op == spv::OpTypeFloat) {
                if (t.width != 32) fail("only 32-bit float constants are supported");
                if ((bits & 0x7f800000u) == 0x7f800000u) {
                    // An infinity or a NaN (spirv-opt folds 1.0 / 0.0 into one): WGSL refuses a constant
                    // expression whose value is not finite, even bitcast<f32>(0x7f800000u), so it comes
                    // from a function, which is never a constant expression.
                    const std::string from_bits = helper("f32_from_bits",
                        "(bits: u32) -> f32 {\n"
                        "  // a value that is not finite: a constant expression may not compute one\n"
                        "  return bitcast<f32>(bits);\n"
                        "}\n");
                    return Expr::name(from_bits + "(" + u32_literal(bits) + ")");
                }
                std::string text = f32_literal(bits);
                return Expr::name(text[0] == '-' ? "(" + text + ")" : text);
            }
            if (t.op == spv::OpTypeInt) {
                if (t.width != 32) fail("only 32-bit integer constants are supported");
                return Expr::name(t.is_signed ? i32_literal(static_cast<int32_t>(bits)) : u32_literal(bits));
            }
            fail("constant of an unexpected type");
        }
        case spv::OpConstantComposite: {
            std::vector<std::string> parts;
            for (uint32_t part : c.words) parts.push_back(constant(part).text);
            // A vector of one repeated value reads better as a splat.
            if (t.op == spv::OpTypeVector && std::all_of(parts.begin(), parts.end(), [&](auto& p) { return p == parts[0]; }))
                return Expr::name(type_name(c.type) + "(" + parts[0] + ")");
            std::string text = type_name(c.type) + "(";
            for (size_t i = 0; i < parts.size(); ++i) text += (i ? ", " : "") + parts[i];
            return Expr::name(text + ")");
        }
        default: fail("unsupported constant " + opcode_name(c.op));
    }
}

void ModuleEmitter::declare_resources() {
    // Samplers split off combined image samplers go after every binding any stage uses.
    std::map<uint32_t, uint32_t>& next_binding = shared_resources.next_sampler_binding;
    for (const auto& [id, var] : m.globals) {
        const Type& pointer = type(var.type);
        const spv::StorageClass storage = pointer.storage;
        if (storage == spv::StorageClassInput || storage == spv::StorageClassOutput) continue;
        if (storage == spv::StorageClassPrivate) {
            private_globals[id] = &var;
            continue;
        }
        if (storage != spv::StorageClassUniform && storage != spv::StorageClassUniformConstant)
            fail(fmt::format("variable '{}' is in {} storage, which crtforge's WGSL emitter does not map "
                             "(uniform blocks, textures and samplers only)", m.name(id), storage_class_name(storage)));
        auto d = m.decorations.find(id);
        if (d == m.decorations.end() || !d->second.binding)
            fail(fmt::format("resource '{}' has no binding decoration", m.name(id)));
        const uint32_t group = d->second.set.value_or(0), binding = *d->second.binding;
        const Type& pointee = type(pointer.element);
        std::string wanted = m.name(id);
        WgslBinding b;
        b.group = group;
        b.binding = binding;
        b.stages = {stage_name};
        if (storage == spv::StorageClassUniform) {
            if (pointee.op != spv::OpTypeStruct) fail("a uniform variable that is not a block");
            std::string sname = struct_name(pointer.element);
            if (wanted.empty() || wanted == "_") {
                auto named = options.block_instance_names.find(m.name(pointer.element));
                wanted = named != options.block_instance_names.end() ? named->second : "params";
            }
            // The same block at the same binding as an earlier stage's: that declaration, shared.
            const std::string& decl = struct_decls.at(sname);
            const std::string body = decl.substr(decl.find('{'));
            std::string name;
            if (auto shared = shared_resources.uniforms.find({group, binding});
                shared != shared_resources.uniforms.end() && shared->second.body == body) {
                struct_decls.erase(sname);
                struct_order.erase(std::find(struct_order.begin(), struct_order.end(), sname));
                sname = struct_names_[pointer.element] = shared->second.struct_name;
                name = shared->second.variable;
            } else {
                name = module_scope_name(wanted);
                shared_resources.uniforms.emplace(std::make_pair(group, binding), SharedUniform{sname, name, body});
            }
            resource_names[id] = name;
            resource_decls[{group, binding}] =
                fmt::format("@group({}) @binding({}) var<uniform> {}: {};\n", group, binding, name, sname);
            b.name = name;
            b.kind = "uniform-buffer";
            b.wgsl_type = sname;
            // The buffer size WebGPU checks: the struct's size under WGSL's layout rules.
            for (size_t i = 0; i < pointee.members.size(); ++i)
                if (type(pointee.members[i]).op == spv::OpTypeStruct) fail("nested structs in a uniform block are not supported");
            b.members = struct_layouts[pointer.element];
            const uint32_t size = struct_sizes[pointer.element];
            b.size = round_up(16, size);
            bindings.push_back(b);
            continue;
        }
        // UniformConstant: a combined image sampler, a texture, or a sampler.
        if (wanted.empty()) wanted = pointee.op == spv::OpTypeSampler ? "samp" : "tex";
        const bool is_texture = pointee.op == spv::OpTypeSampledImage || pointee.op == spv::OpTypeImage;
        const uint32_t image = pointee.op == spv::OpTypeSampledImage ? pointee.element : pointer.element;
        const std::string texture_type = is_texture ? type_name(image) : "";
        const auto shared = shared_resources.textures.find({group, binding});
        const bool reuse = is_texture && shared != shared_resources.textures.end() && shared->second.type == texture_type &&
                           shared->second.sampler.empty() == (pointee.op != spv::OpTypeSampledImage);
        const std::string name = reuse ? shared->second.name : module_scope_name(wanted);
        resource_names[id] = name;
        if (auto border = options.emulate_border.find(m.name(id)); is_texture && border != options.emulate_border.end()) {
            if (type(image).dim != spv::Dim2D) fail("clamp_to_border emulation on '" + m.name(id) + "', which is not a 2D texture");
            border_textures[name] = border->second;
            // Named now, before any function's locals, so that no local can shadow it.
            const std::string helper = border->second ? "border_weight_linear" : "border_weight_nearest";
            if (!shared_resources.helper_names.count(helper)) shared_resources.helper_names[helper] = module_scope_name(helper);
        }
        if (is_texture) {
            resource_decls[{group, binding}] = fmt::format("@group({}) @binding({}) var {}: {};\n", group, binding, name, texture_type);
            b.name = name;
            b.kind = "texture";
            b.wgsl_type = texture_type;
            b.sample_type = type(type(image).element).op == spv::OpTypeFloat ? "float" : type(type(image).element).is_signed ? "sint" : "uint";
            if (!reuse) shared_resources.textures.emplace(std::make_pair(group, binding), SharedTexture{name, texture_type, "", 0});
            if (pointee.op == spv::OpTypeSampledImage) {
                SharedTexture& st = shared_resources.textures.at({group, binding});
                if (!reuse) {
                    st.sampler_binding = next_binding[group]++;
                    st.sampler = module_scope_name(name + "_sampler");
                }
                const uint32_t sampler_binding = st.sampler_binding;
                const std::string sampler = st.sampler;
                sampler_names[id] = sampler;
                resource_decls[{group, sampler_binding}] =
                    fmt::format("@group({}) @binding({}) var {}: sampler;\n", group, sampler_binding, sampler);
                b.paired_with = sampler;
                WgslBinding s;
                s.group = group;
                s.binding = sampler_binding;
                s.name = sampler;
                s.kind = "sampler";
                s.wgsl_type = "sampler";
                s.paired_with = name;
                s.border_in_shader = border_textures.count(name) != 0;
                s.stages = {stage_name};
                bindings.push_back(s);
            }
            bindings.push_back(b);
        } else if (pointee.op == spv::OpTypeSampler) {
            resource_decls[{group, binding}] = fmt::format("@group({}) @binding({}) var {}: sampler;\n", group, binding, name);
            b.name = name;
            b.kind = "sampler";
            b.wgsl_type = "sampler";
            bindings.push_back(b);
        } else {
            fail(fmt::format("uniform-constant variable '{}' of type {} is not supported", name, opcode_name(pointee.op)));
        }
    }
}

std::vector<ModuleEmitter::IoSlot> ModuleEmitter::io_slots(uint32_t type_id) {
    const Type& t = type(type_id);
    std::vector<IoSlot> out;
    switch (t.op) {
        case spv::OpTypeFloat: case spv::OpTypeInt: case spv::OpTypeVector:
            out.push_back({type_id, ""});
            break;
        case spv::OpTypeMatrix:
            for (uint32_t j = 0; j < t.count; ++j) out.push_back({t.element, fmt::format("[{}]", j)});
            break;
        case spv::OpTypeArray:
            for (uint32_t i = 0; i < t.count; ++i)
                for (const IoSlot& s : io_slots(t.element)) out.push_back({s.type, fmt::format("[{}]{}", i, s.path)});
            break;
        default: fail("stage input or output of type " + type_name(type_id) + " has no WGSL form");
    }
    return out;
}

std::string ModuleEmitter::rebuild_from_slots(uint32_t type_id, const std::vector<StageInterface::Slot>& params, size_t& next) {
    const Type& t = type(type_id);
    if (t.op != spv::OpTypeMatrix && t.op != spv::OpTypeArray) return params.at(next++).name;
    std::vector<std::string> parts;
    for (uint32_t i = 0; i < t.count; ++i) parts.push_back(rebuild_from_slots(t.element, params, next));
    std::string text = type_name(type_id) + "(";
    for (size_t i = 0; i < parts.size(); ++i) text += (i ? ", " : "") + parts[i];
    return text + ")";
}

void ModuleEmitter::declare_interface(const EntryPoint& entry) {
    const bool vertex = entry.model == spv::ExecutionModelVertex;
    for (uint32_t id : entry.interface) {
        auto g = m.globals.find(id);
        if (g == m.globals.end()) continue;
        const Type& pointer = type(g->second.type);
        const uint32_t value_type = pointer.element;
        auto d = m.decorations.find(id);
        const Decorations deco = d != m.decorations.end() ? d->second : Decorations{};
        std::string name = m.name(id);
        const bool integer = type(scalar_of(value_type)).op == spv::OpTypeInt;

        auto interpolation = [&]() -> std::string {
            // `flat` alone means `flat, first`, which WebGPU's compatibility mode (GL ES backends)
            // rejects. `either` runs everywhere; it differs from Vulkan's first provoking vertex only
            // where a flat output varies between the triangle's vertices.
            if (deco.flat || integer) return " @interpolate(flat, either)";
            // Where both stages are emitted, `noperspective` is emulated (emulate_linear_outputs).
            const bool linear = deco.no_perspective && !shared_resources.emulate_linear;
            std::string kind = linear ? "linear" : "perspective";
            if (deco.centroid) return " @interpolate(" + kind + ", centroid)";
            if (deco.sample) return " @interpolate(" + kind + ", sample)";
            return linear ? " @interpolate(linear)" : "";
        };

        if (pointer.storage == spv::StorageClassInput) {
            StageInterface::Input in;
            in.variable = id;
            if (deco.builtin) {
                std::string attribute, wgsl_type;
                switch (*deco.builtin) {
                    case spv::BuiltInFragCoord:
                        attribute = "@builtin(position)"; wgsl_type = "vec4<f32>"; name = name.empty() ? "gl_FragCoord" : name; break;
                    case spv::BuiltInFrontFacing:
                        attribute = "@builtin(front_facing)"; wgsl_type = "bool"; name = name.empty() ? "gl_FrontFacing" : name; break;
                    case spv::BuiltInVertexIndex:
                        attribute = "@builtin(vertex_index)"; wgsl_type = "u32"; name = "vertex_index"; break;
                    case spv::BuiltInInstanceIndex:
                        attribute = "@builtin(instance_index)"; wgsl_type = "u32"; name = "instance_index"; break;
                    case spv::BuiltInSampleId:
                        attribute = "@builtin(sample_index)"; wgsl_type = "u32"; name = "sample_index"; break;
                    default: fail(fmt::format("input builtin {} has no WGSL equivalent", static_cast<int>(*deco.builtin)));
                }
                in.params.push_back({attribute, unique_identifier(name, stage_names), wgsl_type, ""});
                in.read = in.params.back().name;
                // SPIR-V reads the index builtins as int; WGSL gives u32.
                if (wgsl_type == "u32" && type(value_type).op == spv::OpTypeInt && type(value_type).is_signed)
                    in.read = "i32(" + in.read + ")";
            } else if (deco.location) {
                // One parameter per location; the body reads the value rebuilt from them.
                const std::string base = name.empty() ? "input" : name;
                const std::vector<IoSlot> slots = io_slots(value_type);
                for (size_t k = 0; k < slots.size(); ++k)
                    in.params.push_back({fmt::format("@location({}){}", *deco.location + k, vertex ? "" : interpolation()),
                                         unique_identifier(slots.size() == 1 ? base : fmt::format("{}_{}", base, k), stage_names),
                                         type_name(slots[k].type), ""});
                const bool packed = !vertex && !shared_resources.packed_locations.empty();
                std::vector<StageInterface::Slot> reads = in.params;
                for (size_t k = 0; k < slots.size(); ++k) {
                    const uint32_t location = *deco.location + static_cast<uint32_t>(k);
                    if (packed) {  // the vertex stage packed its outputs: each location is read out of its packed one
                        auto at = shared_resources.packed_locations.find(location);
                        if (at == shared_resources.packed_locations.end())
                            fail(fmt::format("fragment input location {} is not a vertex output", location));
                        reads[k].name = packed_read(at->second);
                    }
                    if (!vertex && shared_resources.linear_locations.count(location))
                        reads[k].name = "(" + reads[k].name + " / " + clip_w_read() + ")";
                }
                size_t next = 0;
                in.read = rebuild_from_slots(value_type, reads, next);
                if (packed) in.params.clear();
            } else {
                fail(fmt::format("input '{}' has neither a location nor a builtin", name));
            }
            interface.inputs.push_back(in);
            continue;
        }
        if (pointer.storage != spv::StorageClassOutput) continue;
        StageInterface::Output out;
        out.variable = id;
        const Type& vt = type(value_type);
        if (vt.op == spv::OpTypeStruct && !vt.members.empty()) {
            // gl_PerVertex: only gl_Position maps to WGSL; the other members must stay unwritten.
            for (size_t i = 0; i < vt.members.size(); ++i) {
                auto md = m.member_decorations.find({value_type, static_cast<uint32_t>(i)});
                if (md == m.member_decorations.end() || !md->second.builtin) fail("an output block member without a builtin");
                if (*md->second.builtin == spv::BuiltInPosition) {
                    const std::string local = unique_identifier("gl_Position", stage_names);
                    out.block_members[static_cast<uint32_t>(i)] = local;
                    out.fields.push_back({"@builtin(position)", local, "vec4<f32>", local});
                }
            }
            out.wgsl_type = "vec4<f32>";
            interface.outputs.push_back(out);
            continue;
        }
        out.wgsl_type = type_name(value_type);
        if (deco.builtin && *deco.builtin == spv::BuiltInPosition) {
            out.local = unique_identifier(name.empty() ? "gl_Position" : name, stage_names);
            out.fields.push_back({"@builtin(position)", out.local, out.wgsl_type, out.local});
        } else if (deco.builtin && *deco.builtin == spv::BuiltInFragDepth) {
            out.local = unique_identifier(name.empty() ? "gl_FragDepth" : name, stage_names);
            out.fields.push_back({"@builtin(frag_depth)", out.local, out.wgsl_type, out.local});
        } else if (deco.location) {
            out.local = unique_identifier(name.empty() ? "output" : name, stage_names);
            // One returned field per location: column / element k of the local.
            const std::vector<IoSlot> slots = io_slots(value_type);
            for (size_t k = 0; k < slots.size(); ++k) {
                out.located[out.fields.size()] = {*deco.location + static_cast<uint32_t>(k), slots[k].type, vertex ? interpolation() : ""};
                out.fields.push_back({fmt::format("@location({}){}", *deco.location + k, vertex ? interpolation() : ""),
                                      slots.size() == 1 ? out.local : fmt::format("{}_{}", out.local, k), type_name(slots[k].type),
                                      out.local + slots[k].path});
            }
        } else {
            fail(fmt::format("output '{}' has neither a location nor a supported builtin", name));
        }
        interface.outputs.push_back(out);
    }
    if (vertex) {
        emulate_linear_outputs();
        pack_vertex_outputs();
    }
    if (!vertex && (!packed_params_.empty() || clip_w_param_)) {  // parameters of this stage's own making
        StageInterface::Input in;
        for (const auto& [location, param] : packed_params_) in.params.push_back(param);
        if (clip_w_param_) in.params.push_back(*clip_w_param_);
        interface.inputs.push_back(in);
    }
}

void ModuleEmitter::emulate_linear_outputs() {
    if (shared_resources.linear_locations.empty()) return;
    std::string position;
    for (const auto& out : interface.outputs)
        for (const auto& field : out.fields)
            if (field.attribute == "@builtin(position)") position = field.value;
    if (position.empty()) fail("the fragment stage reads noperspective inputs but the vertex stage writes no position");
    uint32_t f32 = 0;
    for (const auto& [id, t] : m.types)
        if (t.op == spv::OpTypeFloat && t.width == 32) f32 = id;
    for (auto& out : interface.outputs)
        for (auto& [f, at] : out.located)
            if (shared_resources.linear_locations.count(at.location)) {
                StageInterface::Slot& field = out.fields[f];
                if (type(scalar_of(at.type)).op != spv::OpTypeFloat)
                    fail(fmt::format("location {} is noperspective but not floating point", at.location));
                field.value = "(" + field.value + ") * " + position + ".w";
            }
    StageInterface::Output w;
    const uint32_t location = shared_resources.clip_w_location;
    w.located[0] = {location, f32, ""};
    w.fields.push_back({fmt::format("@location({})", location), unique_identifier("clip_w", stage_names), "f32", position + ".w"});
    interface.outputs.push_back(std::move(w));
}

std::string ModuleEmitter::clip_w_read() {
    const uint32_t location = shared_resources.clip_w_location;
    if (!shared_resources.packed_locations.empty()) {
        auto at = shared_resources.packed_locations.find(location);
        if (at == shared_resources.packed_locations.end()) fail("the vertex stage sends no w for noperspective inputs");
        return packed_read(at->second);
    }
    if (!clip_w_param_)
        clip_w_param_ = StageInterface::Slot{fmt::format("@location({})", location), unique_identifier("clip_w", stage_names), "f32", ""};
    return clip_w_param_->name;
}

std::string ModuleEmitter::packed_read(const PackedLocation& packed) {
    auto param = packed_params_.find(packed.location);
    if (param == packed_params_.end()) {
        const PackedContainer* container = nullptr;
        for (const PackedContainer& c : shared_resources.packed_containers)
            if (c.location == packed.location) container = &c;
        if (!container) fail(fmt::format("packed location {} is not declared", packed.location));
        param = packed_params_.emplace(packed.location, StageInterface::Slot{
                    fmt::format("@location({}){}", container->location, container->interpolation),
                    unique_identifier(fmt::format("packed_{}", packed.location), stage_names), container->wgsl_type, ""}).first;
    }
    const bool whole = param->second.wgsl_type.rfind("vec", 0) != 0;  // a scalar container: the value itself
    static const char* const kComponents = "xyzw";
    return whole ? param->second.name : param->second.name + "." + std::string(kComponents + packed.first, packed.count);
}

// WebGPU allows fewer inter-stage locations than Vulkan (Dawn: 15, Vulkan: at least 32); a RetroArch
// pass may hand 17 to its fragment stage (scanline-classic's colour pass), or use locations past 14
// (koko-aio's glow pass: 16 and 17). Past the limit, the
// vertex stage's location outputs are packed first fit, in location order, into locations of four
// components that hold one scalar type and one interpolation; the fragment stage reads each value
// back out of its packed location (shared_resources.packed_locations). Where every location is under
// the limit nothing changes.
void ModuleEmitter::pack_vertex_outputs() {
    struct Part {
        StageInterface::Output* output;
        size_t field;
        uint32_t location, components;
        std::string scalar, interpolation;
    };
    std::vector<Part> located;
    for (auto& out : interface.outputs)
        for (const auto& [f, at] : out.located)
            located.push_back({&out, f, at.location, component_count(at.type), type_name(scalar_of(at.type)), at.interpolation});
    const bool fits = std::all_of(located.begin(), located.end(), [](const Part& p) { return p.location < kMaxInterStageLocations; });
    if (fits) return;  // every location already one WebGPU has
    std::sort(located.begin(), located.end(), [](const Part& a, const Part& b) { return a.location < b.location; });
    struct Container {
        std::string scalar, interpolation;
        uint32_t used = 0;
        std::vector<const Part*> parts;
    };
    std::vector<Container> containers;
    for (const Part& l : located) {
        auto fits = std::find_if(containers.begin(), containers.end(), [&](const Container& c) {
            return c.scalar == l.scalar && c.interpolation == l.interpolation && c.used + l.components <= 4;
        });
        if (fits == containers.end()) fits = containers.insert(containers.end(), Container{l.scalar, l.interpolation, 0, {}});
        shared_resources.packed_locations[l.location] = {static_cast<uint32_t>(fits - containers.begin()), fits->used, l.components};
        fits->used += l.components;
        fits->parts.push_back(&l);
    }
    if (containers.size() > kMaxInterStageLocations)
        fail(fmt::format("the vertex stage hands {} values to the fragment stage; packed they still take {} locations, "
                         "WebGPU allows {}", located.size(), containers.size(), kMaxInterStageLocations));
    StageInterface::Output packed;
    for (uint32_t c = 0; c < containers.size(); ++c) {
        const Container& container = containers[c];
        const std::string type = container.used == 1 ? container.scalar : fmt::format("vec{}<{}>", container.used, container.scalar);
        shared_resources.packed_containers.push_back({c, type, container.interpolation});
        std::string value;
        for (const Part* part : container.parts) value += (value.empty() ? "" : ", ") + part->output->fields[part->field].value;
        if (container.parts.size() > 1) value = type + "(" + value + ")";
        const std::string field = unique_identifier(fmt::format("packed_{}", c), stage_names);
        packed.fields.push_back({fmt::format("@location({}){}", c, container.interpolation), field, type, value});
    }
    // The packed fields replace the location fields (builtins such as the position stay).
    std::set<std::pair<const StageInterface::Output*, size_t>> moved;
    for (const Part& l : located) moved.insert({l.output, l.field});
    for (auto& out : interface.outputs) {
        std::vector<StageInterface::Slot> kept;
        for (size_t f = 0; f < out.fields.size(); ++f)
            if (!moved.count({&out, f})) kept.push_back(out.fields[f]);
        out.fields = std::move(kept);
        out.located.clear();  // every located field moved into a packed one
    }
    interface.outputs.push_back(std::move(packed));
}

void ModuleEmitter::emit_entry(const EntryPoint& entry) {
    const bool vertex = entry.model == spv::ExecutionModelVertex;
    const Function* main = m.function(entry.function);
    if (!main) fail("the entry point's function is missing");

    // Every returned value, in order: (attribute, expression).
    std::vector<std::pair<std::string, std::string>> returned;
    std::vector<const StageInterface::Slot*> fields;
    for (const auto& out : interface.outputs) {
        for (const auto& field : out.fields) {
            std::string value = field.value;
            if (vertex && options.flip_vertex_y && field.attribute == "@builtin(position)")
                value = field.value + " * vec4<f32>(1.0, -1.0, 1.0, 1.0)";  // SPIR-V clip space is y-down, WebGPU's y-up
            returned.push_back({field.attribute, value});
            fields.push_back(&field);
        }
    }
    std::string result_type, return_expr;
    if (returned.size() == 1) {
        result_type = " -> " + returned[0].first + " " + fields[0]->wgsl_type;
        return_expr = returned[0].second;
    } else if (!returned.empty()) {
        const std::string sname = module_scope_name(vertex ? "VertexOutput" : "FragmentOutput");
        std::string decl = "struct " + sname + " {\n";
        for (const auto* field : fields) decl += "  " + field->attribute + " " + field->name + ": " + field->wgsl_type + ",\n";
        decl += "}\n";
        struct_decls[sname] = decl;
        struct_order.push_back(sname);
        result_type = " -> " + sname;
        return_expr = sname + "(";
        for (size_t i = 0; i < returned.size(); ++i) return_expr += (i ? ", " : "") + returned[i].second;
        return_expr += ")";
    }

    NameScope locals = stage_names;
    std::string text = vertex ? "@vertex\n" : "@fragment\n";
    text += "fn " + entry_name + "(";
    bool first = true;
    for (const auto& in : interface.inputs)
        for (const auto& param : in.params) {
            text += (first ? "" : ", ") + param.attribute + " " + param.name + ": " + param.wgsl_type;
            first = false;
        }
    text += ")" + result_type + " {\n";
    for (const auto& out : interface.outputs) {
        if (!out.local.empty()) text += "  var " + out.local + ": " + out.wgsl_type + ";\n";
        for (const auto& [index, local] : out.block_members) text += "  var " + local + ": vec4<f32>;\n";
    }
    text += emit_function_body(*this, *main, true, return_expr, locals);
    text += "}\n";
    this->entry = text;
}

void ModuleEmitter::emit() {
    if (m.entry_points.size() != 1) fail("a module must have exactly one entry point");
    const EntryPoint& e = m.entry_points.front();
    if (e.model != spv::ExecutionModelVertex && e.model != spv::ExecutionModelFragment)
        fail("only vertex and fragment shaders can be translated to WGSL");
    for (const auto& [id, name] : m.ext_imports)
        if (name != "GLSL.std.450") fail("extended instruction set '" + name + "' is not supported");
    stage_names = global_names;
    for (const Function& f : m.functions)
        if (f.id != e.function) {
            // glslang names functions with their mangled signature: "curvature(vf2;" -> "curvature".
            const std::string name = m.name(f.id).substr(0, m.name(f.id).find('('));
            function_names[f.id] = module_scope_name(name.empty() ? "function" : name);
        }
    declare_resources();
    declare_interface(e);
    // Helper functions other than the entry, in module order.
    for (const Function& f : m.functions) {
        if (f.id == e.function) continue;
        NameScope locals = stage_names;
        functions.push_back(emit_function_body(*this, f, false, "", locals));
    }
    emit_entry(e);
}

namespace {

uint32_t location_count(const SpirvModule& m, uint32_t type_id) {
    const Type& t = m.type(type_id);
    if (t.op == spv::OpTypeMatrix) return t.count;
    if (t.op == spv::OpTypeArray) return t.count * location_count(m, t.element);
    return 1;
}

// Which fragment input locations are noperspective, and a location neither stage uses for w.
void plan_linear_emulation(const SpirvModule& vertex, const SpirvModule& fragment, SharedResources& shared) {
    std::set<uint32_t> used;
    auto scan = [&](const SpirvModule& m, spv::StorageClass storage, bool mark_linear) {
        for (const auto& [id, var] : m.globals) {
            auto d = m.decorations.find(id);
            if (d == m.decorations.end() || !d->second.location) continue;
            const Type& pointer = m.type(var.type);
            if (pointer.storage != storage) continue;
            const uint32_t count = location_count(m, pointer.element);
            for (uint32_t k = 0; k < count; ++k) {
                used.insert(*d->second.location + k);
                if (mark_linear && d->second.no_perspective && !d->second.flat)
                    shared.linear_locations.insert(*d->second.location + k);
            }
        }
    };
    scan(vertex, spv::StorageClassOutput, false);
    scan(fragment, spv::StorageClassInput, true);
    shared.emulate_linear = true;
    while (used.count(shared.clip_w_location)) ++shared.clip_w_location;
}

}  // namespace

Result<WgslModule> emit_wgsl(const std::vector<StageInput>& stages, const EmitOptions& options) {
    NameScope global_names;
    SharedResources shared_resources;
    std::vector<SpirvModule> modules;
    std::vector<std::unique_ptr<ModuleEmitter>> emitters;
    try {
        for (const auto& stage : stages) {
            // An inter-stage struct travels as its members, each at its own location.
            SpirvBinary split = *stage.spirv;
            auto parsed = parse_spirv(detail::split_interface_structs(split) ? split : *stage.spirv);
            if (!parsed.ok()) return parsed.error();
            modules.push_back(std::move(parsed.value()));
        }
        const SpirvModule* vertex = nullptr;
        const SpirvModule* fragment = nullptr;
        for (const SpirvModule& module : modules)
            if (!module.entry_points.empty()) {
                if (module.entry_points[0].model == spv::ExecutionModelVertex) vertex = &module;
                if (module.entry_points[0].model == spv::ExecutionModelFragment) fragment = &module;
            }
        if (vertex && fragment && vertex == &modules.front()) plan_linear_emulation(*vertex, *fragment, shared_resources);
        for (const SpirvModule& module : modules)
            for (const auto& [id, var] : module.globals) {
                auto d = module.decorations.find(id);
                if (d == module.decorations.end() || !d->second.binding) continue;
                uint32_t& next = shared_resources.next_sampler_binding[d->second.set.value_or(0)];
                next = std::max(next, *d->second.binding + 1);
            }
        for (size_t i = 0; i < modules.size(); ++i) {
            const auto model = modules[i].entry_points.empty() ? spv::ExecutionModelMax : modules[i].entry_points[0].model;
            auto emitter = std::make_unique<ModuleEmitter>(modules[i], options, global_names, shared_resources,
                                                           model == spv::ExecutionModelVertex ? "vertex" : "fragment",
                                                           stages[i].entry_name);
            emitter->emit();
            emitters.push_back(std::move(emitter));
        }
    } catch (const EmitError& e) {
        return make_validation_error("WGSL emitter: " + e.message, e.line.file, e.line.line);
    } catch (const spirv_cross::CompilerError& e) {
        return make_validation_error(std::string("WGSL emitter: ") + e.what());
    } catch (const std::exception& e) {
        // An id or index the module refers to but never defines: malformed SPIR-V, not a crash.
        return make_validation_error(std::string("WGSL emitter: malformed SPIR-V (") + e.what() + ")");
    }

    // Merge: identical declarations are shared; two different ones at one binding are an error.
    WgslModule out;
    auto one_line = [](std::string text) {
        std::replace(text.begin(), text.end(), '\n', ' ');
        return text;
    };
    std::string text;
    if (!options.header_comment.empty()) {
        std::istringstream lines(options.header_comment);
        for (std::string line; std::getline(lines, line);) text += "// " + line + "\n";
        text += "\n";
    }
    bool diagnostic_off = false;
    for (const auto& e : emitters) diagnostic_off = diagnostic_off || e->needs_derivative_uniformity_off;
    if (diagnostic_off)
        text += "// GLSL samples with implicit derivatives inside non-uniform control flow (after the bezel's early\n"
                "// exit); WGSL would reject that, so the check is off, as GLSL never had it.\n"
                "diagnostic(off, derivative_uniformity);\n\n";
    std::vector<std::string> printed_structs;
    for (const auto& e : emitters)
        for (const auto& name : e->struct_order)
            if (std::find(printed_structs.begin(), printed_structs.end(), name) == printed_structs.end()) {
                text += e->struct_decls.at(name) + "\n";
                printed_structs.push_back(name);
            }
    std::map<std::pair<uint32_t, uint32_t>, std::string> resources;
    for (const auto& e : emitters)
        for (const auto& [key, decl] : e->resource_decls) {
            auto [it, inserted] = resources.insert({key, decl});
            if (!inserted && it->second != decl)
                return make_validation_error(fmt::format("WGSL emitter: the stages declare different resources at "
                                                         "@group({}) @binding({}): '{}' and '{}'", key.first, key.second,
                                                         one_line(it->second), one_line(decl)));
        }
    for (const auto& [key, decl] : resources) text += decl;
    if (!resources.empty()) text += "\n";
    std::map<std::string, std::string> helpers;
    for (const auto& e : emitters) helpers.insert(e->helpers.begin(), e->helpers.end());
    for (const auto& [name, def] : helpers) text += def + "\n";
    for (const auto& e : emitters)
        for (const auto& f : e->functions) text += f + "\n";
    for (size_t i = 0; i < emitters.size(); ++i) text += (i ? "\n" : "") + emitters[i]->entry;
    out.text = text;

    for (const auto& e : emitters)
        for (const auto& b : e->bindings) {
            auto it = std::find_if(out.bindings.begin(), out.bindings.end(),
                                   [&](const WgslBinding& x) { return x.group == b.group && x.binding == b.binding; });
            if (it == out.bindings.end()) out.bindings.push_back(b);
            else it->stages.push_back(b.stages.front());
        }
    std::sort(out.bindings.begin(), out.bindings.end(),
              [](const WgslBinding& a, const WgslBinding& b) { return std::tie(a.group, a.binding) < std::tie(b.group, b.binding); });
    return out;
}

}  // namespace crtforge::wgsl
