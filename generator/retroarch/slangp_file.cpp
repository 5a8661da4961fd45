// Reads a RetroArch .slangp preset and its #reference graph. The rules, and where they differ from
// RetroArch, are listed in slangp_file.hpp.
#include "generator/retroarch/slangp_file.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string_view>

#include <fmt/format.h>

#include "generator/retroarch/retroarch_files.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge::retroarch {

namespace {

using detail::is_blank;
using detail::is_graph;
using detail::is_space;
using detail::starts_with;

// The per-pass keys RetroArch reads as <prefix><N> (video_shader_parse_pass).
constexpr const char* kPassKeys[] = {"shader",       "alias",        "filter_linear", "wrap_mode",
                                     "mipmap_input", "float_framebuffer", "srgb_framebuffer", "frame_count_mod",
                                     "scale_type",   "scale_type_x", "scale_type_y", "scale",
                                     "scale_x",      "scale_y"};
constexpr const char* kWrapModes[] = {"clamp_to_border", "clamp_to_edge", "repeat", "mirrored_repeat"};
constexpr const char* kScaleTypes[] = {"source", "viewport", "absolute"};
constexpr const char* kTextureSuffixes[] = {"_linear", "_mipmap", "_wrap_mode"};
// Longer texture names are cut to this by RetroArch (its id buffers hold 64 bytes).
constexpr size_t kMaxTextureName = 63;

struct Entry {
    std::string key, value;
    SourceLocation where;
};

struct Reference {
    std::string path;  // resolved
    SourceLocation where;
};

// One preset file's entries (the first of each key, in file order, #include'd files in place) and
// its #reference lines.
struct PresetText {
    std::string path;
    std::vector<Entry> entries;
    std::map<std::string, size_t> index;
    std::vector<Reference> references;

    const Entry* find(const std::string& key) const {
        const auto it = index.find(key);
        return it == index.end() ? nullptr : &entries[it->second];
    }
};

// "shader12" -> ("shader", 12) when the prefix is a pass key; nothing otherwise.
std::optional<std::pair<std::string, long>> split_pass_key(const std::string& key) {
    size_t digits = key.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(key[digits - 1]))) --digits;
    if (digits == key.size() || digits == 0 || key.size() - digits > 6) return std::nullopt;
    const std::string prefix = key.substr(0, digits);
    if (std::none_of(std::begin(kPassKeys), std::end(kPassKeys), [&](const char* k) { return prefix == k; }))
        return std::nullopt;
    return std::make_pair(prefix, std::strtol(key.c_str() + digits, nullptr, 10));
}

bool is_preset_key(const std::string& key) {
    return key == "shaders" || key == "feedback_pass" || key == "textures" || key == "parameters" ||
           split_pass_key(key).has_value();
}

template <size_t N>
bool one_of(const std::string& value, const char* const (&set)[N]) {
    return std::any_of(std::begin(set), std::end(set), [&](const char* s) { return value == s; });
}

template <size_t N>
std::string list_of(const char* const (&set)[N]) {
    return join_list(std::vector<std::string>(std::begin(set), std::end(set)), " | ");
}

// config_file_strip_comment: a '#' ends the line unless a quoted string opened before it closes after it.
std::string strip_comment(const std::string& line) {
    const size_t hash = line.find('#');
    if (hash == std::string::npos) return line;
    const size_t quote = line.find('"');
    if (quote != std::string::npos && quote < hash) {
        const size_t close = line.find('"', quote + 1);
        if (close != std::string::npos && close > hash) return line;
    }
    return line.substr(0, hash);
}

// config_file_extract_value for directives: a quoted string, or a run of printable characters.
std::string directive_value(const std::string& text) {
    size_t i = 0;
    while (i < text.size() && is_space(text[i])) ++i;
    if (i < text.size() && text[i] == '"') {
        const size_t close = text.find('"', i + 1);
        return text.substr(i + 1, close == std::string::npos ? std::string::npos : close - i - 1);
    }
    size_t end = i;
    while (end < text.size() && is_graph(text[end])) ++end;
    return text.substr(i, end - i);
}

