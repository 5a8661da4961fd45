// Reads a RetroArch .slang shader: includes, metadata pragmas, the two stages. The rules, and where
// they differ from RetroArch, are listed in slang_source.hpp.
#include "generator/retroarch/slang_source.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <filesystem>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "crtforge/identifier_chars.hpp"
#include "generator/retroarch/retroarch_files.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge::retroarch {

namespace {

using detail::is_blank;
using detail::starts_with;

// RetroArch's render target formats (glslang_util.c: glslang_find_format).
constexpr const char* kFormats[] = {
    "R8_UNORM",         "R8_UINT",          "R8_SINT",          "R8G8_UNORM",
    "R8G8_UINT",        "R8G8_SINT",        "R8G8B8A8_UNORM",   "R8G8B8A8_UINT",
    "R8G8B8A8_SINT",    "R8G8B8A8_SRGB",    "A2B10G10R10_UNORM_PACK32",
    "A2B10G10R10_UINT_PACK32",              "R16_UINT",         "R16_SINT",
    "R16_SFLOAT",       "R16G16_UINT",      "R16G16_SINT",      "R16G16_SFLOAT",
    "R16G16B16A16_UINT", "R16G16B16A16_SINT", "R16G16B16A16_SFLOAT", "R32_UINT",
    "R32_SINT",         "R32_SFLOAT",       "R32G32_UINT",      "R32G32_SINT",
    "R32G32_SFLOAT",    "R32G32B32A32_UINT", "R32G32B32A32_SINT", "R32G32B32A32_SFLOAT",
};

// RetroArch's id and description buffers hold 63 bytes and a terminator.
constexpr size_t kMaxParameterText = 63;

struct Line {
    int file = 0;    // index into Expander::files
    int number = 0;  // 1-based, in that file
    std::string text;
};

std::string where_str(const std::string& file, int line) { return file + ":" + std::to_string(line); }

// Whether glslang can take `path` inside #line's double quotes: it reads the name verbatim.
bool quotable(const std::string& path) {
    return std::none_of(path.begin(), path.end(),
                        [](char c) { return c == '"' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

// Include expansion: every file's lines in reading order, includes replaced by their lines.
struct Expander {
    explicit Expander(const detail::RootGuard& root_guard) : guard(root_guard) {}

    const detail::RootGuard& guard;
    std::vector<std::string> files, identities;
    std::vector<std::string> missing_optional;
    std::vector<Line> lines;
    std::string version_line;
    std::vector<std::string> stack_ids, stack_paths;
    size_t expanded = 0;

    int file_index(const std::string& path, const std::string& identity) {
        for (size_t i = 0; i < identities.size(); ++i)
            if (identities[i] == identity) return static_cast<int>(i);
        files.push_back(path);
        identities.push_back(identity);
        return static_cast<int>(files.size() - 1);
    }

    // `at_file`/`at_line`: the #include naming `path` (empty for the shader itself).
    Status expand(const std::string& path, const std::string& at_file, int at_line, int depth) {
        const bool root_file = at_file.empty();
        auto fail = [&](const std::string& message) {
            return root_file ? make_error(message, path, 0, "path") : make_error(message, at_file, at_line, "include");
        };
        if (!guard.contains(path)) return fail("'" + path + "' is outside the root folder " + guard.root());
        if (!quotable(path))
            return fail("'" + path + "' contains a double quote or a control character, which a #line directive cannot carry");
        const std::string identity = detail::file_identity(path);
        if (const auto it = std::find(stack_ids.begin(), stack_ids.end(), identity); it != stack_ids.end()) {
            std::string cycle;
            for (auto p = stack_paths.begin() + (it - stack_ids.begin()); p != stack_paths.end(); ++p) cycle += *p + " -> ";
            return fail("include cycle: " + cycle + path);
        }
        if (depth > kMaxIncludeDepth)
            return fail(fmt::format("includes are nested more than {} deep", kMaxIncludeDepth));
        auto text = detail::read_bounded(path, at_file, at_line, root_file ? "" : "include",
                                         root_file ? "shader" : "included file");
        if (!text.ok()) return text.error();
        if (text.value().find('\0') != std::string::npos)
            return make_error("contains a NUL byte; a .slang file is text", path, 0);
        const int index = file_index(path, identity);
        const std::vector<std::string> file_lines = detail::split_lines(std::move(text.value()));

        size_t first = 0;
        if (root_file) {
            if (file_lines.empty() || !starts_with(file_lines[0], "#version "))
                return make_error("the first line must be the #version statement (e.g. '#version 450')", path, 1, "version");
            version_line = file_lines[0];
            first = 1;
        }
        stack_ids.push_back(identity);
        stack_paths.push_back(path);
        for (size_t i = first; i < file_lines.size(); ++i) {
            const std::string& text_line = file_lines[i];
            const int number = static_cast<int>(i + 1);
            const bool optional = starts_with(text_line, "#pragma include_optional ");
            if (optional || starts_with(text_line, "#include ")) {
                const size_t open = text_line.find('"');
                const size_t close = open == std::string::npos ? open : text_line.find('"', open + 1);
                if (close == std::string::npos || close == open + 1)
                    return make_error(std::string("expected ") + (optional ? "#pragma include_optional" : "#include") +
                                          " \"file\"",
                                      path, number, "include");
                const std::string included = detail::resolve_relative(path, text_line.substr(open + 1, close - open - 1));
                if (optional) {
                    std::error_code ec;
                    if (!guard.contains(included))
                        return make_error("'" + included + "' is outside the root folder " + guard.root(), path, number, "include");
                    if (!std::filesystem::exists(included, ec)) {
                        if (std::find(missing_optional.begin(), missing_optional.end(), included) == missing_optional.end())
                            missing_optional.push_back(included);
                        continue;
                    }
                }
                if (auto st = expand(included, path, number, depth + 1); !st.ok()) return st;
                continue;
            }
            expanded += text_line.size() + 1;
            if (expanded > kMaxExpandedBytes)
                return make_error(fmt::format("the shader with its includes exceeds {} bytes", kMaxExpandedBytes), path,
                                  number, "include");
            lines.push_back(Line{index, number, text_line});
        }
        stack_ids.pop_back();
        stack_paths.pop_back();
        return Ok{};
    }
};

// `#endif`, `#else`, `#elif`: a #line emitted inside a branch the preprocessor skips is ignored, so
// line tracking is re-established after each of them (as RetroArch does after #endif).
bool ends_conditional_branch(const std::string& text) {
    size_t i = 0;
    while (i < text.size() && is_blank(text[i])) ++i;
    if (i >= text.size() || text[i] != '#') return false;
    ++i;
    while (i < text.size() && is_blank(text[i])) ++i;
    for (const char* word : {"endif", "else", "elif"}) {
        const std::string_view w(word);
        if (text.compare(i, w.size(), w) == 0) {
            const size_t after = i + w.size();
            if (after == text.size() || !crtforge::detail::is_identifier_char(text[after]))
                return true;
        }
    }
    return false;
}

// A stage's GLSL: the #version line, the #line extension, the stage's lines with #line directives
// (or blank lines, for short forward gaps in the same file) keeping every line at its source place.
std::string build_stage(const std::string& version_line, const std::vector<const Line*>& lines,
                        const std::vector<std::string>& files) {
    constexpr int kMaxBlankPadding = 8;
    std::string out = version_line + "\n#extension GL_GOOGLE_cpp_style_line_directive : require\n";
    int file = -1, next = 0;
    bool force = true, continued = false;
    for (const Line* line : lines) {
        const bool forward = line->file == file && line->number >= next;
        const bool directive = force || !forward || line->number - next > kMaxBlankPadding;
        if (directive && !(continued && forward)) {
            out += fmt::format("#line {} \"{}\"\n", line->number, files[static_cast<size_t>(line->file)]);
        } else {
            out.append(static_cast<size_t>(line->number - next), '\n');
        }
        out += line->text;
        out += '\n';
        file = line->file;
        next = line->number + 1;
        continued = !line->text.empty() && line->text.back() == '\\';
        force = ends_conditional_branch(line->text);
    }
    return out;
}

struct Declared {
    std::string value;
    SourceLocation where;
};

// `#pragma parameter ID "DESCRIPTION" INITIAL MINIMUM MAXIMUM [STEP]`, as slang_process.cpp's
// glslang_parse_meta reads it.
Result<SlangParameter> parse_parameter(const std::string& text, const std::string& file, int line) {
    auto fail = [&](const std::string& message) {
        return make_error(message + " (expected #pragma parameter ID \"DESCRIPTION\" INITIAL MINIMUM MAXIMUM [STEP])",
                          file, line, "pragma parameter");
    };
    SlangParameter p;
    p.where = SourceLocation{file, line};
    size_t i = std::string_view("#pragma parameter ").size();
    while (i < text.size() && is_blank(text[i])) ++i;
    size_t end = i;
    while (end < text.size() && !is_blank(text[end])) ++end;
    if (end == i) return fail("the parameter has no ID");
    p.id = text.substr(i, end - i);
    if (p.id.size() > kMaxParameterText)
        return fail(fmt::format("the ID is {} bytes; RetroArch refuses more than {}", p.id.size(), kMaxParameterText));
    i = end;
    while (i < text.size() && is_blank(text[i])) ++i;
    if (i >= text.size() || text[i] != '"') return fail("the description of '" + p.id + "' must be in double quotes");
    const size_t close = text.find('"', i + 1);
    if (close == std::string::npos) return fail("the description of '" + p.id + "' has no closing double quote");
    p.description = text.substr(i + 1, close - i - 1);
    if (p.description.size() > kMaxParameterText)
        return fail(fmt::format("the description of '{}' is {} bytes; RetroArch refuses more than {}", p.id,
                                p.description.size(), kMaxParameterText));
    i = close + 1;
    double* numbers[] = {&p.initial, &p.minimum, &p.maximum};
    const char* names[] = {"INITIAL", "MINIMUM", "MAXIMUM"};
    for (int k = 0; k < 3; ++k) {
        while (i < text.size() && is_blank(text[i])) ++i;
        size_t consumed = 0;
        const double value = detail::parse_number_prefix(std::string_view(text).substr(i), consumed);
        if (consumed == 0) return fail(std::string(names[k]) + " of '" + p.id + "' is not a number");
        if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max())
            return fail(std::string(names[k]) + " of '" + p.id + "' is not a finite number within float range (RetroArch reads it as a float)");
        *numbers[k] = value;
        i += consumed;
    }
    while (i < text.size() && is_blank(text[i])) ++i;
    size_t consumed = 0;
    const double step = i < text.size() ? detail::parse_number_prefix(std::string_view(text).substr(i), consumed) : 0.0;
    if (consumed > 0 && std::isfinite(step) && std::fabs(step) > std::numeric_limits<float>::max())
        return fail("STEP of '" + p.id + "' is beyond float range (RetroArch reads it as a float)");
    if (consumed > 0 && std::isfinite(step)) {
        p.step = step;
        p.has_step = true;
    } else {
        p.step = static_cast<double>(0.1f * (static_cast<float>(p.maximum) - static_cast<float>(p.minimum)));
    }
    return p;
}

bool same_as_retroarch_sees_it(const SlangParameter& a, const SlangParameter& b) {
    auto f = [](double v) { return static_cast<float>(v); };
    return a.description == b.description && f(a.initial) == f(b.initial) && f(a.minimum) == f(b.minimum) &&
           f(a.maximum) == f(b.maximum) && f(a.step) == f(b.step);
}

// The text after `#pragma <keyword> ` with leading blanks skipped.
std::string pragma_argument(const std::string& text, std::string_view prefix) {
    size_t i = prefix.size();
    while (i < text.size() && is_blank(text[i])) ++i;
    return text.substr(i);
}

}  // namespace

Result<SlangSource> load_slang_source(const std::string& path, const std::string& root) {
    auto guard = detail::RootGuard::make(root);
    if (!guard.ok()) return guard.error();
    Expander ex(guard.value());
    if (auto st = ex.expand(path, "", 0, 0); !st.ok()) return st.error();

    SlangSource out;
    out.path = path;
    std::optional<Declared> name, format;
    enum class Section { Both, Vertex, Fragment } section = Section::Both;
    bool has_vertex = false, has_fragment = false;
    std::vector<const Line*> vertex, fragment;
    for (const Line& line : ex.lines) {
        const std::string& text = line.text;
        const std::string& file = ex.files[static_cast<size_t>(line.file)];
        if (starts_with(text, "#pragma stage ")) {
            if (text == "#pragma stage vertex") {
                section = Section::Vertex;
                has_vertex = true;
            } else if (text == "#pragma stage fragment") {
                section = Section::Fragment;
                has_fragment = true;
            } else {
                return make_error("expected exactly '#pragma stage vertex' or '#pragma stage fragment' (RetroArch "
                                  "compares the whole line and drops the code after any other)",
                                  file, line.number, "pragma stage");
            }
            continue;
        }
        if (starts_with(text, "#pragma name ")) {
            const std::string value = pragma_argument(text, "#pragma name ");
            if (value.empty()) return make_error("the name is missing", file, line.number, "pragma name");
            if (std::any_of(value.begin(), value.end(), [](char c) { return detail::is_space(c); }))
                return make_error("'" + value + "' is not one name (RetroArch would take the whole rest of the line)", file,
                                  line.number, "pragma name");
            if (name)
                return make_error("a second #pragma name (the first is at " + where_str(name->where.file, name->where.line) + ")",
                                  file, line.number, "pragma name");
            // The name becomes the pass's alias: an identifier in every target and part of file names.
            if (value.size() > crtforge::detail::kMaxIdentifierLength)
                return make_error(crtforge::detail::not_identifier(value), file, line.number, "pragma name");
            name = Declared{value, SourceLocation{file, line.number}};
            continue;
        }
        if (starts_with(text, "#pragma format ")) {
            const std::string value = pragma_argument(text, "#pragma format ");
            if (std::find_if(std::begin(kFormats), std::end(kFormats), [&](const char* f) { return value == f; }) ==
                std::end(kFormats))
                return make_error("unknown format '" + value + "' (RetroArch's formats: " +
                                      join_list(std::vector<std::string>(std::begin(kFormats), std::end(kFormats))) + ")",
                                  file, line.number, "pragma format");
            if (format)
                return make_error("a second #pragma format (the first is at " + where_str(format->where.file, format->where.line) +
                                      ")",
                                  file, line.number, "pragma format");
            format = Declared{value, SourceLocation{file, line.number}};
            continue;
        }
        if (starts_with(text, "#pragma parameter ")) {
            auto parameter = parse_parameter(text, file, line.number);
            if (!parameter.ok()) return parameter.error();
            const SlangParameter& p = parameter.value();
            const auto it = std::find_if(out.parameters.begin(), out.parameters.end(),
                                         [&](const SlangParameter& q) { return q.id == p.id; });
            if (it == out.parameters.end()) {
                out.parameters.push_back(p);
            } else if (!same_as_retroarch_sees_it(*it, p)) {
                return make_error(fmt::format("'{}' is declared again with a different description or values "
                                              "(first at {}: \"{}\" {} {} {} {}; here \"{}\" {} {} {} {})",
                                              p.id, where_str(it->where.file, it->where.line), it->description, it->initial,
                                              it->minimum, it->maximum, it->step, p.description, p.initial, p.minimum,
                                              p.maximum, p.step),
                                  file, line.number, "pragma parameter");
            }
            continue;
        }
        if (section != Section::Fragment) vertex.push_back(&line);
        if (section != Section::Vertex) fragment.push_back(&line);
    }
    if (!has_vertex || !has_fragment)
        return make_error(std::string("the shader has no ") +
                              (!has_vertex && !has_fragment ? "'#pragma stage vertex' nor '#pragma stage fragment'"
                               : has_vertex                 ? "'#pragma stage fragment'"
                                                            : "'#pragma stage vertex'") +
                              " section",
                          path, 0, "pragma stage");

    out.vertex = build_stage(ex.version_line, vertex, ex.files);
    out.fragment = build_stage(ex.version_line, fragment, ex.files);
    if (name) out.name = name->value;
    if (format) out.format = format->value;
    out.files = std::move(ex.files);
    out.missing_optional = std::move(ex.missing_optional);
    return out;
}

}  // namespace crtforge::retroarch
