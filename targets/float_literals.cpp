// Shortest round-trip float literals in SPIRV-Cross output (see float_literals.hpp).
#include "targets/float_literals.hpp"

#include <cctype>
#include <cstdlib>

#include "crtforge/value.hpp"

namespace crtforge::detail {

namespace {

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

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

std::string shorten_float_literals(const std::string& source) {
    std::string out;
    out.reserve(source.size());
    size_t i = 0;
    const size_t n = source.size();
    while (i < n) {
        const char c = source[i];
        // Comments and preprocessor lines are copied as they are.
        if (c == '/' && i + 1 < n && source[i + 1] == '/') {
            const size_t end = source.find('\n', i);
            const size_t stop = end == std::string::npos ? n : end;
            out.append(source, i, stop - i);
            i = stop;
            continue;
        }
        if (c == '/' && i + 1 < n && source[i + 1] == '*') {
            const size_t end = source.find("*/", i + 2);
            const size_t stop = end == std::string::npos ? n : end + 2;
            out.append(source, i, stop - i);
            i = stop;
            continue;
        }
        if (c == '#' && (i == 0 || source[i - 1] == '\n')) {
            const size_t end = source.find('\n', i);
            const size_t stop = end == std::string::npos ? n : end;
            out.append(source, i, stop - i);
            i = stop;
            continue;
        }
        if (is_word_char(c) && !is_digit(c)) {  // an identifier, digits and all
            const size_t start = i;
            while (i < n && is_word_char(source[i])) ++i;
            out.append(source, start, i - start);
            continue;
        }
        const bool starts_number = is_digit(c) || (c == '.' && i + 1 < n && is_digit(source[i + 1]));
        if (!starts_number || (i > 0 && (source[i - 1] == '.' || is_word_char(source[i - 1])))) {
            out += c;
            ++i;
            continue;
        }
        const size_t start = i;
        while (i < n && (is_digit(source[i]) || source[i] == '.')) ++i;
        if (i < n && (source[i] == 'e' || source[i] == 'E')) {
            size_t j = i + 1;
            if (j < n && (source[j] == '+' || source[j] == '-')) ++j;
            if (j < n && is_digit(source[j])) {
                i = j;
                while (i < n && is_digit(source[i])) ++i;
            }
        }
        const std::string token = source.substr(start, i - start);
        size_t suffix_end = i;
        while (suffix_end < n && is_word_char(source[suffix_end])) ++suffix_end;
        const std::string suffix = source.substr(i, suffix_end - i);
        // Only a plain literal or HLSL's float suffix; `lf`, `u`, `h` and the like stay untouched.
        out += suffix.empty() || suffix == "f" || suffix == "F" ? shorter(token) : token;
        out += suffix;
        i = suffix_end;
    }
    return out;
}

}  // namespace crtforge::detail
