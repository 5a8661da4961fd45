// Shortest round-trip float literals in SPIRV-Cross output (see float_literals.hpp).
#include "targets/float_literals.hpp"

#include <functional>
#include "targets/word_scan.hpp"

#include <cctype>
#include <cstdlib>

#include "crtforge/value.hpp"

namespace crtforge::detail {

namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Where the exponent (e-5, E+12) at `i` ends: `i` itself if none is there.
size_t exponent_end(const std::string& text, size_t i) {
    const size_t n = text.size();
    if (i >= n || (text[i] != 'e' && text[i] != 'E')) return i;
    size_t j = i + 1;
    if (j < n && (text[j] == '+' || text[j] == '-')) ++j;
    if (j >= n || !is_digit(text[j])) return i;
    while (j < n && is_digit(text[j])) ++j;
    return j;
}

// Where the comment or preprocessor line at `i` ends (kept as it is): `i` itself if none starts there.
size_t inert_end(const std::string& text, size_t i) {
    const size_t n = text.size();
    const bool line = (text[i] == '/' && i + 1 < n && text[i + 1] == '/') || (text[i] == '#' && (i == 0 || text[i - 1] == '\n'));
    const bool block = text[i] == '/' && i + 1 < n && text[i + 1] == '*';
    if (!line && !block) return i;
    const size_t end = block ? text.find("*/", i + 2) : text.find('\n', i);
    return end == std::string::npos ? n : end + (block ? 2 : 0);
}

// The shortest text for the literal `token`, or `token` itself when it must stay.
std::string shorter(const std::string& token) {
    if (token.find_first_of(".eE") == std::string::npos) return token;  // an integer
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) return token;
    const float as_float = static_cast<float>(value);
    if (static_cast<double>(as_float) != value) return token;  // not a float32 value: a double, keep it
    std::string text = float_literal(as_float);
    if (text.find_first_of("eE") != std::string::npos) return token;  // exponent syntax varies by consumer
    return text.size() < token.size() ? text : token;
}

}  // namespace

std::string rewrite_float_literals(const std::string& source,
                                   const std::function<std::string(const std::string& token, const std::string& suffix)>& rewrite) {
    std::string out;
    out.reserve(source.size());
    size_t i = 0;
    const size_t n = source.size();
    while (i < n) {
        const char c = source[i];
        // Comments and preprocessor lines are copied as they are.
        if (const size_t stop = inert_end(source, i); stop != i) {
            out.append(source, i, stop - i);
            i = stop;
            continue;
        }
        if (is_identifier_char(c) && !is_digit(c)) {  // an identifier, digits and all
            const size_t start = i;
            while (i < n && is_identifier_char(source[i])) ++i;
            out.append(source, start, i - start);
            continue;
        }
        const bool starts_number = is_digit(c) || (c == '.' && i + 1 < n && is_digit(source[i + 1]));
        if (!starts_number || (i > 0 && (source[i - 1] == '.' || is_identifier_char(source[i - 1])))) {
            out += c;
            ++i;
            continue;
        }
        const size_t start = i;
        while (i < n && (is_digit(source[i]) || source[i] == '.')) ++i;
        i = exponent_end(source, i);
        const std::string token = source.substr(start, i - start);
        size_t suffix_end = i;
        while (suffix_end < n && is_identifier_char(source[suffix_end])) ++suffix_end;
        const std::string suffix = source.substr(i, suffix_end - i);
        if (token.find_first_of(".eE") == std::string::npos) {
            out += token + suffix;  // an integer
        } else {
            out += rewrite(token, suffix);
        }
        i = suffix_end;
    }
    return out;
}

std::string shorten_float_literals(const std::string& source) {
    return rewrite_float_literals(source, [](const std::string& token, const std::string& suffix) {
        // Only a plain literal or HLSL's float suffix; `lf`, `u`, `h` and the like stay untouched.
        return (suffix.empty() || suffix == "f" || suffix == "F" ? shorter(token) : token) + suffix;
    });
}

namespace {

// The length of the float literal at `at` (digits, '.', an exponent, HLSL's `f`), 0 if none.
size_t literal_length(const std::string& text, size_t at) {
    size_t i = at;
    const size_t n = text.size();
    while (i < n && (is_digit(text[i]) || text[i] == '.')) ++i;
    if (i == at || text.find_first_of("0123456789", at) >= i) return 0;
    i = exponent_end(text, i);
    if (i < n && (text[i] == 'f' || text[i] == 'F')) ++i;
    return i < n && is_identifier_char(text[i]) ? 0 : i - at;
}

// The length of a component selection `.x` (one of xyzw) at `at` that ends the expression there.
size_t component_length(const std::string& text, size_t at) {
    const size_t n = text.size();
    if (at + 1 >= n || text[at] != '.' || std::string_view("xyzw").find(text[at + 1]) == std::string_view::npos) return 0;
    if (at + 2 < n && (is_identifier_char(text[at + 2]) || text[at + 2] == '.')) return 0;
    return 2;
}

}  // namespace

std::string without_splat_selects(const std::string& source) {
    std::string out;
    out.reserve(source.size());
    const size_t n = source.size();
    for (size_t i = 0; i < n;) {
        const char c = source[i];
        if (const size_t stop = inert_end(source, i); stop != i) {
            out.append(source, i, stop - i);
            i = stop;
            continue;
        }
        const bool boundary = i == 0 || (!is_identifier_char(source[i - 1]) && source[i - 1] != '.');
        // GLSL, Godot: vecN(L).c, where L may be negative (kept in parentheses).
        if (boundary && source.compare(i, 3, "vec") == 0 && i + 4 < n && source[i + 3] >= '2' && source[i + 3] <= '4' && source[i + 4] == '(') {
            const size_t value = i + 5;
            const bool negative = value < n && source[value] == '-';
            const size_t length = literal_length(source, value + (negative ? 1 : 0));
            const size_t close = value + (negative ? 1 : 0) + length;
            if (length && close < n && source[close] == ')')
                if (const size_t component = component_length(source, close + 1)) {
                    const std::string literal = source.substr(value, close - value);
                    out += negative ? "(" + literal + ")" : literal;
                    i = close + 1 + component;
                    continue;
                }
        }
        // HLSL: L.xxxx.c (a unary minus before it applies after the selection, as before).
        if (boundary && is_digit(c))
            if (const size_t length = literal_length(source, i)) {
                size_t at = i + length;
                size_t splat = 0;
                if (at < n && source[at] == '.')
                    while (at + 1 + splat < n && source[at + 1 + splat] == 'x') ++splat;
                if (splat >= 2 && splat <= 4)
                    if (const size_t component = component_length(source, at + 1 + splat)) {
                        out.append(source, i, length);
                        i = at + 1 + splat + component;
                        continue;
                    }
                out.append(source, i, length);
                i += length;
                continue;
            }
        out += c;
        ++i;
    }
    return out;
}

}  // namespace crtforge::detail