// Whether RetroArch would read `text` as a `key = value` entry.
bool looks_like_entry(const std::string& text) {
    size_t i = 0;
    while (i < text.size() && is_space(text[i])) ++i;
    const size_t key = i;
    while (i < text.size() && is_graph(text[i])) ++i;
    if (i == key || text.substr(key, i - key).find('=') != std::string::npos) return false;
    while (i < text.size() && is_space(text[i])) ++i;
    return i < text.size() && text[i] == '=';
}

class Reader {
public:
    Reader(const detail::RootGuard& guard, std::vector<Diagnostic>& warnings) : guard_(guard), warnings_(warnings) {}

    // The preset at `path`, read once; `at` is the line naming it (empty for the preset loaded).
    Result<const PresetText*> read(const std::string& path, const SourceLocation& at) {
        const std::string identity = detail::file_identity(path);
        if (const auto it = cache_.find(identity); it != cache_.end()) return static_cast<const PresetText*>(it->second.get());
        auto text = std::make_unique<PresetText>();
        text->path = path;
        std::vector<std::string> include_stack;
        if (auto st = parse_into(*text, path, at, "#reference", 0, include_stack); !st.ok()) return st.error();
        const PresetText* out = text.get();
        cache_.emplace(identity, std::move(text));
        return out;
    }

