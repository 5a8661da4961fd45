// Strict decimal integers for command-line and plan text: the whole text is the number, no sign
// unless negative, no spaces, no overflow. sscanf("%d") wraps 4294967297 around to 1; this refuses it.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>

namespace crtforge {

inline std::optional<int64_t> parse_int(std::string_view text) {
    int64_t value = 0;
    if (text.empty() || text.size() > 19) return std::nullopt;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// "A<sep>B" as two strict integers.
inline std::optional<std::pair<int64_t, int64_t>> parse_int_pair(std::string_view text, char sep, char alt_sep = 0) {
    size_t at = text.find(sep);
    if (at == std::string_view::npos && alt_sep) at = text.find(alt_sep);
    if (at == std::string_view::npos) return std::nullopt;
    const auto a = parse_int(text.substr(0, at)), b = parse_int(text.substr(at + 1));
    if (!a || !b) return std::nullopt;
    return std::make_pair(*a, *b);
}

}  // namespace crtforge
