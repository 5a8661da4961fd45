#include "crtforge/inert_text.hpp"

#include <cstdint>

namespace crtforge {

std::string inert_comment(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) {
            out += ' ';
        } else if (c == '\\') {
            out += '/';
        } else if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0x85) {
            out += ' ';  // U+0085 NEXT LINE
            ++i;
        } else if (c == 0xE2 && i + 2 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0x80 &&
                   (static_cast<unsigned char>(text[i + 2]) == 0xA8 || static_cast<unsigned char>(text[i + 2]) == 0xA9)) {
            out += ' ';  // U+2028 LINE SEPARATOR, U+2029 PARAGRAPH SEPARATOR
            i += 2;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

std::string inert_quoted(std::string_view text) {
    std::string out = inert_comment(text);
    for (char& c : out)
        if (c == '"') c = '\'';
    return out;
}

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string xml_escape(std::string_view text) {
    static constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        // The length of the UTF-8 sequence starting here (0: not a valid start byte).
        const size_t n = c < 0x80 ? 1 : (c >= 0xC2 && c <= 0xDF) ? 2 : (c >= 0xE0 && c <= 0xEF) ? 3 : (c >= 0xF0 && c <= 0xF4) ? 4 : 0;
        bool valid = n && i + n <= text.size();
        uint32_t code = n == 1 ? c : n == 2 ? c & 0x1Fu : n == 3 ? c & 0x0Fu : c & 0x07u;
        for (size_t k = 1; valid && k < n; ++k) {
            const auto b = static_cast<unsigned char>(text[i + k]);
            valid = (b & 0xC0) == 0x80;
            code = code << 6 | (b & 0x3Fu);
        }
        // Overlong forms, surrogates and code points past U+10FFFF are not UTF-8 either.
        valid = valid && !(n == 3 && (code < 0x800 || (code >= 0xD800 && code <= 0xDFFF))) && !(n == 4 && (code < 0x10000 || code > 0x10FFFF));
        const bool allowed = valid && (code >= 0x20 || code == 0x9 || code == 0xA || code == 0xD) && code != 0xFFFE && code != 0xFFFF;
        if (!allowed) out += kReplacement;
        else if (n == 1) out += html_escape(text.substr(i, 1));
        else out += text.substr(i, n);
        i += valid ? n : 1;
    }
    return out;
}

}  // namespace crtforge
