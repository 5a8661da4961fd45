// Helpers shared by the RetroArch parsers (slang_source.cpp, slangp_file.cpp): bounded file reads,
// the `root` folder no file may leave, RetroArch's line splitting and strtod-style numbers. Internal:
// header-only, not part of the public API.
#pragma once

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/files.hpp"

namespace crtforge::retroarch::detail {

// A single .slang, include or .slangp file bigger than this is refused before it is parsed.
constexpr size_t kMaxRetroArchFileBytes = 4u << 20;

// The folder every file read must stay inside, after `..` and symlinks are resolved. An empty root
// is no limit.
class RootGuard {
public:
    static Result<RootGuard> make(const std::string& root) {
        RootGuard guard;
        if (root.empty()) return guard;
        std::error_code ec;
        const std::filesystem::path canonical = std::filesystem::canonical(root, ec);
        if (ec || !std::filesystem::is_directory(canonical, ec))
            return make_error("the root folder does not exist or is not a folder", root, 0, "root");
        guard.root_ = canonical.lexically_normal();
        return guard;
    }

    // Whether `path` (resolving `..` and every symlink of the part that exists) lies inside the root.
    bool contains(const std::string& path) const {
        if (root_.empty()) return true;
        std::error_code ec;
        std::filesystem::path resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
        if (ec) return false;
        resolved = resolved.lexically_normal();
        auto r = root_.begin();
        auto p = resolved.begin();
        for (; r != root_.end(); ++r, ++p) {
            if (p == resolved.end() || *p != *r) return false;
        }
        return true;
    }

    std::string root() const { return root_.string(); }

private:
    std::filesystem::path root_;
};

// "dir/of/base" joined with `rel` (kept as is when absolute), lexically normalised; `\` in `rel` is a
// separator, as RetroArch conforms slashes on Unix too.
inline std::string resolve_relative(const std::string& base_file, std::string rel) {
    for (char& c : rel)
        if (c == '\\') c = '/';
    std::filesystem::path p(rel);
    if (p.is_absolute()) return p.lexically_normal().string();
    const std::filesystem::path dir = std::filesystem::path(base_file).parent_path();
    std::string out = (dir / p).lexically_normal().string();
    return out.empty() ? std::string(".") : out;
}

// A canonical key for cycle detection: the same file reached by two spellings is one file.
inline std::string file_identity(const std::string& path) {
    std::error_code ec;
    std::filesystem::path c = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    return ec ? std::filesystem::path(path).lexically_normal().string() : c.lexically_normal().string();
}

// The whole file (read_text_file: a regular file, at most kMaxRetroArchFileBytes), its error located
// at (at_file, at_line, field) — the line that named the file — or at the file itself.
inline Result<std::string> read_bounded(const std::string& path, const std::string& at_file, int at_line,
                                        const std::string& field, const std::string& what) {
    std::error_code ec;
    const std::string& where = at_file.empty() ? path : at_file;
    if (!std::filesystem::exists(path, ec)) return make_error(what + " '" + path + "' does not exist", where, at_line, field);
    auto text = read_text_file(path, kMaxRetroArchFileBytes);
    if (!text.ok()) return make_error(what + " '" + path + "' " + text.error().message, where, at_line, field);
    return text;
}

// The file's lines as RetroArch sees them: a UTF-8 byte order mark dropped, every '\r' removed
// (RetroArch strips them all, so CRLF and stray CRs read alike), split at '\n'; a final newline does
// not open an empty last line.
inline std::vector<std::string> split_lines(std::string text) {
    if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF &&
        static_cast<unsigned char>(text[1]) == 0xBB && static_cast<unsigned char>(text[2]) == 0xBF)
        text.erase(0, 3);
    std::string clean;
    clean.reserve(text.size());
    for (char c : text)
        if (c != '\r') clean += c;
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < clean.size()) {
        size_t end = clean.find('\n', start);
        if (end == std::string::npos) end = clean.size();
        lines.push_back(clean.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

inline bool is_blank(char c) { return c == ' ' || c == '\t'; }
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }
// C's isgraph() in the "C" locale: printable ASCII other than space.
inline bool is_graph(char c) { return c > ' ' && c < 0x7f; }

inline bool starts_with(std::string_view text, std::string_view prefix) {
    return text.size() >= prefix.size() && text.compare(0, prefix.size(), prefix) == 0;
}

// The longest prefix of `text` that C's strtod() reads as a number (decimal or hexadecimal, an
// optional sign, inf and nan), independent of the locale; `consumed` is 0 when there is none.
inline double parse_number_prefix(std::string_view text, size_t& consumed) {
    consumed = 0;
    size_t i = 0;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
        negative = text[i] == '-';
        ++i;
    }
    double value = 0;
    const char* begin = text.data() + i;
    const char* end = text.data() + text.size();
    std::chars_format format = std::chars_format::general;
    if (end - begin > 2 && begin[0] == '0' && (begin[1] == 'x' || begin[1] == 'X') &&
        (std::isxdigit(static_cast<unsigned char>(begin[2])) ||
         (begin[2] == '.' && end - begin > 3 && std::isxdigit(static_cast<unsigned char>(begin[3]))))) {
        begin += 2;
        format = std::chars_format::hex;
    }
    if (begin < end && (*begin == '+' || *begin == '-')) return 0;  // no second sign
    const auto [ptr, ec] = std::from_chars(begin, end, value, format);
    if (ptr == begin) return 0;
    if (ec == std::errc::result_out_of_range) value = HUGE_VAL;  // strtod's overflow; refused as not finite
    consumed = static_cast<size_t>(ptr - text.data());
    return negative ? -value : value;
}

// The whole of `text` as a finite number in C float syntax, or nothing.
inline std::optional<double> parse_number(std::string_view text) {
    size_t consumed = 0;
    const double value = parse_number_prefix(text, consumed);
    if (consumed == 0 || consumed != text.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

}  // namespace crtforge::retroarch::detail
