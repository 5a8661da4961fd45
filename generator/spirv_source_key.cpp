#include "generator/spirv_source_key.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

#include "crtforge/identifier_chars.hpp"

namespace crtforge {

namespace {

constexpr std::string_view kFormMacro = "CRT_FORM_";
constexpr std::string_view kSpecPrefix = "layout(constant_id = ";


size_t count_of(std::string_view text, std::string_view what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string_view::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

// A line that is one `//` comment and nothing a comment could hide: no backslash continuing it
// onto the next line, no `*/` that would end a block comment it may stand in.
bool is_plain_comment_line(std::string_view line) {
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line.substr(first, 2) != "//") return false;
    if (line.find("*/") != std::string_view::npos) return false;
    const size_t last = line.find_last_not_of(" \t\r");
    return line[last] != '\\';
}

// `#define CRT_FORM_<name> 1`, exactly as the assembler writes it.
bool is_form_define(std::string_view line) {
    constexpr std::string_view prefix = "#define CRT_FORM_";
    if (line.substr(0, prefix.size()) != prefix || line.size() < prefix.size() + 3 || line.substr(line.size() - 2) != " 1") return false;
    const std::string_view name = line.substr(prefix.size(), line.size() - prefix.size() - 2);
    for (char c : name)
        if (!detail::is_identifier_char(c)) return false;
    return !name.empty();
}

template <typename Visit>
void for_each_line(std::string_view text, Visit&& visit) {
    while (!text.empty()) {
        const size_t end = std::min(text.find('\n'), text.size());
        visit(text.substr(0, end));
        text.remove_prefix(std::min(end + 1, text.size()));
    }
}

struct FloatSpec {
    uint32_t id = 0;
    size_t value_at = 0, value_size = 0;  // the value's place in the line
    float value = 0;
};

// `layout(constant_id = N) const float NAME = VALUE;` with VALUE a finite decimal literal
// (optionally negated): BakedParams::Specialized's spelling of a float param.
std::optional<FloatSpec> float_spec_line(std::string_view line) {
    if (line.substr(0, kSpecPrefix.size()) != kSpecPrefix) return std::nullopt;
    size_t at = kSpecPrefix.size();
    FloatSpec out;
    const char* id_end = line.data() + line.size();
    auto id = std::from_chars(line.data() + at, id_end, out.id);
    if (id.ec != std::errc() || id.ptr == line.data() + at) return std::nullopt;
    at = static_cast<size_t>(id.ptr - line.data());
    constexpr std::string_view middle = ") const float ";
    if (line.substr(at, middle.size()) != middle) return std::nullopt;
    at += middle.size();
    const size_t name_start = at;
    while (at < line.size() && detail::is_identifier_char(line[at])) ++at;
    if (at == name_start || (line[name_start] >= '0' && line[name_start] <= '9')) return std::nullopt;
    if (line.substr(at, 3) != " = ") return std::nullopt;
    at += 3;
    if (line.empty() || line.back() != ';') return std::nullopt;
    const std::string_view value = line.substr(at, line.size() - 1 - at);
    if (value.empty()) return std::nullopt;
    const size_t digits = value[0] == '-' ? 1 : 0;
    if (digits >= value.size() || !((value[digits] >= '0' && value[digits] <= '9') || value[digits] == '.')) return std::nullopt;
    for (char c : value.substr(digits))
        if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')) return std::nullopt;
    double parsed = 0;  // glslang reads the literal as a double, then makes the float constant of it
    auto read = std::from_chars(value.data(), value.data() + value.size(), parsed);
    if (read.ec != std::errc() || read.ptr != value.data() + value.size()) return std::nullopt;
    out.value = static_cast<float>(parsed);
    if (!std::isfinite(out.value)) return std::nullopt;
    out.value_at = at;
    out.value_size = value.size();
    return out;
}

}  // namespace

SourceKey source_key(const std::string& source) {
    SourceKey key;
    // A source that reads its own file name keeps every byte: dropping the names would join keys.
    if (source.find("__FILE__") != std::string::npos) {
        key.text = source;
        return key;
    }
    // The form defines are names nothing reads only where no other line mentions the prefix.
    bool blank_forms = false;
    if (const size_t mentions = count_of(source, kFormMacro); mentions > 0) {
        size_t defines = 0;
        for_each_line(source, [&](std::string_view line) { defines += is_form_define(line); });
        blank_forms = defines == mentions;
    }
    std::string& out = key.text;
    out.reserve(source.size());
    bool verbatim = false;
    for_each_line(source, [&](std::string_view line) {
        if (line.rfind("#line ", 0) == 0) {
            if (const size_t quote = line.find('"'); quote != std::string_view::npos) line = line.substr(0, quote);
        } else if (is_plain_comment_line(line) || (blank_forms && is_form_define(line))) {
            line = {};
        } else if (auto spec = float_spec_line(line)) {
            // Two declarations of one id are not the assembler's: that source keeps its values.
            verbatim |= !key.float_values.emplace(spec->id, float_spec_value(spec->value)).second;
            line = line.substr(0, spec->value_at);
            out.append(line).append("?;\n");
            return;
        }
        out.append(line).push_back('\n');
    });
    if (verbatim) {
        key.float_values.clear();
        key.text = source;
    }
    return key;
}

}  // namespace crtforge