    const std::vector<std::string>& files() const { return files_; }

private:
    Status parse_into(PresetText& out, const std::string& path, const SourceLocation& at, const std::string& field,
                      int include_depth, std::vector<std::string>& include_stack) {
        if (!guard_.contains(path))
            return make_error("'" + path + "' is outside the root folder " + guard_.root(), at.file.empty() ? path : at.file,
                              at.line, at.file.empty() ? "path" : field);
        auto text = detail::read_bounded(path, at.file, at.line, at.file.empty() ? "" : field, "preset");
        if (!text.ok()) return text.error();
        if (text.value().find('\0') != std::string::npos) return make_error("contains a NUL byte; a .slangp file is text", path, 0);
        const std::string identity = detail::file_identity(path);
        if (std::find(file_ids_.begin(), file_ids_.end(), identity) == file_ids_.end()) {
            file_ids_.push_back(identity);
            files_.push_back(path);
        }
        include_stack.push_back(identity);
        const std::vector<std::string> lines = detail::split_lines(std::move(text.value()));
        int block_start = 0;  // the line of an open /* comment
        for (size_t i = 0; i < lines.size(); ++i) {
            const std::string& raw = lines[i];
            const int number = static_cast<int>(i + 1);
            const SourceLocation here{path, number};
            if (block_start) {
                const size_t close = raw.find("*/");
                if (close != std::string::npos) {
                    block_start = 0;
                    continue;
                }
                if (looks_like_entry(strip_comment(raw)))
                    return make_error("this 'key = value' line lies inside the /* comment opened at line " +
                                          std::to_string(block_start) +
                                          ", but RetroArch reads it: a .slangp has no block comments",
                                      path, number);
                continue;
            }
            if (starts_with(raw, "#")) {
                if (starts_with(raw, "#reference ")) {
                    const std::string value = directive_value(raw.substr(11));
                    if (value.empty()) return make_error("#reference needs a path", path, number, "#reference");
                    const std::string resolved = detail::resolve_relative(path, value);
                    if (include_depth > 0)
                        warnings_.push_back(make_error("ignored: RetroArch ignores #reference in an #include'd file",
                                                       path, number, "#reference"));
                    else
                        out.references.push_back(Reference{resolved, here});
                } else if (starts_with(raw, "#include ")) {
                    const std::string value = directive_value(raw.substr(9));
                    if (value.empty()) return make_error("#include needs a path", path, number, "#include");
                    const std::string resolved = detail::resolve_relative(path, value);
                    if (include_depth + 1 > kMaxPresetIncludeDepth)
                        return make_error(fmt::format("#include is nested more than {} deep", kMaxPresetIncludeDepth), path,
                                          number, "#include");
                    if (std::find(include_stack.begin(), include_stack.end(), detail::file_identity(resolved)) !=
                        include_stack.end())
                        return make_error("#include cycle: '" + resolved + "' is already being read", path, number,
                                          "#include");
                    if (auto st = parse_into(out, resolved, here, "#include", include_depth + 1, include_stack); !st.ok())
                        return st;
                }
                continue;  // any other line starting with '#' is a comment
            }
            size_t i0 = 0;
            while (i0 < raw.size() && is_space(raw[i0])) ++i0;
            const std::string_view trimmed = std::string_view(raw).substr(i0);
            if (starts_with(trimmed, "#reference") || starts_with(trimmed, "#include"))
                return make_error("RetroArch ignores an indented directive; start it in the first column", path, number,
                                  starts_with(trimmed, "#reference") ? "#reference" : "#include");
            if (starts_with(trimmed, "/*")) {
                if (raw.find("*/", i0 + 2) == std::string::npos) block_start = number;
                continue;
            }
            const std::string line = strip_comment(raw);
            size_t p = 0;
            while (p < line.size() && is_space(line[p])) ++p;
            if (p == line.size() || starts_with(std::string_view(line).substr(p), "//")) continue;

            const size_t key_begin = p;
            while (p < line.size() && is_graph(line[p])) ++p;
            const std::string key = line.substr(key_begin, p - key_begin);
            if (key.empty())
                return make_error("expected 'key = value' (keys are printable ASCII)", path, number);
            // Lines RetroArch's config reader drops: dropped here too, with a warning.
            if (const size_t eq = key.find('='); eq != std::string::npos) {
                warnings_.push_back(make_error("ignored: write blanks around '=': RetroArch reads '" + key +
                                                   "' as one key without a value and drops the line",
                                               path, number, key.substr(0, eq)));
                continue;
            }
            while (p < line.size() && is_space(line[p])) ++p;
            if (p == line.size() || line[p] != '=') {
                warnings_.push_back(make_error("ignored: expected 'key = value'; RetroArch drops this line", path, number, key));
                continue;
            }
            ++p;
            while (p < line.size() && is_space(line[p])) ++p;
            std::string value;
            if (p < line.size() && line[p] == '"') {
                size_t close = line.find('"', p + 1);
                if (close == std::string::npos) {
                    warnings_.push_back(make_error("the double quote is not closed; RetroArch reads to the end of the line",
                                                   path, number, key));
                    close = line.size();
                }
                value = line.substr(p + 1, close - p - 1);
                p = std::min(close + 1, line.size());
            } else {
                const size_t begin = p;
                while (p < line.size() && is_graph(line[p])) ++p;
                value = line.substr(begin, p - begin);
            }
            while (p < line.size() && is_space(line[p])) ++p;
            const std::string_view rest = std::string_view(line).substr(p);
            if (!rest.empty() && !starts_with(rest, "//") && !starts_with(rest, "#"))
                warnings_.push_back(make_error("ignored: the text after the value, '" + std::string(rest) +
                                                   "' (RetroArch ignores it too)",
                                               path, number, key));

            if (const Entry* first = out.find(key)) {
                warnings_.push_back(make_error("given again; RetroArch keeps the first value, at " + first->where.file + ":" +
                                                   std::to_string(first->where.line),
                                               path, number, key));
                continue;
            }
            out.index.emplace(key, out.entries.size());
            out.entries.push_back(Entry{key, value, here});
        }
        if (block_start) return make_error("the /* comment is not closed", path, block_start);
        include_stack.pop_back();
        return Ok{};
    }

