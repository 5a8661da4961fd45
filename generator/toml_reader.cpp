#include "generator/toml_reader.hpp"

#include <algorithm>
#include <cctype>

#include "crtforge/identifier_chars.hpp"
#include <cmath>

#include <fmt/format.h>

namespace crtforge::detail {

std::string join_field(const std::string& prefix, const std::string& key) {
    return prefix.empty() ? key : prefix + "." + key;
}

bool is_identifier(const std::string& name) {
    if (name.size() > kMaxIdentifierLength) return false;
    if (name.empty() || !detail::is_identifier_start(name[0])) return false;
    for (char c : name)
        if (!detail::is_identifier_char(c)) return false;
    // Names starting with gl_ or containing "__" are reserved in GLSL.
    return name.rfind("gl_", 0) != 0 && name.find("__") == std::string::npos;
}

std::string not_identifier(const std::string& name) {
    // Appends only: gcc 12 warns -Wrestrict (a false positive, GCC 105329) on `"'" + s + ...`.
    std::string out = "'";
    if (name.size() > kMaxIdentifierLength) {
        out.append(name, 0, 24);
        out += "...' is ";
        out += std::to_string(name.size());
        out += " characters long; a name is at most ";
        out += std::to_string(kMaxIdentifierLength);
        out += " (it becomes an identifier in every target language and part of file names)";
        return out;
    }
    out += name;
    out += "' is not an identifier";
    return out;
}

namespace {

// Bounds checked before toml++ sees the text: its parser recurses once per dotted-key segment
// (a header of ~40 000 segments overflowed the stack), and no template file needs more than a few.
constexpr int kMaxKeySegments = 32;

// The longest chain of dotted-key segments outside strings and comments, and the line it is on.
// Numbers (1.5, times) have one dot; quoted segments ("a"."b") count like bare ones.
std::pair<int, int> longest_dotted_key(const std::string& text) {
    int longest = 0, longest_line = 1, dots = 0, line = 1;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            dots = 0;
        } else if (c == '#') {
            while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (c == '"' || c == '\'') {
            // Skip the string (basic strings honour backslash escapes; triple quotes span lines).
            const bool triple = text.compare(i, 3, std::string(3, c)) == 0;
            const std::string close = triple ? std::string(3, c) : std::string(1, c);
            size_t j = i + close.size();
            while (j < text.size() && text.compare(j, close.size(), close) != 0) {
                if (text[j] == '\\' && c == '"') ++j;
                else if (text[j] == '\n') {
                    if (!triple) break;
                    ++line;
                }
                ++j;
            }
            i = std::min(text.size(), j + close.size()) - 1;
        } else if (c == '.') {
            if (++dots > longest) {
                longest = dots;
                longest_line = line;
            }
        } else if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' || c == '\t')) {
            dots = 0;
        }
    }
    return {longest + 1, longest_line};
}

}  // namespace

Status check_toml_bounds(const std::string& text, const std::string& path) {
    if (text.size() > kMaxTomlBytes)
        return make_error(fmt::format("is {} bytes; a template file may have at most {}", text.size(), kMaxTomlBytes), path);
    if (auto [segments, line] = longest_dotted_key(text); segments > kMaxKeySegments)
        return make_error(fmt::format("a key of {} dotted segments; at most {} are allowed", segments, kMaxKeySegments), path, line);
    return Ok{};
}

Result<toml::table> TomlReader::parse(const std::string& text) const {
    if (auto bounds = check_toml_bounds(text, path_); !bounds.ok()) return bounds.error();
    try {
        return toml::parse(text, path_);
    } catch (const toml::parse_error& e) {
        return make_error(std::string(e.description()), path_,
                          static_cast<int>(e.source().begin.line), {},
                          static_cast<int>(e.source().begin.column));
    }
}

