// Small helpers over toml++ that turn "wrong or missing field" into a Diagnostic naming the file,
// line and field. Shared by the stage-spec and preset parsers.
#pragma once

#include <optional>
#include <string>

#include <toml++/toml.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spec.hpp"

namespace crtforge::detail {

// The largest template file (TOML, GLSL) read: none needs more than a few KB, and a bound read
// keeps a FIFO, a device or a huge file from taking the process's memory.
inline constexpr size_t kMaxTomlBytes = 4u << 20;

// What toml++ may be given: a bounded size and bounded dotted keys (its parser recurses per key
// segment). A file beyond them is an error at the offending line, never a stack overflow.
Status check_toml_bounds(const std::string& text, const std::string& path);

class TomlReader {
public:
    explicit TomlReader(std::string path) : path_(std::move(path)) {}

    // Parses text; a syntax error becomes a diagnostic at the parser's position.
    Result<toml::table> parse(const std::string& text) const;

    const std::string& path() const { return path_; }
    int line_of(const toml::node& node) const {
        return static_cast<int>(node.source().begin.line);
    }
    Diagnostic error(const toml::node* node, const std::string& field, const std::string& message) const {
        return make_error(message, path_, node ? line_of(*node) : 0, field,
                          node ? static_cast<int>(node->source().begin.column) : 0);
    }

    // Required/optional typed fields of a table. `owner` is the table (for the line number when
    // the field is missing), `prefix` the dotted path of that table.
    Result<std::string> string(const toml::table& owner, const std::string& key,
                               const std::string& prefix, bool required) const;
    Result<std::optional<int64_t>> integer(const toml::table& owner, const std::string& key,
                                           const std::string& prefix) const;
    Result<std::optional<bool>> boolean(const toml::table& owner, const std::string& key,
                                        const std::string& prefix) const;
    Result<std::optional<double>> number(const toml::table& owner, const std::string& key,
                                         const std::string& prefix) const;
    // [a, b] of integers, each within [min, max]; missing = nullopt.
    Result<std::optional<std::pair<int, int>>> int_pair(const toml::table& owner, const std::string& key,
                                                        const std::string& prefix, int min, int max) const;
    // A string that must be one of `names`; returns its index (nullopt when missing).
    Result<std::optional<size_t>> choice(const toml::table& owner, const std::string& key, const std::string& prefix,
                                         std::initializer_list<const char*> names) const;
    // An array of strings; missing = empty.
    Result<std::vector<std::string>> strings(const toml::table& owner, const std::string& key,
                                             const std::string& prefix) const;

    // Rejects keys not in `allowed` (typos should not be silently ignored).
    Status only_keys(const toml::table& table, std::initializer_list<const char*> allowed,
                     const std::string& prefix) const;

    // A value for a param of the given spec (type, range, enum values), from any TOML node.
    Result<Value> param_value(const toml::node& node, const ParamSpec& spec,
                              const std::string& field) const;
    // The same but the type comes from `type` and no range check (used while reading the spec
    // itself, before min/max are known).
    Result<Value> typed_value(const toml::node& node, ParamType type,
                              const std::vector<std::string>& enum_values,
                              const std::string& field) const;

private:
    std::string path_;
};

std::string join_field(const std::string& prefix, const std::string& key);
// What makes a text unsafe to copy into generated code (a control character, a Unicode line
// terminator, a trailing backslash), described for an error; empty when the text is plain.
// Every string the spec and preset readers take goes through it.
std::string unsafe_text(const std::string& text);
// A name crtforge puts into generated code and file names: a GLSL identifier (not gl_..., no
// "__") of at most kMaxIdentifierLength characters.
inline constexpr size_t kMaxIdentifierLength = 64;
bool is_identifier(const std::string& name);
// Why `name` is not one, for an error: "'x-y' is not an identifier", or its length (a long name is
// not quoted whole).
std::string not_identifier(const std::string& name);

}  // namespace crtforge::detail
