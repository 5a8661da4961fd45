#include "generator/reserved_words.hpp"

#include <set>

namespace crtforge::detail {

namespace {

// GLSL 4.50 / ES 3.00 keywords, reserved words and the builtin functions the generated code calls
// or a snippet may call (a uniform of that name hides the function).
const std::set<std::string>& glsl_words() {
    static const std::set<std::string> words = {
        "attribute", "const", "uniform", "varying", "buffer", "shared", "coherent", "volatile", "restrict", "readonly",
        "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch", "sample", "break",
        "continue", "do", "for", "while", "switch", "case", "default", "if", "else", "subroutine", "in", "out", "inout",
        "float", "double", "int", "void", "bool", "true", "false", "invariant", "precise", "discard", "return", "mat2",
        "mat3", "mat4", "dmat2", "dmat3", "dmat4", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3",
        "bvec4", "dvec2", "dvec3", "dvec4", "uint", "uvec2", "uvec3", "uvec4", "lowp", "mediump", "highp", "precision",
        "sampler1D", "sampler2D", "sampler3D", "samplerCube", "sampler2DArray", "sampler2DShadow", "isampler2D",
        "usampler2D", "image2D", "struct", "common", "partition", "active", "asm", "class", "union", "enum", "typedef",
        "template", "this", "resource", "goto", "inline", "noinline", "public", "static", "extern", "external",
        "interface", "long", "short", "half", "fixed", "unsigned", "superp", "input", "output", "hvec2", "hvec3", "hvec4",
        "fvec2", "fvec3", "fvec4", "sampler3DRect", "filter", "sizeof", "cast", "namespace", "using",
        // builtin functions
        "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh",
        "pow", "exp", "log", "exp2", "log2", "sqrt", "inversesqrt", "abs", "sign", "floor", "trunc", "round", "roundEven",
        "ceil", "fract", "mod", "modf", "min", "max", "clamp", "mix", "step", "smoothstep", "isnan", "isinf", "fma",
        "length", "distance", "dot", "cross", "normalize", "faceforward", "reflect", "refract", "matrixCompMult",
        "transpose", "determinant", "inverse", "lessThan", "lessThanEqual", "greaterThan", "greaterThanEqual", "equal",
        "notEqual", "any", "all", "not", "texture", "textureSize", "texelFetch", "textureLod", "textureGrad", "dFdx",
        "dFdy", "fwidth", "floatBitsToInt", "intBitsToFloat", "packHalf2x16", "unpackHalf2x16"};
    return words;
}

const std::set<std::string>& hlsl_words() {
    static const std::set<std::string> words = {
        "cbuffer", "tbuffer", "register", "packoffset", "groupshared", "nointerpolation", "linear", "centroid",
        "row_major", "column_major", "matrix", "vector", "float2", "float3", "float4", "float2x2", "float3x3", "float4x4",
        "int2", "int3", "int4", "uint2", "uint3", "uint4", "bool2", "bool3", "bool4", "half2", "half3", "half4", "min16float",
        "min16float2", "min16float3", "min16float4", "dword", "string", "technique", "pass", "compile", "sampler",
        "SamplerState", "Texture2D", "Texture3D", "RWTexture2D", "Buffer", "StructuredBuffer", "snorm", "unorm",
        "lerp", "saturate", "frac", "rsqrt", "ddx", "ddy", "mul", "atan2", "fmod", "clip", "tex2D", "asfloat", "asint",
        "asuint", "discard", "triangle", "line", "point", "lineadj", "triangleadj", "export", "precise", "globallycoherent",
        "SV_Target", "SV_Position"};
    return words;
}

// WGSL keywords and reserved words (W3C WGSL, "Keyword and reserved word summary") and the builtin
// functions and types the emitter prints.
const std::set<std::string>& wgsl_words() {
    static const std::set<std::string> words = {
        "alias", "array", "atomic", "bitcast", "const_assert", "diagnostic", "enable", "fn", "let", "loop", "mat2x2",
        "mat3x3", "mat4x4", "override", "ptr", "requires", "sampler_comparison", "texture_2d", "var", "vec", "f32", "f16",
        "i32", "u32", "function", "private", "storage", "workgroup", "uniform", "read", "write", "read_write", "select",
        "arrayLength", "textureSample", "textureSampleLevel", "textureLoad", "textureDimensions", "extractBits",
        "insertBits", "countOneBits", "reverseBits", "firstLeadingBit", "firstTrailingBit", "quantizeToF16", "unpack2x16float",
        "pack2x16float", "dpdx", "dpdy", "inverseSqrt", "vs_main", "fs_main", "NULL", "Self", "abstract", "actor", "alignas",
        "alignof", "as", "async", "attribute", "auto", "await", "become", "binding_array", "cast", "catch", "co_await",
        "co_return", "co_yield", "coherent", "column_major", "compile", "compile_fragment", "concept", "const_cast",
        "consteval", "constexpr", "constinit", "crate", "debugger", "decltype", "delete", "demote", "demote_to_helper",
        "do", "dynamic_cast", "elif", "explicit", "export", "extends", "extern", "external", "fallthrough", "filter",
        "final", "finally", "friend", "from", "fxgroup", "get", "goto", "groupshared", "handle", "highp", "impl",
        "implements", "import", "inline", "instanceof", "interface", "layout", "lowp", "macro", "macro_rules", "match",
        "mediump", "meta", "mod", "module", "move", "mut", "mutable", "namespace", "new", "nil", "noexcept", "noinline",
        "nointerpolation", "noperspective", "null", "nullptr", "of", "operator", "package", "packoffset", "partition",
        "pass", "patch", "pixelfragment", "precise", "precision", "premerge", "priv", "protected", "pub", "public",
        "readonly", "ref", "regardless", "register", "reinterpret_cast", "require", "resource", "restrict", "self", "set",
        "shared", "sizeof", "smooth", "snorm", "static", "static_assert", "static_cast", "std", "subroutine", "super",
        "target", "template", "this", "thread_local", "throw", "trait", "try", "type", "typedef", "typeid", "typename",
        "typeof", "union", "unless", "unorm", "unsafe", "unsized", "use", "using", "varying", "virtual", "volatile", "wgsl",
        "where", "with", "writeonly", "yield"};
    return words;
}

// Godot's shading language (3.x and 4.x): keywords, hints and render modes, and the canvas_item
// builtins (upper case, but a param may be spelled so).
const std::set<std::string>& godot_words() {
    static const std::set<std::string> words = {
        "shader_type", "render_mode", "hint_range", "hint_color", "source_color", "hint_albedo", "hint_black",
        "hint_white", "hint_default_white", "hint_default_black", "hint_screen_texture", "filter_nearest",
        "filter_linear", "repeat_enable", "repeat_disable", "instance", "global", "group_uniforms", "canvas_item",
        "spatial", "particles", "sky", "fog", "vertex", "fragment", "light", "start", "process", "TIME", "PI", "TAU", "E",
        "UV", "COLOR", "VERTEX", "TEXTURE", "TEXTURE_PIXEL_SIZE", "SCREEN_UV", "SCREEN_TEXTURE", "SCREEN_PIXEL_SIZE",
        "FRAGCOORD", "NORMAL", "NORMAL_TEXTURE", "NORMALMAP", "NORMALMAP_DEPTH", "POINT_COORD", "AT_LIGHT_PASS",
        "SPECULAR_SHININESS", "SPECULAR_SHININESS_TEXTURE", "LIGHT", "LIGHT_COLOR", "LIGHT_POSITION", "SHADOW_COLOR",
        "WORLD_MATRIX", "MODEL_MATRIX", "CANVAS_MATRIX", "SCREEN_MATRIX", "PROJECTION_MATRIX", "EXTRA_MATRIX",
        "INSTANCE_CUSTOM", "INSTANCE_ID", "VERTEX_ID", "POINT_SIZE", "CUSTOM0", "CUSTOM1", "MODULATE", "ALPHA",
        "REGION_RECT", "SDF", "texture_sdf", "screen_uv_to_sdf", "sdf_to_screen_uv", "texture_sdf_normal"};
    return words;
}

}  // namespace

std::string reserving_language(const std::string& name) {
    if (glsl_words().count(name)) return "GLSL";
    if (hlsl_words().count(name)) return "HLSL";
    if (wgsl_words().count(name)) return "WGSL";
    if (godot_words().count(name)) return "Godot";
    return {};
}

}  // namespace crtforge::detail
