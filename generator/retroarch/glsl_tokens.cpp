#include "generator/retroarch/glsl_tokens.hpp"

#include <cctype>

#include "crtforge/identifier_chars.hpp"

namespace crtforge::retroarch {

namespace {


// The end of the whitespace, comments and line continuations starting at `i`.
size_t space_end(const std::string& s, size_t i) {
    while (i < s.size()) {
        if (std::isspace(static_cast<unsigned char>(s[i]))) {
            ++i;
        } else if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == '\n' || s[i + 1] == '\r')) {
            ++i;
        } else if (s.compare(i, 2, "//") == 0) {
            while (i < s.size() && s[i] != '\n') ++i;
        } else if (s.compare(i, 2, "/*") == 0) {
            const size_t end = s.find("*/", i + 2);
            i = end == std::string::npos ? s.size() : end + 2;
        } else {
            break;
        }
    }
    return i;
}

// A number from `start`: digits, a point, an exponent with its sign, a suffix (1.0e-3f, 0x1Fu).
size_t number_end(const std::string& s, size_t start) {
    const bool hex = s.compare(start, 2, "0x") == 0 || s.compare(start, 2, "0X") == 0;
    size_t i = start + 1;
    while (i < s.size()) {
        const char c = s[i];
        if (crtforge::detail::is_identifier_char(c) || c == '.') ++i;
        else if ((c == '+' || c == '-') && !hex && (s[i - 1] == 'e' || s[i - 1] == 'E')) ++i;
        else break;
    }
    return i;
}

}  // namespace

std::vector<GlslToken> tokenize_glsl(const std::string& s) {
    std::vector<GlslToken> out;
    size_t i = 0;
    while (i < s.size()) {
        const size_t space = space_end(s, i);
        if (space > i) {
            out.push_back({GlslToken::Kind::Space, s.substr(i, space - i)});
            i = space;
            continue;
        }
        const char c = s[i];
        size_t end = i + 1;
        GlslToken::Kind kind = GlslToken::Kind::Punct;
        if (crtforge::detail::is_identifier_start(c)) {
            while (end < s.size() && crtforge::detail::is_identifier_char(s[end])) ++end;
            kind = GlslToken::Kind::Identifier;
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
            end = number_end(s, i);
            kind = GlslToken::Kind::Number;
        }
        out.push_back({kind, s.substr(i, end - i)});
        i = end;
    }
    return out;
}

std::string join_tokens(const std::vector<GlslToken>& tokens) {
    std::string out;
    for (const GlslToken& t : tokens) out += t.text;
    return out;
}

size_t next_significant(const std::vector<GlslToken>& tokens, size_t i) {
    for (++i; i < tokens.size(); ++i)
        if (tokens[i].kind != GlslToken::Kind::Space) return i;
    return tokens.size();
}

long previous_significant(const std::vector<GlslToken>& tokens, size_t i) {
    for (long k = static_cast<long>(i) - 1; k >= 0; --k)
        if (tokens[static_cast<size_t>(k)].kind != GlslToken::Kind::Space) return k;
    return -1;
}

}  // namespace crtforge::retroarch
