#include "crtforge/value.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace crtforge {

const char* param_type_name(ParamType type) {
    switch (type) {
        case ParamType::Float: return "float";
        case ParamType::Int: return "int";
        case ParamType::Bool: return "bool";
        case ParamType::Enum: return "enum";
        case ParamType::Color: return "color";
    }
    return "?";
}

bool parse_param_type(const std::string& text, ParamType& out) {
    for (ParamType t : {ParamType::Float, ParamType::Int, ParamType::Bool, ParamType::Enum,
                        ParamType::Color}) {
        if (text == param_type_name(t)) {
            out = t;
            return true;
        }
    }
    return false;
}

namespace {
template <typename F>
std::string shortest_float_literal(F v) {
    std::string s = fmt::format("{}", v);  // shortest round-trip text for F
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}
}  // namespace

std::string float_literal(double v) { return shortest_float_literal(v); }
std::string float_literal(float v) { return shortest_float_literal(v); }

bool parse_hex_color(const std::string& text, Color& out) {
    if (text.size() != 7 || text[0] != '#') return false;
    Color c{};
    for (int i = 0; i < 3; ++i) {
        unsigned v = 0;
        for (int k = 0; k < 2; ++k) {
            const char ch = static_cast<char>(std::tolower(static_cast<unsigned char>(text[1 + 2 * i + k])));
            if (!std::isxdigit(static_cast<unsigned char>(ch))) return false;
            v = v * 16 + static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(ch)) ? ch - '0' : ch - 'a' + 10);
        }
        c[i] = v / 255.0;
    }
    out = c;
    return true;
}

std::string value_to_exact_string(const Value& value) {
    if (auto c = std::get_if<Color>(&value)) return fmt::format("{} {} {}", (*c)[0], (*c)[1], (*c)[2]);
    if (auto d = std::get_if<double>(&value)) return fmt::format("{}", *d);
    return value_to_string(value);
}

std::string value_to_string(const Value& value) {
    if (auto d = std::get_if<double>(&value)) return float_literal(*d);
    if (auto i = std::get_if<int64_t>(&value)) return std::to_string(*i);
    if (auto b = std::get_if<bool>(&value)) return *b ? "true" : "false";
    if (auto s = std::get_if<std::string>(&value)) return "\"" + *s + "\"";
    const Color& c = std::get<Color>(value);
    auto byte = [](double x) { return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
    return fmt::format("#{:02x}{:02x}{:02x}", byte(c[0]), byte(c[1]), byte(c[2]));
}

std::string value_to_glsl(const Value& value, ParamType type, int enum_index) {
    switch (type) {
        case ParamType::Float: return float_literal(std::get<double>(value));
        case ParamType::Int: return std::to_string(std::get<int64_t>(value));
        case ParamType::Bool: return std::get<bool>(value) ? "true" : "false";
        case ParamType::Enum: return std::to_string(enum_index);
        case ParamType::Color: {
            const Color& c = std::get<Color>(value);
            return fmt::format("vec3({}, {}, {})", float_literal(c[0]), float_literal(c[1]),
                               float_literal(c[2]));
        }
    }
    return "0";
}

const char* glsl_type_for(ParamType type) {
    switch (type) {
        case ParamType::Float: return "float";
        case ParamType::Int: return "int";
        case ParamType::Bool: return "bool";
        case ParamType::Enum: return "int";
        case ParamType::Color: return "vec3";
    }
    return "float";
}

}  // namespace crtforge
