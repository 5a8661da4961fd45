// The WGSL printer's extended and image instructions: GLSL.std.450 mapped onto WGSL builtins (with
// GLSL's semantics kept where WGSL's differ: targets/wgsl/README.md), and sampling, fetches and
// size queries. The rest of the printer is wgsl_printer.cpp.
#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <spirv_cross/GLSL.std.450.h>

#include "targets/wgsl/wgsl_function_printer.hpp"

namespace crtforge::wgsl {

namespace {

// GLSL.std.450 instructions that are one WGSL builtin of the same arguments.
const std::map<GLSLstd450, const char*>& same_builtin() {
    static const std::map<GLSLstd450, const char*> table = {
        {GLSLstd450Round, "round"},  // WGSL rounds half to even: a valid GLSL round()
        {GLSLstd450RoundEven, "round"}, {GLSLstd450Trunc, "trunc"}, {GLSLstd450FAbs, "abs"},
        {GLSLstd450FSign, "sign"}, {GLSLstd450Floor, "floor"}, {GLSLstd450Ceil, "ceil"}, {GLSLstd450Fract, "fract"},
        {GLSLstd450Radians, "radians"}, {GLSLstd450Degrees, "degrees"}, {GLSLstd450Sin, "sin"}, {GLSLstd450Cos, "cos"},
        {GLSLstd450Tan, "tan"}, {GLSLstd450Asin, "asin"}, {GLSLstd450Acos, "acos"}, {GLSLstd450Atan, "atan"},
        {GLSLstd450Sinh, "sinh"}, {GLSLstd450Cosh, "cosh"}, {GLSLstd450Tanh, "tanh"}, {GLSLstd450Asinh, "asinh"},
        {GLSLstd450Acosh, "acosh"}, {GLSLstd450Atanh, "atanh"}, {GLSLstd450Atan2, "atan2"}, {GLSLstd450Pow, "pow"},
        {GLSLstd450Exp, "exp"}, {GLSLstd450Log, "log"}, {GLSLstd450Exp2, "exp2"}, {GLSLstd450Log2, "log2"},
        {GLSLstd450Sqrt, "sqrt"}, {GLSLstd450InverseSqrt, "inverseSqrt"}, {GLSLstd450Determinant, "determinant"},
        {GLSLstd450FMin, "min"}, {GLSLstd450FMax, "max"}, {GLSLstd450FMix, "mix"}, {GLSLstd450Step, "step"},
        {GLSLstd450Fma, "fma"}, {GLSLstd450PackSnorm4x8, "pack4x8snorm"}, {GLSLstd450PackUnorm4x8, "pack4x8unorm"},
        {GLSLstd450PackSnorm2x16, "pack2x16snorm"}, {GLSLstd450PackUnorm2x16, "pack2x16unorm"},
        {GLSLstd450PackHalf2x16, "pack2x16float"}, {GLSLstd450UnpackSnorm2x16, "unpack2x16snorm"},
        {GLSLstd450UnpackUnorm2x16, "unpack2x16unorm"}, {GLSLstd450UnpackHalf2x16, "unpack2x16float"},
        {GLSLstd450UnpackSnorm4x8, "unpack4x8snorm"}, {GLSLstd450UnpackUnorm4x8, "unpack4x8unorm"},
        {GLSLstd450Length, "length"}, {GLSLstd450Distance, "distance"}, {GLSLstd450Cross, "cross"},
        {GLSLstd450Normalize, "normalize"}, {GLSLstd450FaceForward, "faceForward"}, {GLSLstd450Reflect, "reflect"},
        {GLSLstd450Refract, "refract"},
    };
    return table;
}

// Integer GLSL.std.450 instructions: one WGSL builtin, operands in the result's signedness.
const std::map<GLSLstd450, const char*>& same_integer_builtin() {
    static const std::map<GLSLstd450, const char*> table = {
        {GLSLstd450SAbs, "abs"}, {GLSLstd450SSign, "sign"}, {GLSLstd450UMin, "min"}, {GLSLstd450SMin, "min"},
        {GLSLstd450UMax, "max"}, {GLSLstd450SMax, "max"}, {GLSLstd450UClamp, "clamp"}, {GLSLstd450SClamp, "clamp"},
    };
    return table;
}

}  // namespace

std::string FunctionPrinter::matrix_inverse_helper(uint32_t n) {
    if (n == 2)
        return mod_.helper("inverse_2x2",
            "(m: mat2x2<f32>) -> mat2x2<f32> {\n"
            "  let det = m[0][0] * m[1][1] - m[1][0] * m[0][1];\n"
            "  return mat2x2<f32>(vec2<f32>(m[1][1], -m[0][1]), vec2<f32>(-m[1][0], m[0][0])) * (1.0 / det);\n"
            "}\n");
    if (n == 3)
        return mod_.helper("inverse_3x3",
            "(m: mat3x3<f32>) -> mat3x3<f32> {\n"
            "  // the rows of the inverse are the cross products of the other two columns, over the determinant\n"
            "  let bc = cross(m[1], m[2]);\n"
            "  let ca = cross(m[2], m[0]);\n"
            "  let ab = cross(m[0], m[1]);\n"
            "  return transpose(mat3x3<f32>(bc, ca, ab)) * (1.0 / dot(m[0], bc));\n"
            "}\n");
    return mod_.helper("inverse_4x4",
        "(m: mat4x4<f32>) -> mat4x4<f32> {\n"
        "  // columns a, b, c, d as 3-vectors with their w components x, y, z, w: the rows of the\n"
        "  // inverse come from the cross products of column pairs, over the determinant\n"
        "  let a = m[0].xyz; let b = m[1].xyz; let c = m[2].xyz; let d = m[3].xyz;\n"
        "  let x = m[0].w; let y = m[1].w; let z = m[2].w; let w = m[3].w;\n"
        "  var s = cross(a, b); var t = cross(c, d);\n"
        "  var u = a * y - b * x; var v = c * w - d * z;\n"
        "  let k = 1.0 / (dot(s, v) + dot(t, u));\n"
        "  s = s * k; t = t * k; u = u * k; v = v * k;\n"
        "  return transpose(mat4x4<f32>(vec4<f32>(cross(b, v) + t * y, -dot(b, t)), vec4<f32>(cross(v, a) - t * x, dot(a, t)),\n"
        "                               vec4<f32>(cross(d, u) + s * w, -dot(d, s)), vec4<f32>(cross(u, c) - s * z, dot(c, s))));\n"
        "}\n");
}

void FunctionPrinter::ext_instruction(const Instruction& inst) {
    const auto& o = inst.operands;
    if (o.size() < 2) unsupported(inst, "an operand is missing");
    auto set = m_.ext_imports.find(o[0]);
    if (set == m_.ext_imports.end() || set->second != "GLSL.std.450")
        unsupported(inst, "an extended instruction set other than GLSL.std.450");
    const auto e = operand_enum(o[1], GLSLstd450Count);
    // modf / frexp: WGSL returns both parts in a struct where GLSL writes one through a pointer
    // (Modf, Frexp) or returns its own struct (ModfStruct, FrexpStruct).
    if (e == GLSLstd450Modf || e == GLSLstd450Frexp || e == GLSLstd450ModfStruct || e == GLSLstd450FrexpStruct) {
        if (o.size() < 3) unsupported(inst, "an operand is missing");
        const bool modf = e == GLSLstd450Modf || e == GLSLstd450ModfStruct;
        const char* second = modf ? "whole" : "exp";
        const std::string parts = temp_name(inst.result) + "_parts";
        line("let " + parts + " = " + (modf ? "modf(" : "frexp(") + value(o[2]).text + ");");
        if (e == GLSLstd450Modf || e == GLSLstd450Frexp) {
            if (o.size() < 4) unsupported(inst, "an operand is missing");
            line(ref(o[3]) + " = " + parts + "." + second + ";");
            define(inst, Expr::primary(parts + ".fract"), true, true);
        } else {
            define(inst, Expr::primary(mod_.type_name(inst.type) + "(" + parts + ".fract, " + parts + "." + second + ")"), true);
        }
        return;
    }
    std::vector<Expr> args;
    for (size_t i = 2; i < o.size(); ++i) args.push_back(value(o[i]));
    auto arg = [&](size_t i) -> const Expr& {
        if (i >= args.size()) unsupported(inst, "an operand is missing");
        return args[i];
    };
    auto texts = [&]() {
        std::vector<std::string> out;
        for (const Expr& a : args) out.push_back(a.text);
        return join_list(out);
    };
    if (auto it = same_builtin().find(e); it != same_builtin().end()) {
        define(inst, Expr::primary(std::string(it->second) + "(" + texts() + ")"), true);
        return;
    }
    if (auto it = same_integer_builtin().find(e); it != same_integer_builtin().end()) {
        std::vector<std::string> typed_args;
        for (size_t i = 2; i < o.size(); ++i) typed_args.push_back(typed(o[i], inst.type));
        define(inst, Expr::primary(std::string(it->second) + "(" + join_list(typed_args) + ")"), true);
        return;
    }
    auto constant_floats = [&](size_t i) -> std::optional<std::vector<float>> {
        auto c = m_.constants.find(o[i]);
        if (c == m_.constants.end()) return std::nullopt;
        std::vector<uint32_t> bits;
        if (c->second.op == spv::OpConstant) {
            bits = c->second.words;
        } else if (c->second.op == spv::OpConstantComposite) {
            for (uint32_t part : c->second.words) {
                auto p = m_.constants.find(part);
                if (p == m_.constants.end() || p->second.words.empty()) return std::nullopt;
                bits.push_back(p->second.words[0]);
            }
        } else if (c->second.op == spv::OpConstantNull) {
            bits.assign(mod_.component_count(c->second.type), 0u);
        } else {
            return std::nullopt;
        }
        if (bits.empty()) return std::nullopt;
        std::vector<float> out;
        for (uint32_t b : bits) out.push_back(std::bit_cast<float>(b));
        return out;
    };
    // True when two constant operands are in the order WGSL's const-evaluation rejects.
    auto reversed = [&](size_t lo, size_t hi, bool allow_equal) {
        if (hi >= o.size()) return false;
        auto a = constant_floats(lo), b = constant_floats(hi);
        if (!a || !b) return false;
        for (size_t i = 0; i < std::max(a->size(), b->size()); ++i) {
            const float x = (*a)[std::min(i, a->size() - 1)], y = (*b)[std::min(i, b->size() - 1)];
            if (allow_equal ? x > y : x >= y) return true;
        }
        return false;
    };
    switch (e) {
        case GLSLstd450FClamp:
            // WGSL rejects clamp() whose constant low > high; GLSL defines clamp as min(max(x, lo), hi).
            if (reversed(3, 4, true))
                define(inst, Expr::primary("min(max(" + arg(0).text + ", " + arg(1).text + "), " + arg(2).text + ")"), true);
            else
                define(inst, Expr::primary("clamp(" + texts() + ")"), true);
            return;
        case GLSLstd450SmoothStep:
            // smoothstep(e0, e1, x) with constant e0 >= e1 is a WGSL error but a valid GLSL expression
            // (Quiet Frame's vignette writes one): spell out the Hermite curve GLSL defines.
            if (reversed(2, 3, false)) {
                if (analysis_.use_count(inst.result) == 0) return;  // dead, and pure
                const std::string t = "clamp((" + arg(2).text + " - " + arg(0).operand() + ") / (" + arg(1).operand() + " - " +
                                      arg(0).operand() + "), " + mod_.type_name(inst.type) + "(0.0), " +
                                      mod_.type_name(inst.type) + "(1.0))";
                const std::string name = temp_name(inst.result) + "_t";
                line("let " + name + " = " + t + ";");
                define(inst, Expr::binary(name + " * " + name + " * (3.0 - 2.0 * " + name + ")"), true);
            } else {
                define(inst, Expr::primary("smoothstep(" + texts() + ")"), true);
            }
            return;
        case GLSLstd450Ldexp: {
            const uint32_t n = mod_.component_count(inst.type);
            const std::string exp_type = n == 1 ? "i32" : fmt::format("vec{}<i32>", n);
            define(inst, Expr::primary("ldexp(" + arg(0).text + ", bitcast<" + exp_type + ">(" + arg(1).text + "))"), true);
            return;
        }
        case GLSLstd450FindILsb: case GLSLstd450FindSMsb: case GLSLstd450FindUMsb: {
            const char* name = e == GLSLstd450FindILsb ? "firstTrailingBit" : "firstLeadingBit";
            const bool want_signed = e == GLSLstd450FindSMsb;
            const uint32_t n = mod_.component_count(inst.type);
            const std::string operand_type = n == 1 ? (want_signed ? "i32" : "u32") : fmt::format("vec{}<{}>", n, want_signed ? "i32" : "u32");
            std::string text = std::string(name) + "(bitcast<" + operand_type + ">(" + arg(0).text + "))";
            if (m_.type(mod_.scalar_of(inst.type)).is_signed != want_signed)
                text = "bitcast<" + mod_.type_name(inst.type) + ">(" + text + ")";
            define(inst, Expr::primary(text), true);
            return;
        }
        case GLSLstd450MatrixInverse: {
            // WGSL has no inverse(): the adjugate over the determinant, as a helper per size (a
            // singular matrix gives non-finite values, as GLSL leaves it undefined).
            const Type& t = m_.type(inst.type);
            if (t.op != spv::OpTypeMatrix || t.count < 2 || t.count > 4 || mod_.component_count(t.element) != t.count)
                unsupported(inst, "inverse() of a matrix that is not square");
            define(inst, Expr::primary(matrix_inverse_helper(t.count) + "(" + arg(0).text + ")"), true);
            return;
        }
        default: {
            static const std::map<GLSLstd450, const char*> names = {
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
    if (o.size() < 1) unsupported(inst, "an operand is missing");
    auto image = images_.find(o[0]);
    if (image == images_.end()) unsupported(inst, "the image does not come from a module variable");
    const auto& [texture, sampler] = image->second;
    switch (inst.op) {
        case spv::OpImageQuerySizeLod: case spv::OpImageQuerySize: {
            std::string text = "textureDimensions(" + texture +
                               (inst.op == spv::OpImageQuerySizeLod && o.size() > 1 ? ", " + value(o[1]).text : "") + ")";
            if (m_.type(mod_.scalar_of(inst.type)).is_signed) text = mod_.type_name(inst.type) + "(" + text + ")";
            define(inst, Expr::primary(text), true);
            return;
        }
        case spv::OpImageQueryLevels: {
            std::string text = "textureNumLevels(" + texture + ")";
            if (m_.type(inst.type).is_signed) text = "i32(" + text + ")";
            define(inst, Expr::primary(text), true);
            return;
        }
        default: break;
    }
    if (o.size() < 2) unsupported(inst, "an operand is missing");
    // clamp_to_border on a clamp-to-edge sampler (EmitOptions::emulate_border): the sample is
    // faded below, by a weight that reads the coordinate again, so an expression is named once.
    auto border = mod_.border_textures.find(texture);
    const bool fade = inst.op != spv::OpImageFetch && border != mod_.border_textures.end();
    if (fade && analysis_.use_count(inst.result) == 0) return;  // dead, and pure
    const Expr coord_expr = value(o[1]);
    std::string coord = coord_expr.text;
    if (fade && !coord_expr.named) {
        const std::string name = temp_name(inst.result) + "_uv";
        line("let " + name + " = " + coord + ";");
        coord = name;
    }
    // OpImageGather has its component before the image operands.
    const size_t mask_at = inst.op == spv::OpImageGather ? 3 : 2;
    const uint32_t mask = o.size() > mask_at ? o[mask_at] : 0;
    std::map<uint32_t, std::string> operands;  // image-operand bit -> text
    size_t next = mask_at + 1;
    auto operand = [&](size_t i) {
        if (i >= o.size()) unsupported(inst, "an image operand is missing");
        return value(o[i]).text;
    };
    for (uint32_t bit : {spv::ImageOperandsBiasMask, spv::ImageOperandsLodMask, spv::ImageOperandsGradMask,
                         spv::ImageOperandsConstOffsetMask, spv::ImageOperandsOffsetMask, spv::ImageOperandsConstOffsetsMask,
                         spv::ImageOperandsSampleMask, spv::ImageOperandsMinLodMask}) {
        if (!(mask & bit)) continue;
        if (bit == spv::ImageOperandsGradMask) {
            operands[bit] = operand(next) + ", " + operand(next + 1);
            next += 2;
        } else {
            operands[bit] = operand(next);
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
        needs_uniform_flow();
        if (operands.count(spv::ImageOperandsBiasMask))
            text = "textureSampleBias(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsBiasMask] + offset + ")";
        else
            text = "textureSample(" + texture + ", " + sampler + ", " + coord + offset + ")";
    } else if (inst.op == spv::OpImageGather) {
        // textureGather(component, t, s, coords): the component operand is the constant after the coordinate.
        if (o.size() < 3) unsupported(inst, "an operand is missing");
        const std::string component = value(o[2]).text;
        text = "textureGather(" + component + ", " + texture + ", " + sampler + ", " + coord + offset + ")";
    } else if (operands.count(spv::ImageOperandsLodMask)) {
        text = "textureSampleLevel(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsLodMask] + offset + ")";
    } else if (operands.count(spv::ImageOperandsGradMask)) {
        text = "textureSampleGrad(" + texture + ", " + sampler + ", " + coord + ", " + operands[spv::ImageOperandsGradMask] + offset + ")";
    } else {
        unsupported(inst, "an explicit-LOD sample without Lod or Grad");
    }
    if (!fade) {
        define(inst, Expr::primary(text), true);
        return;
    }
    // Outside the texture an edge sampler repeats the edge texel where a border one reads
    // transparent black, so the border sample is the edge sample times the share of its footprint
    // inside (exact for nearest, and for linear at the level read). An explicit level of detail
    // reads a level of the mip chain whose texels are larger: the footprint is measured in that
    // level's texels (Vulkan's nearest level, ceil(lod + 0.5) - 1, clamped to the chain; between
    // two blended levels, the nearer one's). Implicit levels are measured at level 0.
    std::string uv = coord;
    std::string size = "vec2<f32>(textureDimensions(" + texture + "))";
    if (inst.op == spv::OpImageSampleExplicitLod && operands.count(spv::ImageOperandsLodMask)) {
        const std::string name = mod_.helper("border_level_size",
            "(t: texture_2d<f32>, lod: f32) -> vec2<f32> {\n"
            "  // the size of the mip level an explicit lod reads (the nearest one)\n"
            "  let last = f32(textureNumLevels(t) - 1u);\n"
            "  return vec2<f32>(textureDimensions(t, u32(clamp(ceil(lod + 0.5) - 1.0, 0.0, last))));\n"
            "}\n");
        size = name + "(" + texture + ", " + operands[spv::ImageOperandsLodMask] + ")";
    }
    if (operands.count(spv::ImageOperandsConstOffsetMask))
        uv = "(" + uv + " + vec2<f32>(" + operands[spv::ImageOperandsConstOffsetMask] + ") / " + size + ")";
    std::string weight;
    if (inst.op == spv::OpImageGather) {
        const std::string name = mod_.helper("border_weight_gather",
            "(uv: vec2<f32>, size: vec2<f32>) -> vec4<f32> {\n"
            "  // 1 for each of the four gathered texels that is inside the texture, in textureGather's order\n"
            "  let lo = floor(uv * size - vec2<f32>(0.5));\n"
            "  let hi = lo + vec2<f32>(1.0);\n"
            "  let in_lo = select(vec2<f32>(0.0), vec2<f32>(1.0), (lo >= vec2<f32>(0.0)) & (lo < size));\n"
            "  let in_hi = select(vec2<f32>(0.0), vec2<f32>(1.0), (hi >= vec2<f32>(0.0)) & (hi < size));\n"
            "  return vec4<f32>(in_lo.x * in_hi.y, in_hi.x * in_hi.y, in_hi.x * in_lo.y, in_lo.x * in_lo.y);\n"
            "}\n");
        weight = name + "(" + uv + ", " + size + ")";
    } else if (border->second) {
        const std::string name = mod_.helper("border_weight_linear",
            "(uv: vec2<f32>, size: vec2<f32>) -> f32 {\n"
            "  // the share of a bilinear footprint's weight on texels inside the texture, per axis\n"
            "  let inside = clamp(min(uv, vec2<f32>(1.0) - uv) * size + vec2<f32>(0.5), vec2<f32>(0.0), vec2<f32>(1.0));\n"
            "  return inside.x * inside.y;\n"
            "}\n");
        weight = name + "(" + uv + ", " + size + ")";
    } else {
        const std::string name = mod_.helper("border_weight_nearest",
            "(uv: vec2<f32>) -> f32 {\n"
            "  // 1 where the nearest texel is inside the texture\n"
            "  return select(0.0, 1.0, all(uv >= vec2<f32>(0.0)) && all(uv < vec2<f32>(1.0)));\n"
            "}\n");
        weight = name + "(" + uv + ")";
    }
    define(inst, Expr::binary(text + " * " + weight), true);
}

}  // namespace crtforge::wgsl