std::string unsafe_text(const std::string& text) {
    for (size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) return fmt::format("control character U+{:04X} at byte {}", c, i);
        // U+0085 (C2 85), U+2028 and U+2029 (E2 80 A8/A9) end a line for some consumers.
        if (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0x85)
            return fmt::format("line terminator U+0085 at byte {}", i);
        if (c == 0xE2 && i + 2 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0x80 &&
            (static_cast<unsigned char>(text[i + 2]) == 0xA8 || static_cast<unsigned char>(text[i + 2]) == 0xA9))
            return fmt::format("line terminator U+{:04X} at byte {}", static_cast<unsigned char>(text[i + 2]) == 0xA8 ? 0x2028 : 0x2029, i);
    }
    // In a // comment a trailing backslash continues the comment onto the next line.
    if (!text.empty() && text.back() == '\\') return "a trailing backslash";
    return {};
}

Result<std::string> TomlReader::string(const toml::table& owner, const std::string& key,
                                       const std::string& prefix, bool required) const {
    const toml::node* node = owner.get(key);
    if (!node) {
        if (required) return error(&owner, join_field(prefix, key), "is required but missing");
        return std::string{};
    }
    if (!node->is_string()) return error(node, join_field(prefix, key), "must be a string");
    std::string text(node->as_string()->get());
    // An empty string is a mistake, not the key left out (`base = ""` once meant "no base").
    if (text.empty()) return error(node, join_field(prefix, key), "is empty (leave the key out instead)");
    if (const std::string bad = unsafe_text(text); !bad.empty())
        return error(node, join_field(prefix, key), "has a " + bad + " (text reaches generated code's comments; one plain line only)");
    return text;
}

Result<std::optional<int64_t>> TomlReader::integer(const toml::table& owner, const std::string& key,
                                                   const std::string& prefix) const {
    const toml::node* node = owner.get(key);
    if (!node) return std::optional<int64_t>{};
    if (!node->is_integer()) return error(node, join_field(prefix, key), "must be an integer");
    return std::optional<int64_t>{node->as_integer()->get()};
}

Result<std::optional<bool>> TomlReader::boolean(const toml::table& owner, const std::string& key,
                                                const std::string& prefix) const {
    const toml::node* node = owner.get(key);
    if (!node) return std::optional<bool>{};
    if (!node->is_boolean()) return error(node, join_field(prefix, key), "must be true or false");
    return std::optional<bool>{node->as_boolean()->get()};
}

Result<std::optional<double>> TomlReader::number(const toml::table& owner, const std::string& key,
                                                 const std::string& prefix) const {
    const toml::node* node = owner.get(key);
    if (!node) return std::optional<double>{};
    if (node->is_integer()) return std::optional<double>{static_cast<double>(node->as_integer()->get())};
    if (!node->is_floating_point() || !std::isfinite(node->as_floating_point()->get()))
        return error(node, join_field(prefix, key), "must be a finite number");
    return std::optional<double>{node->as_floating_point()->get()};
}

Result<std::optional<std::pair<int, int>>> TomlReader::int_pair(const toml::table& owner, const std::string& key,
                                                                const std::string& prefix, int min, int max) const {
    const toml::node* node = owner.get(key);
    if (!node) return std::optional<std::pair<int, int>>{};
    const toml::array* a = node->as_array();
    const std::string field = join_field(prefix, key);
    if (!a || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer())
        return error(node, field, "must be [a, b] of two integers");
    const int64_t x = a->get(0)->as_integer()->get(), y = a->get(1)->as_integer()->get();
    if (x < min || x > max || y < min || y > max)
        return error(node, field, fmt::format("[{}, {}] is outside {}..{}", x, y, min, max));
    return std::optional<std::pair<int, int>>{std::make_pair(static_cast<int>(x), static_cast<int>(y))};
}

Result<std::optional<size_t>> TomlReader::choice(const toml::table& owner, const std::string& key, const std::string& prefix,
                                                 std::initializer_list<const char*> names) const {
    auto text = string(owner, key, prefix, false);
    if (!text.ok()) return text.error();
    if (!owner.get(key)) return std::optional<size_t>{};
    size_t i = 0;
    for (const char* n : names) {
        if (text.value() == n) return std::optional<size_t>{i};
        ++i;
    }
    return error(owner.get(key), join_field(prefix, key),
                 "'" + text.value() + "' is not one of: " + join_list(std::vector<std::string>(names.begin(), names.end())));
}