    const detail::RootGuard& guard_;
    std::vector<Diagnostic>& warnings_;
    std::map<std::string, std::unique_ptr<PresetText>> cache_;
    std::vector<std::string> files_, file_ids_;
};

Result<std::optional<bool>> get_bool(const PresetText& file, const std::string& key) {
    const Entry* e = file.find(key);
    if (!e || e->value.empty()) return std::optional<bool>{};
    if (e->value == "true" || e->value == "1") return std::optional<bool>{true};
    if (e->value == "false" || e->value == "0") return std::optional<bool>{false};
    return make_error("'" + e->value + "' is not a boolean (true, false, 1 or 0)", e->where.file, e->where.line, key);
}

// strtoul(value, nullptr, 0) over the whole value: decimal, 0x hexadecimal or 0 octal.
std::optional<unsigned long> parse_unsigned(const std::string& value) {
    if (value.empty() || !std::isdigit(static_cast<unsigned char>(value[0]))) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const unsigned long v = std::strtoul(value.c_str(), &end, 0);
    if (errno != 0 || end != value.c_str() + value.size()) return std::nullopt;
    return v;
}

Result<std::optional<double>> get_number(const PresetText& file, const std::string& key) {
    const Entry* e = file.find(key);
    if (!e || e->value.empty()) return std::optional<double>{};
    const auto v = detail::parse_number(e->value);
    if (!v) return make_error("'" + e->value + "' is not a number", e->where.file, e->where.line, key);
    return std::optional<double>{*v};
}

template <size_t N>
Result<std::optional<std::string>> get_enum(const PresetText& file, const std::string& key, const char* const (&set)[N]) {
    const Entry* e = file.find(key);
    if (!e || e->value.empty()) return std::optional<std::string>{};
    if (!one_of(e->value, set))
        return make_error("'" + e->value + "' is not one of " + list_of(set), e->where.file, e->where.line, key);
    return std::optional<std::string>{e->value};
}

// A wrap mode: RetroArch replaces an unknown one by its default (clamp_to_border) with a warning.
std::optional<std::string> get_wrap_mode(const PresetText& file, const std::string& key, std::vector<Diagnostic>& warnings) {
    const Entry* e = file.find(key);
    if (!e || e->value.empty()) return std::nullopt;
    if (one_of(e->value, kWrapModes)) return e->value;
    warnings.push_back(make_error("'" + e->value + "' is not one of " + list_of(kWrapModes) +
                                      "; RetroArch uses its default, clamp_to_border",
                                  e->where.file, e->where.line, key));
    return std::nullopt;
}

// A file named by the preset (a shader or a texture): inside the root, an existing regular file.
Status check_named_file(const detail::RootGuard& guard, const std::string& resolved, const Entry& e, const std::string& what) {
    if (!guard.contains(resolved))
        return make_error("'" + resolved + "' is outside the root folder " + guard.root(), e.where.file, e.where.line, e.key);
    std::error_code ec;
    const auto status = std::filesystem::status(resolved, ec);
    if (ec || !std::filesystem::exists(status))
        return make_error(what + " '" + resolved + "' does not exist", e.where.file, e.where.line, e.key);
    if (!std::filesystem::is_regular_file(status))
        return make_error(what + " '" + resolved + "' is not a regular file", e.where.file, e.where.line, e.key);
    return Ok{};
}

}  // namespace

