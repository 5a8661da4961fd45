#include "targets/wgsl/wgsl_names.hpp"

#include <bit>

#include <fmt/format.h>

#include "crtforge/value.hpp"

namespace crtforge::wgsl {

namespace {

// WGSL keywords, reserved words, and the predeclared names we never shadow (types and the
// builtin functions our output calls), so a param called `filter` or `mix` cannot break a module.
const std::set<std::string>& reserved_words() {
    static const std::set<std::string> words = {
        // keywords
        "alias", "break", "case", "const", "const_assert", "continue", "continuing", "default", "diagnostic",
        "discard", "else", "enable", "false", "fn", "for", "if", "let", "loop", "override", "requires", "return",
        "struct", "switch", "true", "var", "while",
        // reserved words
        "NULL", "Self", "abstract", "active", "alignas", "alignof", "as", "asm", "asm_fragment", "async",
        "attribute", "auto", "await", "become", "binding_array", "cast", "catch", "class", "co_await", "co_return",
        "co_yield", "coherent", "column_major", "common", "compile", "compile_fragment", "concept", "const_cast",
        "consteval", "constexpr", "constinit", "crate", "debugger", "decltype", "delete", "demote",
        "demote_to_helper", "do", "dynamic_cast", "enum", "explicit", "export", "extends", "extern", "external",
        "fallthrough", "filter", "final", "finally", "friend", "from", "fxgroup", "get", "goto", "groupshared",
        "highp", "impl", "implements", "import", "inline", "instanceof", "interface", "layout", "lowp", "macro",
        "macro_rules", "match", "mediump", "meta", "mod", "module", "move", "mut", "mutable", "namespace", "new",
        "nil", "noexcept", "noinline", "nointerpolation", "non_coherent", "noncoherent", "noperspective", "null",
        "nullptr", "of", "operator", "package", "packoffset", "partition", "pass", "patch", "pixelfragment",
        "precise", "precision", "premerge", "priv", "protected", "pub", "public", "readonly", "ref", "regardless",
        "register", "reinterpret_cast", "require", "resource", "restrict", "self", "set", "shared", "sizeof",
        "smooth", "snorm", "static", "static_assert", "static_cast", "std", "subroutine", "super", "target",
        "template", "this", "thread_local", "throw", "trait", "try", "type", "typedef", "typeid", "typename",
        "typeof", "union", "unless", "unorm", "unsafe", "unsized", "use", "using", "varying", "virtual",
        "volatile", "wgsl", "where", "with", "writeonly", "yield",
        // predeclared types and functions we emit
        "f32", "f16", "i32", "u32", "bool", "vec2", "vec3", "vec4", "mat2x2", "mat3x3", "mat4x4", "array",
        "ptr", "sampler", "texture_2d", "atomic", "bitcast", "select", "all", "any", "abs", "acos", "asin",
        "atan", "atan2", "ceil", "clamp", "cos", "cosh", "cross", "degrees", "determinant", "distance", "dot",
        "dpdx", "dpdy", "exp", "exp2", "faceForward", "floor", "fma", "fract", "fwidth", "inverseSqrt", "ldexp",
        "length", "log", "log2", "max", "min", "mix", "normalize", "pow", "radians", "reflect", "refract",
        "round", "sign", "sin", "sinh", "smoothstep", "sqrt", "step", "tan", "tanh", "transpose", "trunc",
        "textureSample", "textureSampleLevel", "textureSampleBias", "textureSampleGrad", "textureLoad",
        "textureDimensions", "textureNumLevels",
    };
    return words;
}

bool ident_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool ident_char(char c) { return ident_start(c) || (c >= '0' && c <= '9'); }

}  // namespace

std::string unique_identifier(const std::string& wanted, NameScope& scope) {
    std::string base;
    for (char c : wanted) base += ident_char(c) ? c : '_';
    while (base.size() >= 2 && base[0] == '_' && base[1] == '_') base.erase(0, 1);
    if (base.empty() || base == "_") base.assign(1, 'v');
    if (!ident_start(base[0])) base.insert(0, 1, 'v');
    if (reserved_words().count(base)) base += "_";
    std::string name = base;
    if (scope.count(name)) {
        int& n = scope.next_.try_emplace(base, 1).first->second;
        do name = fmt::format("{}_{}", base, n++);
        while (scope.count(name));
    }
    scope.insert(name);
    return name;
}

std::string f32_literal(uint32_t bits) {
    if ((bits & 0x7f800000u) == 0x7f800000u) return fmt::format("bitcast<f32>(0x{:08x}u)", bits);
    return float_literal(std::bit_cast<float>(bits));
}

std::string i32_literal(int32_t value) {
    // -2147483648 is not a literal WGSL accepts (the literal 2147483648 does not fit i32).
    if (value == INT32_MIN) return "i32(-2147483647 - 1)";
    return value < 0 ? fmt::format("({}i)", value) : fmt::format("{}i", value);
}

std::string u32_literal(uint32_t value) { return fmt::format("{}u", value); }

}  // namespace crtforge::wgsl