Result<std::vector<std::string>> TomlReader::strings(const toml::table& owner, const std::string& key,
                                                     const std::string& prefix) const {
    std::vector<std::string> out;
    const toml::node* node = owner.get(key);
    if (!node) return out;
    const toml::array* array = node->as_array();
    if (!array) return error(node, join_field(prefix, key), "must be an array of strings");
    for (const toml::node& item : *array) {
        if (!item.is_string())
            return error(&item, join_field(prefix, key), "must be an array of strings");
        out.emplace_back(item.as_string()->get());
        if (const std::string bad = unsafe_text(out.back()); !bad.empty())
            return error(&item, join_field(prefix, key), "has a " + bad + " (one plain line only)");
    }
    return out;
}

Status TomlReader::only_keys(const toml::table& table, std::initializer_list<const char*> allowed,
                             const std::string& prefix) const {
    for (const auto& [key, node] : table) {
        bool known = false;
        for (const char* a : allowed) known = known || key.str() == a;
        if (!known) {
            const std::string list = join_list(std::vector<std::string>(allowed.begin(), allowed.end()));
            return error(&node, join_field(prefix, std::string(key.str())),
                         "unknown key (expected one of: " + list + ")");
        }
    }
    return Ok{};
}

namespace {

// "#rrggbb" or [r, g, b] with components in 0..1.
bool read_color(const toml::node& node, Color& out) {
    if (const auto* s = node.as_string()) return parse_hex_color(s->get(), out);
    if (const auto* a = node.as_array()) {
        if (a->size() != 3) return false;
        for (size_t i = 0; i < 3; ++i) {
            const toml::node& c = *a->get(i);
            if (c.is_floating_point()) out[i] = c.as_floating_point()->get();
            else if (c.is_integer()) out[i] = static_cast<double>(c.as_integer()->get());
            else return false;
            if (!(out[i] >= 0.0 && out[i] <= 1.0)) return false;
        }
        return true;
    }
    return false;
}

}  // namespace

Result<Value> TomlReader::typed_value(const toml::node& node, ParamType type,
                                      const std::vector<std::string>& enum_values,
                                      const std::string& field) const {
    switch (type) {
        case ParamType::Float:
            if (node.is_floating_point()) {
                double v = node.as_floating_point()->get();
                if (!std::isfinite(v)) return error(&node, field, "must be a finite number");
                return Value{v};
            }
            if (node.is_integer()) return Value{static_cast<double>(node.as_integer()->get())};
            return error(&node, field, "must be a number (float param)");
        case ParamType::Int:
            if (node.is_integer()) return Value{node.as_integer()->get()};
            return error(&node, field, "must be an integer (int param)");
        case ParamType::Bool:
            if (node.is_boolean()) return Value{node.as_boolean()->get()};
            return error(&node, field, "must be true or false (bool param)");
        case ParamType::Enum: {
            if (!node.is_string()) return error(&node, field, "must be a string (enum param)");
            std::string v(node.as_string()->get());
            if (const std::string bad = unsafe_text(v); !bad.empty()) return error(&node, field, "has a " + bad);
            for (const auto& e : enum_values)
                if (e == v) return Value{v};
            const std::string list = join_list(enum_values);
            return error(&node, field, "'" + v + "' is not one of: " + list);
        }
        case ParamType::Color: {
            Color c{};
            if (read_color(node, c)) return Value{c};
            return error(&node, field, "must be a colour: \"#rrggbb\" or [r, g, b] with 0..1 components");
        }
    }
    return error(&node, field, "unsupported type");
}

Result<Value> TomlReader::param_value(const toml::node& node, const ParamSpec& spec,
                                      const std::string& field) const {
    auto value = typed_value(node, spec.type, spec.enum_values, field);
    if (!value.ok()) return value;
    double v = 0;
    if (auto d = std::get_if<double>(&value.value())) v = *d;
    else if (auto i = std::get_if<int64_t>(&value.value())) v = static_cast<double>(*i);
    else return value;
    if ((spec.min && v < *spec.min) || (spec.max && v > *spec.max))
        return error(&node, field,
                     fmt::format("{} is outside the range [{}, {}] declared at {}:{}",
                                 value_to_string(value.value()), spec.min.value_or(-INFINITY),
                                 spec.max.value_or(INFINITY), spec.where.file, spec.where.line));
    return value;
}

}  // namespace crtforge::detail