Result<SlangpPreset> load_slangp(const std::string& path, const std::string& root) {
    auto guard_result = detail::RootGuard::make(root);
    if (!guard_result.ok()) return guard_result.error();
    const detail::RootGuard& guard = guard_result.value();
    SlangpPreset out;
    out.path = path;
    Reader reader(guard, out.warnings);

    auto top_result = reader.read(path, SourceLocation{});
    if (!top_result.ok()) return top_result.error();
    const PresetText* top = top_result.value();

    // The preset holding the passes: each file's first #reference, to a file without any.
    auto find_root = [&](const PresetText* start) -> Result<const PresetText*> {
        std::vector<std::string> chain{detail::file_identity(start->path)};
        std::vector<std::string> names{start->path};
        const PresetText* current = start;
        while (!current->references.empty()) {
            const Reference& ref = current->references.front();
            const std::string identity = detail::file_identity(ref.path);
            if (std::find(chain.begin(), chain.end(), identity) != chain.end())
                return make_error("#reference cycle: " + join_list(names, " -> ") + " -> " + ref.path, ref.where.file,
                                  ref.where.line, "#reference");
            if (static_cast<int>(chain.size()) > kMaxReferenceDepth)
                return make_error(fmt::format("more than {} #reference steps to a preset without #reference",
                                              kMaxReferenceDepth),
                                  ref.where.file, ref.where.line, "#reference");
            auto next = reader.read(ref.path, ref.where);
            if (!next.ok()) return next.error();
            chain.push_back(identity);
            names.push_back(ref.path);
            current = next.value();
        }
        return current;
    };
    auto root_result = find_root(top);
    if (!root_result.ok()) return root_result.error();
    const PresetText& base = *root_result.value();
    const Entry* shaders = base.find("shaders");
    if (!shaders)
        return make_error(base.path == top->path ? std::string("the preset has no 'shaders' entry")
                                                 : "the preset that " + top->path +
                                                       " refers to (by each file's first #reference) has no 'shaders' entry",
                          base.path, 0, "shaders");
    for (size_t k = 1; k < top->references.size(); ++k) {
        const Reference& ref = top->references[k];
        auto referenced = reader.read(ref.path, ref.where);
        if (!referenced.ok()) return referenced.error();
        auto sub_root = find_root(referenced.value());
        if (!sub_root.ok()) return sub_root.error();
        if (sub_root.value()->find("shaders"))
            return make_error("only the first #reference may lead to a preset with passes; '" + sub_root.value()->path +
                                  "' has 'shaders' (RetroArch refuses this too: further references carry parameter "
                                  "values and texture paths only)",
                              ref.where.file, ref.where.line, "#reference");
    }

    // Passes.
    const auto count = parse_unsigned(shaders->value);
    if (!count || *count < 1 || *count > static_cast<unsigned long>(kMaxShaderPasses))
        return make_error(fmt::format("'{}' is not a number of passes from 1 to {}", shaders->value, kMaxShaderPasses),
                          shaders->where.file, shaders->where.line, "shaders");
    const int passes = static_cast<int>(*count);
    for (int n = 0; n < passes; ++n) {
        const std::string num = std::to_string(n);
        SlangpPass pass;
        for (const Entry& e : base.entries) {
            const auto split = split_pass_key(e.key);
            if (split && split->second == n && e.key == split->first + num) pass.key_lines[split->first] = e.where;
        }
        const Entry* shader = base.find("shader" + num);
        if (!shader || shader->value.empty())
            return make_error(fmt::format("pass {} has no shader (shaders = {}, so shader0 to shader{} are needed)", n, passes,
                                          passes - 1),
                              shader ? shader->where.file : shaders->where.file, shader ? shader->where.line : shaders->where.line,
                              "shader" + num);
        // RetroArch resolves a pass's path against the preset file it reads the passes from.
        pass.shader = detail::resolve_relative(base.path, shader->value);
        if (auto st = check_named_file(guard, pass.shader, *shader, "shader"); !st.ok()) return st.error();
        pass.where = shader->where;
        if (const Entry* alias = base.find("alias" + num)) {
            // It becomes an identifier in every target and part of file names: refused here, at
            // its line, not in the crtforge preset the import would write.
            if (alias->value.size() > crtforge::detail::kMaxIdentifierLength)
                return make_error(crtforge::detail::not_identifier(alias->value), alias->where.file, alias->where.line, "alias" + num);
            pass.alias = alias->value;
        }
        std::pair<std::optional<bool>*, const char*> bools[] = {{&pass.filter_linear, "filter_linear"},
                                                                 {&pass.mipmap_input, "mipmap_input"},
                                                                 {&pass.float_framebuffer, "float_framebuffer"},
                                                                 {&pass.srgb_framebuffer, "srgb_framebuffer"}};
        for (auto& [target, key] : bools) {
            auto v = get_bool(base, key + num);
            if (!v.ok()) return v.error();
            *target = v.value();
        }
        pass.wrap_mode = get_wrap_mode(base, "wrap_mode" + num, out.warnings);
        if (const Entry* e = base.find("frame_count_mod" + num); e && !e->value.empty()) {
            const auto v = parse_unsigned(e->value);
            if (!v || *v > static_cast<unsigned long>(INT_MAX))
                return make_error("'" + e->value + "' is not a whole number of frames", e->where.file, e->where.line, e->key);
            pass.frame_count_mod = static_cast<int>(*v);
        }
        std::pair<std::optional<std::string>*, const char*> types[] = {
            {&pass.scale_type, "scale_type"}, {&pass.scale_type_x, "scale_type_x"}, {&pass.scale_type_y, "scale_type_y"}};
        for (auto& [target, key] : types) {
            auto v = get_enum(base, key + num, kScaleTypes);
            if (!v.ok()) return v.error();
            *target = v.value();
        }
        std::pair<std::optional<double>*, const char*> scales[] = {
            {&pass.scale, "scale"}, {&pass.scale_x, "scale_x"}, {&pass.scale_y, "scale_y"}};
        for (auto& [target, key] : scales) {
            auto v = get_number(base, key + num);
            if (!v.ok()) return v.error();
            *target = v.value();
        }
        out.passes.push_back(std::move(pass));
    }
    for (const Entry& e : base.entries)
        if (const auto split = split_pass_key(e.key); split && split->second >= passes)
            out.warnings.push_back(make_error(fmt::format("ignored: the preset has {} pass{}", passes, passes == 1 ? "" : "es"),
                                              e.where.file, e.where.line, e.key));

    // Textures.
    if (const Entry* list = base.find("textures")) {
        std::set<std::string> seen;
        size_t start = 0;
        while (start <= list->value.size()) {
            size_t end = list->value.find(';', start);
            if (end == std::string::npos) end = list->value.size();
            const std::string name = list->value.substr(start, end - start);
            start = end + 1;
            if (name.empty()) continue;
            auto fail = [&](const std::string& message) {
                return make_error(message, list->where.file, list->where.line, "textures");
            };
            if (std::any_of(name.begin(), name.end(), [](char c) { return is_space(c); }))
                return fail("texture name '" + name + "' has blanks (RetroArch looks the name up as written)");
            if (name.size() > kMaxTextureName)
                return fail(fmt::format("texture name '{}' is longer than {} bytes", name, kMaxTextureName));
            if (!seen.insert(name).second) return fail("texture '" + name + "' is listed twice");
            if (static_cast<int>(out.textures.size()) == kMaxTextures)
                return fail(fmt::format("more than {} textures", kMaxTextures));
            const Entry* file = base.find(name);
            if (!file || file->value.empty()) return fail("texture '" + name + "' has no '" + name + " = path' entry");
            SlangpTexture texture;
            texture.name = name;
            texture.path = detail::resolve_relative(base.path, file->value);
            if (auto st = check_named_file(guard, texture.path, *file, "texture"); !st.ok()) return st.error();
            texture.where = file->where;
            auto linear = get_bool(base, name + "_linear");
            if (!linear.ok()) return linear.error();
            texture.linear = linear.value();
            auto mipmap = get_bool(base, name + "_mipmap");
            if (!mipmap.ok()) return mipmap.error();
            texture.mipmap = mipmap.value();
            texture.wrap_mode = get_wrap_mode(base, name + "_wrap_mode", out.warnings);
            out.textures.push_back(std::move(texture));
        }
    }
    auto texture_setting = [&](const std::string& key) {
        for (const SlangpTexture& t : out.textures)
            for (const char* suffix : kTextureSuffixes)
                if (key == t.name + suffix) return true;
        return false;
    };

    // Overrides: every file of the reference graph, its references (in order) before itself.
    std::vector<const PresetText*> order;
    std::vector<std::string> stack;
    std::function<Status(const PresetText*, int)> gather = [&](const PresetText* file, int depth) -> Status {
        stack.push_back(detail::file_identity(file->path));
        for (const Reference& ref : file->references) {
            if (std::find(stack.begin(), stack.end(), detail::file_identity(ref.path)) != stack.end())
                return make_error("#reference cycle: '" + ref.path + "' refers back to this file", ref.where.file,
                                  ref.where.line, "#reference");
            if (depth + 1 > kMaxReferenceDepth)
                return make_error(fmt::format("#reference is nested more than {} deep", kMaxReferenceDepth), ref.where.file,
                                  ref.where.line, "#reference");
            auto next = reader.read(ref.path, ref.where);
            if (!next.ok()) return next.error();
            if (auto st = gather(next.value(), depth + 1); !st.ok()) return st;
        }
        stack.pop_back();
        order.push_back(file);
        return Ok{};
    };
    if (auto st = gather(top, 0); !st.ok()) return st.error();

    std::map<std::string, size_t> parameter_index;
    std::set<const PresetText*> warned;
    for (const PresetText* file : order) {
        const bool is_base = file == &base;
        for (const Entry& e : file->entries) {
            const auto texture = std::find_if(out.textures.begin(), out.textures.end(),
                                              [&](const SlangpTexture& t) { return t.name == e.key; });
            if (texture != out.textures.end()) {
                if (!is_base && !e.value.empty()) {  // a texture path override
                    const std::string resolved = detail::resolve_relative(file->path, e.value);
                    if (auto st = check_named_file(guard, resolved, e, "texture"); !st.ok()) return st.error();
                    texture->path = resolved;
                    texture->where = e.where;
                }
                continue;
            }
            if (is_preset_key(e.key) || texture_setting(e.key)) {
                if (!is_base && e.key != "parameters" && warned.insert(file).second)
                    out.warnings.push_back(make_error("ignored, as every pass and texture setting of a preset with a "
                                                      "#reference is: RetroArch takes them from " + base.path,
                                                      e.where.file, e.where.line, e.key));
                continue;
            }
            if (e.value.empty()) {
                out.empty_values[e.key] = e.where;
                continue;
            }
            size_t consumed = 0;
            const double value = detail::parse_number_prefix(e.value, consumed);
            // Not a number: not a parameter value. A whole value that is a number but not a finite one
            // (inf, nan, 1e999) is kept: the importer refuses it where the key names a shader
            // parameter. (A word that only starts like one, `alias1 = "InfoCachePass"`, is a word.)
            if (consumed == 0 || (!std::isfinite(value) && consumed != e.value.size())) continue;
            if (consumed != e.value.size())
                out.warnings.push_back(make_error(fmt::format("'{}' is not a number; RetroArch would read {} if '{}' is a "
                                                              "shader parameter",
                                                              e.value, value, e.key),
                                                  e.where.file, e.where.line, e.key));
            if (const auto it = parameter_index.find(e.key); it != parameter_index.end()) {
                out.parameters[it->second].second = value;
            } else {
                parameter_index.emplace(e.key, out.parameters.size());
                out.parameters.emplace_back(e.key, value);
            }
            out.parameter_lines[e.key] = e.where;
        }
    }
    out.files = reader.files();
    return out;
}

}  // namespace crtforge::retroarch
