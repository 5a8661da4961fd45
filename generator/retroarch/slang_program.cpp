#include "generator/retroarch/slang_program.hpp"

#include "crtforge/spirv_compiler.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <regex>
#include <set>

#include <fmt/format.h>

#include "generator/retroarch/glsl_tokens.hpp"

namespace crtforge::retroarch {

namespace {

using Kind = GlslToken::Kind;
using Tokens = std::vector<GlslToken>;

// What the rewrite adds in front of each stage: the defines RetroArch 1.20 sets for the uniforms it
// provides (crtforge provides them too), and the size of a texture as RetroArch's vec4.
constexpr const char* kPrologue =
    "#define _HAS_ORIGINALASPECT_UNIFORMS\n"
    "#define _HAS_FRAMETIME_UNIFORMS\n"
    // A function, not a macro: a size is read where the shader reads it, and a shader may have a
    // local named `textureSize` there (yee64); the builtin is seen from here.
    "vec4 CRT_RA_SIZE(sampler2D t) { vec2 size = vec2(textureSize(t, 0)); return vec4(size, 1.0 / size); }\n";
constexpr const char* kShaderMain = "crt_retroarch_main";
// The quad corner (0..1 inside RetroArch's quad) a vertex stage that moves its quad hands on.
constexpr const char* kCornerVarying = "crtQuadCorner";
// RetroArch's MVP for every pass: the orthographic projection of 0..1 onto clip space (y down in
// Vulkan, as crtforge's full-screen triangle).
constexpr const char* kMvp = "mat4(2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, -1.0, 0.0, 1.0)";

struct Member {
    std::string type, name;
    std::string array;  // "[4]" or ""
};

struct Block {
    std::string instance;  // "" when the members are read bare
    std::vector<Member> members;
    size_t start = 0, end = 0;  // its tokens (an instance block's become a struct and a global)
};

struct Declarations {
    std::vector<Block> blocks;
    std::vector<std::pair<std::string, size_t>> samplers;  // name, its declaration's first token
    std::vector<Member> vertex_inputs;  // by location: [0] position, [1] texture coordinate
    std::string fragment_output;        // the vec4 at location 0
};

bool is(const Tokens& t, size_t i, const char* text) { return i < t.size() && t[i].text == text; }

// The line breaks of tokens [from, to].
std::string line_breaks(const Tokens& t, size_t from, size_t to) {
    std::string lines;
    for (size_t i = from; i <= to && i < t.size(); ++i)
        for (char c : t[i].text)
            if (c == '\n') lines += '\n';
    return lines;
}

// Replaces tokens [from, to] by their line breaks alone, so every later line keeps its number.
void blank(Tokens& t, size_t from, size_t to) {
    const std::string lines = line_breaks(t, from, to);
    t[from] = {Kind::Space, lines.empty() ? " " : lines};
    for (size_t i = from + 1; i <= to && i < t.size(); ++i) t[i] = {Kind::Space, ""};
}

// The index just past a balanced (...) starting at `open`, or npos.
size_t skip_parens(const Tokens& t, size_t open) {
    int depth = 0;
    for (size_t i = open; i < t.size(); ++i) {
        if (t[i].text == "(") ++depth;
        if (t[i].text == ")" && --depth == 0) return i;
    }
    return std::string::npos;
}

// An error at token `i`: its file and line, read through the stage text's #line directives (the
// line numbers count from the .slang or include the token came from).
Diagnostic error_at(const Tokens& t, size_t i, std::string file, const std::string& field, const std::string& message) {
    static const std::regex directive(R"re(^\s*#\s*line\s+(\d+)(?:\s+"([^"]*)")?)re");
    std::string before;
    for (size_t k = 0; k < i && k < t.size(); ++k) before += t[k].text;
    int line = 1;
    size_t start = 0;
    for (size_t end = before.find('\n'); end != std::string::npos; start = end + 1, end = before.find('\n', start)) {
        std::smatch m;
        const std::string text = before.substr(start, end - start);
        if (std::regex_search(text, m, directive)) {
            line = std::stoi(m[1]);
            if (m[2].matched) file = m[2];
        } else {
            ++line;
        }
    }
    return make_error(message, file, line, field);
}

// `i`, or past the precision qualifiers that start there.
size_t past_precision(const Tokens& t, size_t i) {
    while (i < t.size() && (t[i].text == "highp" || t[i].text == "mediump" || t[i].text == "lowp")) i = next_significant(t, i);
    return i;
}

// Member declarations between `{` at `open` and its `}`: "[layout(...)] [precision] type name[, name];".
Result<std::vector<Member>> parse_members(const Tokens& t, size_t open, size_t& close, const std::string& file) {
    std::vector<Member> out;
    size_t i = next_significant(t, open);
    while (i < t.size() && t[i].text != "}") {
        if (t[i].text == "layout") {
            const size_t end = skip_parens(t, next_significant(t, i));
            if (end == std::string::npos) return error_at(t, i, file, "uniform block", "unbalanced layout( in a uniform block");
            i = next_significant(t, end);
        }
        i = past_precision(t, i);
        if (i >= t.size() || t[i].kind != Kind::Identifier) return error_at(t, i, file, "uniform block", "a uniform block member without a type");
        const std::string type = t[i].text;
        i = next_significant(t, i);
        while (true) {
            if (i >= t.size() || t[i].kind != Kind::Identifier)
                return error_at(t, i, file, "uniform block", "a uniform block member without a name");
            Member m{type, t[i].text, ""};
            i = next_significant(t, i);
            while (is(t, i, "[")) {
                for (; i < t.size() && t[i].text != "]"; ++i) m.array += t[i].text;
                m.array += "]";
                i = next_significant(t, i);
            }
            out.push_back(m);
            if (is(t, i, ",")) { i = next_significant(t, i); continue; }
            if (is(t, i, ";")) { i = next_significant(t, i); break; }
            return error_at(t, i, file, "uniform block", "could not read the uniform block member '" + m.name + "'");
        }
    }
    if (i >= t.size()) return error_at(t, open, file, "uniform block", "a uniform block without its closing }");
    close = i;
    return out;
}

// The location a layout(...) qualifier names, if any.
std::optional<int> location_of(const std::string& layout) {
    static const std::regex location(R"(location\s*=\s*(\d+))");
    std::smatch m;
    if (!std::regex_search(layout, m, location)) return std::nullopt;
    return std::stoi(m[1]);
}

// Finds and removes the uniform blocks, the sampler declarations and (vertex) the vertex inputs.
Result<Declarations> take_declarations(Tokens& t, bool vertex, const std::string& file) {
    Declarations out;
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].text != "layout" && t[i].text != "uniform") continue;
        size_t start = i, at = i;
        std::string layout;
        if (t[at].text == "layout") {
            const size_t open = next_significant(t, at);
            if (!is(t, open, "(")) continue;
            const size_t close = skip_parens(t, open);
            if (close == std::string::npos) continue;
            for (size_t k = open; k <= close; ++k) layout += t[k].text;
            at = next_significant(t, close);
        }
        if (is(t, at, "uniform")) {
            const size_t type = past_precision(t, next_significant(t, at));
            if (type >= t.size() || t[type].kind != Kind::Identifier) continue;
            const size_t after = next_significant(t, type);
            if (is(t, after, "{")) {  // a block: uniform Name { members } [instance];
                size_t close = 0;
                auto members = parse_members(t, after, close, file);
                if (!members.ok()) return members.error();
                size_t end = next_significant(t, close);
                Block block;
                if (end < t.size() && t[end].kind == Kind::Identifier) {
                    block.instance = t[end].text;
                    end = next_significant(t, end);
                }
                if (!is(t, end, ";")) return error_at(t, start, file, "uniform block", "a uniform block without its closing ;");
                block.members = std::move(members.value());
                block.start = start;
                block.end = end;
                out.blocks.push_back(std::move(block));
                blank(t, start, end);
                i = end;
                continue;
            }
            const std::string& sampler_type = t[type].text;
            const bool sampler = sampler_type.rfind("sampler", 0) == 0 || sampler_type.rfind("usampler", 0) == 0 ||
                                 sampler_type.rfind("isampler", 0) == 0;
            if (sampler && after < t.size() && t[after].kind == Kind::Identifier) {
                const size_t end = next_significant(t, after);
                if (!is(t, end, ";"))
                    return error_at(t, start, file, "uniform", "sampler '" + t[after].text + "': only single sampler declarations are read");
                if (sampler_type[0] != 's')  // test/format.slangp's reader of an R32_UINT pass
                    return error_at(t, start, file, "uniform", "sampler '" + t[after].text + "' is a " + sampler_type +
                                                                   ": integer textures (the passes of an integer format such as R32_UINT) "
                                                                   "are not supported; crtforge's passes hold float or normalised colours");
                if (sampler_type != "sampler2D")
                    return error_at(t, start, file, "uniform", "sampler '" + t[after].text + "' is a " + sampler_type +
                                                                   "; RetroArch passes bind sampler2D");
                out.samplers.push_back({t[after].text, start});
                blank(t, start, end);
                i = end;
            }
            continue;
        }
        const std::optional<int> location = location_of(layout);
        if (!vertex && is(t, at, "out") && location == 0) {
            const size_t type = past_precision(t, next_significant(t, at)), name = next_significant(t, type);
            if (is(t, type, "vec4") && name < t.size() && t[name].kind == Kind::Identifier) out.fragment_output = t[name].text;
            if (type < t.size() && (t[type].text.rfind("uint", 0) == 0 || t[type].text.rfind("uvec", 0) == 0 ||
                                    t[type].text.rfind("int", 0) == 0 || t[type].text.rfind("ivec", 0) == 0))
                return error_at(t, start, file, "fragment output",
                                "the fragment stage writes a " + t[type].text + " at location 0: integer framebuffers (R32_UINT and "
                                "the like) are not supported; crtforge's passes hold float or normalised colours");
            continue;
        }
        if (vertex && is(t, at, "in") && location) {
            const int index = *location;
            const size_t type = past_precision(t, next_significant(t, at)), name = next_significant(t, type), end = next_significant(t, name);
            if (name >= t.size() || t[name].kind != Kind::Identifier || !is(t, end, ";")) continue;
            if (index > 1)
                return error_at(t, start, file, "vertex input",
                                fmt::format("vertex input '{}' at location {}: RetroArch passes have a position (0) and a "
                                            "texture coordinate (1) only",
                                            t[name].text, index));
            if (out.vertex_inputs.size() < 2) out.vertex_inputs.resize(2);
            out.vertex_inputs[static_cast<size_t>(index)] = {t[type].text, t[name].text, ""};
            // The input becomes a global the generated main() sets.
            const std::string lines = line_breaks(t, start, end);
            const Member& input = out.vertex_inputs[static_cast<size_t>(index)];
            blank(t, start, end);
            t[start] = {Kind::Identifier, input.type + " " + input.name + ";" + lines};
            i = end;
        }
    }
    return out;
}

// The zero of a GLSL type (and array).
std::string zero_of(const Member& m) {
    const std::string scalar = m.type == "bool" ? "false" : m.type + "(0)";
    if (m.array.empty()) return scalar;
    const int n = std::max(1, std::atoi(m.array.c_str() + 1));
    std::string items;
    for (int k = 0; k < n; ++k) items += (k ? ", " : "") + scalar;
    return m.type + m.array + "(" + items + ")";
}

// A vec4 value as the member's type wants it.
std::string as_type(const Member& m, const std::string& vec4) { return m.type == "vec4" ? vec4 : m.type + "(" + vec4 + ")"; }

struct Translation {
    const ProgramContext& context;
    TranslatedProgram& out;
    // Set by the vertex stage where its clip position is not RetroArch's quad as it is
    // (moves_quad()): the fragment stage then drops what the full-screen triangle covers beyond
    // the quad, told by the corner handed on at `corner_location`.
    bool quad_moved = false;
    int corner_location = 0;

    void use_texture(const std::string& name) {
        if (std::find(out.textures.begin(), out.textures.end(), name) == out.textures.end()) out.textures.push_back(name);
    }
    void use_param(const std::string& id) {
        if (std::find(out.params.begin(), out.params.end(), id) == out.params.end()) out.params.push_back(id);
    }

    // What a block member reads, as an expression.
    std::string expression(const Member& m) {
        if (!m.array.empty()) return zero_of(m);
        if (auto p = context.params.find(m.name); p != context.params.end()) {
            use_param(m.name);
            return m.type == "float" ? p->second : m.type + "(" + p->second + ")";
        }
        // Sizes crtforge's builtins hold: vec4(size, 1 / size).
        static const std::map<std::string, Builtin> sizes = {
            {"SourceSize", Builtin::SourceSize}, {"OutputSize", Builtin::OutputSize}, {"FinalViewportSize", Builtin::ViewportSize}};
        if (auto size = sizes.find(m.name); size != sizes.end()) {
            out.builtins.insert(size->second);
            const std::string name = builtin_name(size->second);
            return as_type(m, "vec4(" + name + ", 1.0 / " + name + ")");
        }
        if (m.name == "MVP") return kMvp;
        if (m.name == "FrameCount") { out.builtins.insert(Builtin::FrameCount); return m.type + "(frameCount)"; }
        if (m.name == "FrameDirection" || m.name == "CurrentSubFrame" || m.name == "TotalSubFrames") return m.type + "(1)";
        if (m.name == "Rotation") return m.type + "(0)";
        if (m.name == "OriginalFPS") return m.type + "(" + fmt::format("{:.6f}", context.fps) + ")";
        if (m.name == "FrameTimeDelta") return m.type + "(" + fmt::format("{}", static_cast<long>(1e6 / context.fps + 0.5)) + ")";
        if ((m.name == "OriginalAspect" || m.name == "OriginalAspectRotated") && context.textures.count("Original")) {
            use_texture("Original");
            return m.type + "(CRT_RA_SIZE(Original).x / CRT_RA_SIZE(Original).y)";
        }
        // <texture>Size#: the size of that texture, which the pass then binds.
        static const std::regex size_of("^(.*)Size([0-9]*)$");
        std::smatch match;
        if (std::regex_match(m.name, match, size_of))
            if (const std::string texture = match[1].str() + match[2].str(); context.textures.count(texture)) {
                use_texture(texture);
                return as_type(m, "CRT_RA_SIZE(" + texture + ")");
            }
        return zero_of(m);  // neither a semantic nor a parameter: RetroArch leaves it unset
    }
};

// The tokens that name a layout qualifier (`location`, `binding`, `std140` in `layout(std140,
// binding = 0)`): words of the language there, not names of the shader's, whatever a parameter
// or a rename is called. A qualifier's value (`location = N`) is an expression and not one.
std::vector<bool> layout_qualifier_names(const Tokens& t) {
    std::vector<bool> out(t.size(), false);
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].kind != Kind::Identifier || t[i].text != "layout") continue;
        size_t k = next_significant(t, i);
        if (k >= t.size() || t[k].text != "(") continue;
        int depth = 0;
        std::string before;  // the last significant token at the qualifier list's own depth
        for (; k < t.size(); ++k) {
            const GlslToken& token = t[k];
            if (token.kind == Kind::Space) continue;
            if (token.text == "(") ++depth;
            if (token.text == ")" && --depth == 0) break;
            if (depth == 1 && token.kind == Kind::Identifier && (before == "(" || before == ",")) out[k] = true;
            if (depth == 1 || token.text == "(") before = token.text;
        }
        i = k;
    }
    return out;
}

// Every identifier of the text but a layout qualifier's name, to make names that are not yet taken.
std::set<std::string> identifiers(const Tokens& t, const std::vector<bool>& qualifier_names) {
    std::set<std::string> out;
    for (size_t i = 0; i < t.size(); ++i)
        if (t[i].kind == Kind::Identifier && !qualifier_names[i]) out.insert(t[i].text);
    return out;
}

// Whether a vertex stage places its quad anywhere but where RetroArch's MVP puts it: any write of
// gl_Position other than `gl_Position = [global. | params.]MVP * <position input>;` (newpixie-mini
// turns it over, the handheld mega-* shrink it). Only then does the import's full-screen triangle,
// which covers more than the quad, need its excess dropped.
bool moves_quad(const Tokens& t, const std::string& position) {
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].kind != Kind::Identifier || t[i].text != "gl_Position") continue;
        std::string statement;
        for (size_t k = next_significant(t, i); k < t.size() && t[k].text != ";"; k = next_significant(t, k))
            if (t[k].text != "(" && t[k].text != ")") statement += t[k].text;
        if (statement != "=global.MVP*" + position && statement != "=params.MVP*" + position && statement != "=MVP*" + position)
            return true;
    }
    return false;
}

// The product of the `[N]` dimensions starting at `at` (one not a literal counts 1) and the index
// of the token after them.
std::pair<int, size_t> array_dimensions(const Tokens& t, size_t at) {
    int count = 1;
    while (at < t.size() && t[at].text == "[") {
        const size_t n = next_significant(t, at);
        if (n < t.size() && t[n].kind == Kind::Number && t[n].text.size() < 4) count *= std::stoi(t[n].text);
        at = next_significant(t, next_significant(t, n));
    }
    return {count, at};
}

// How many locations a declaration's type takes: a matrix one per column (a double one two for
// a column of 3 or 4), a dvec3/dvec4 two, a struct its members', anything else one.
int locations_of_type(const Tokens& t, const std::string& type, int depth = 0) {
    const bool dmat = type.rfind("dmat", 0) == 0;
    const std::string tail = dmat || type.rfind("mat", 0) == 0 ? type.substr(dmat ? 4 : 3) : std::string();  // "3", "4x3"
    if (!tail.empty() && std::isdigit(static_cast<unsigned char>(tail[0]))) {
        const int columns = tail[0] - '0';
        const int rows = tail.size() == 3 && tail[1] == 'x' ? tail[2] - '0' : columns;
        return columns * (dmat && rows > 2 ? 2 : 1);
    }
    if (type == "dvec3" || type == "dvec4") return 2;
    if (depth > 8) return 1;
    // A struct: its definition's members, each with its own arrays.
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].text != "struct") continue;
        const size_t name = next_significant(t, i);
        const size_t open = name < t.size() && t[name].text == type ? next_significant(t, name) : t.size();
        if (open >= t.size() || t[open].text != "{") continue;
        int total = 0;
        for (size_t k = next_significant(t, open); k < t.size() && t[k].text != "}";) {
            const size_t member = next_significant(t, k);
            auto [count, after] = array_dimensions(t, member < t.size() ? next_significant(t, member) : t.size());
            total += locations_of_type(t, t[k].text, depth + 1) * count;
            while (after < t.size() && t[after].text != ";" && t[after].text != "}") after = next_significant(t, after);
            k = after < t.size() && t[after].text == ";" ? next_significant(t, after) : after;
        }
        return std::max(total, 1);
    }
    return 1;
}

// The location after the highest a stage's inputs and outputs take: `location = N` and what the
// declaration after the layout spans (a matrix, an array, a struct there take several).
int next_free_location(const Tokens& t) {
    static const std::set<std::string> qualifiers{"in", "out", "flat", "smooth", "noperspective", "centroid", "sample", "patch", "highp",
                                                  "mediump", "lowp", "invariant", "precise"};
    int next = 0;
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].kind != Kind::Identifier || t[i].text != "location") continue;
        const size_t eq = next_significant(t, i);
        const size_t number = eq < t.size() && t[eq].text == "=" ? next_significant(t, eq) : t.size();
        if (number >= t.size() || t[number].kind != Kind::Number || t[number].text.size() >= 4) continue;
        size_t k = number;
        int depth = 1;  // inside the layout's parentheses
        while (depth > 0 && (k = next_significant(t, k)) < t.size()) depth += t[k].text == "(" ? 1 : t[k].text == ")" ? -1 : 0;
        k = next_significant(t, k);
        while (k < t.size() && qualifiers.count(t[k].text)) k = next_significant(t, k);
        const int type_span = k < t.size() && t[k].kind == Kind::Identifier ? locations_of_type(t, t[k].text) : 1;
        const int count = array_dimensions(t, k < t.size() ? next_significant(t, next_significant(t, k)) : t.size()).first;  // past the name
        next = std::max(next, std::stoi(t[number].text) + std::max(type_span * count, 1));
    }
    return next;
}

Result<std::string> translate_stage(const std::string& source, bool vertex, const std::string& file, Translation& tr) {
    // What RetroArch's compiler sees: macros expanded and only the active #if branches, so a
    // declaration a macro names or an #ifdef leaves out reads as it does there.
    auto preprocessed = preprocess_vulkan_glsl(source, vertex ? ShaderStage::Vertex : ShaderStage::Fragment, file);
    if (!preprocessed.ok()) return preprocessed.error();
    Tokens t = tokenize_glsl(preprocessed.value());
    // What directives are left (#version, #extension, #line, #pragma) become space, so the
    // declarations read as code: the #version and line-directive extension lines go (the
    // assembler writes its own), the others stay as written.
    // One pass into a new list: erasing each directive's tokens in place moved the whole tail once
    // per directive (koko-aio's passes have thousands of #line directives after preprocessing).
    Tokens kept;
    kept.reserve(t.size());
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i].text != "#") {
            kept.push_back(std::move(t[i]));
            continue;
        }
        const size_t word = next_significant(t, i);
        size_t end = i;
        while (end + 1 < t.size() && t[end + 1].text.find('\n') == std::string::npos) ++end;
        const bool drop = is(t, word, "version") ||
                          (is(t, word, "extension") && is(t, next_significant(t, word), "GL_GOOGLE_cpp_style_line_directive"));
        if (drop) {
            blank(t, i, end);
            for (size_t k = i; k <= end; ++k) kept.push_back(std::move(t[k]));
        } else {
            std::string line;
            for (size_t k = i; k <= end; ++k) line += t[k].text;
            kept.push_back({Kind::Space, std::move(line)});
        }
        i = end;
    }
    t = std::move(kept);
    const int free_location = next_free_location(t);
    auto declared = take_declarations(t, vertex, file);
    if (!declared.ok()) return declared.error();
    const Declarations& d = declared.value();
    if (vertex && (d.vertex_inputs.size() < 2 || d.vertex_inputs[0].name.empty() || d.vertex_inputs[1].name.empty()))
        return make_error("the vertex stage must declare inputs at locations 0 (position) and 1 (texture coordinate)", file, 0,
                          "vertex input");
    if (vertex) {
        tr.quad_moved = moves_quad(t, d.vertex_inputs[0].name);
        tr.corner_location = free_location;
    }
    for (const auto& [s, at] : d.samplers) {
        if (s == "Source") continue;
        if (!tr.context.textures.count(s))
            return error_at(t, at, file, "sampler " + s,
                            "sampler '" + s + "' names no texture of the preset (not Original, OriginalHistory#, PassOutput#, "
                            "PassFeedback#, a pass alias or its Feedback, or a LUT)");
        tr.use_texture(s);
    }

    std::map<std::string, const Member*> bare_member;
    for (const Block& b : d.blocks)
        for (const Member& m : b.members)
            if (b.instance.empty()) bare_member[m.name] = &m;

    // Names the rewrite brings in; where the shader has them already, its own get another name.
    const std::vector<bool> qualifier_names = layout_qualifier_names(t);
    const std::set<std::string> taken = identifiers(t, qualifier_names);
    std::set<std::string> introduced = {"source", "sourceSize", "outputSize", "viewportSize", "frameCount", "time", "CrtParams",
                                        "CRT_RA_SIZE", kShaderMain, "crtCorner"};
    for (const Block& b : d.blocks)
        for (const Member& m : b.members)
            if (auto p = tr.context.params.find(m.name); p != tr.context.params.end()) introduced.insert(p->second);
    std::map<std::string, std::string> renamed;
    for (const std::string& name : introduced) {
        if (!taken.count(name) || bare_member.count(name)) continue;
        std::string fresh = name + "_ra";
        for (int n = 2; taken.count(fresh); ++n) fresh = name + "_ra" + std::to_string(n);
        renamed[name] = fresh;
    }
    auto renamed_name = [&](const std::string& name) {
        auto r = renamed.find(name);
        return r == renamed.end() ? name : r->second;
    };
    // An instance block's reads, `params.X` (also where a macro built them), become what crtforge
    // provides for X, in place: a module then holds only the values its code reads, so passes
    // that two presets share with the same values read compile to the same module. A shader
    // that uses the instance otherwise (passes it whole, declares the name again) gets a struct
    // and a global of it, initialised with every member.
    std::map<size_t, std::string> inlined;  // the instance token's index -> the member's value
    std::set<size_t> member_tokens;        // the `.` and member tokens that go with it
    for (const Block& b : d.blocks) {
        if (b.instance.empty()) continue;
        std::map<std::string, std::string> value_of;
        for (const Member& m : b.members) value_of[m.name] = tr.expression(m);  // every member: its param and texture are the pass's
        std::map<size_t, std::string> reads;
        std::set<size_t> read_tokens;
        bool only_member_reads = true;
        for (size_t i = 0; i < t.size() && only_member_reads; ++i) {
            if (t[i].kind != Kind::Identifier || t[i].text != b.instance) continue;
            const long before = previous_significant(t, i);
            if (before >= 0 && t[static_cast<size_t>(before)].text == ".") continue;  // another struct's field of that name
            const size_t dot = next_significant(t, i);
            const size_t member = dot < t.size() ? next_significant(t, dot) : t.size();
            if (member >= t.size() || t[dot].text != "." || !value_of.count(t[member].text)) {
                only_member_reads = false;
                break;
            }
            reads[i] = "(" + value_of.at(t[member].text) + ")";
            for (size_t k = i + 1; k <= member; ++k) read_tokens.insert(k);
        }
        if (only_member_reads) {
            inlined.insert(reads.begin(), reads.end());
            member_tokens.insert(read_tokens.begin(), read_tokens.end());
            continue;
        }
        std::string type = "CrtRetroArch_" + b.instance, fields, values;
        while (taken.count(type)) type += "_";
        for (const Member& m : b.members) {
            fields += fmt::format(" {} {}{};", m.type, m.name, m.array);  // a field keeps its name: no rename reaches past a dot
            values += (values.empty() ? "" : ", ") + value_of.at(m.name);
        }
        t[b.start] = {Kind::Identifier, fmt::format("struct {0} {{{1} }}; {0} {2} = {0}({3});{4}", type, fields,
                                                    renamed_name(b.instance), values, line_breaks(t, b.start, b.start))};
    }

    const bool reads_frag_coord =
        !vertex && std::any_of(t.begin(), t.end(), [](const GlslToken& k) { return k.kind == Kind::Identifier && k.text == "gl_FragCoord"; });
    const bool own_main = vertex || tr.context.opaque_output || tr.quad_moved || reads_frag_coord;  // the import's main() calls it
    Tokens out;
    for (size_t i = 0; i < t.size(); ++i) {
        GlslToken token = t[i];
        if (auto read = inlined.find(i); read != inlined.end()) {
            out.push_back({Kind::Identifier, read->second});
            continue;
        }
        if (member_tokens.count(i)) {
            if (token.kind == Kind::Space) out.push_back(token);  // line breaks keep the lines where they were
            continue;
        }
        if (token.kind != Kind::Identifier || qualifier_names[i]) { out.push_back(token); continue; }
        const long before = previous_significant(t, i);
        const bool after_dot = before >= 0 && t[static_cast<size_t>(before)].text == ".";
        if (!after_dot && bare_member.count(token.text)) {
            out.push_back({Kind::Identifier, "(" + tr.expression(*bare_member.at(token.text)) + ")"});
            continue;
        }
        if (!after_dot && token.text == "Source") token.text = "source";
        else if (auto r = renamed.find(token.text); r != renamed.end() && !after_dot) token.text = r->second;
        else if (own_main && !after_dot && token.text == "main") token.text = kShaderMain;
        out.push_back(token);
    }
    std::string result = kPrologue + join_tokens(out);
    // The stage's own main() renamed, and the import's main() around it.
    std::string before, after;
    if (!vertex && tr.quad_moved) {
        // The triangle's pixels beyond RetroArch's quad (its corner past 1) are not drawn.
        result += fmt::format("\nlayout(location = {}) in vec2 {};\n", tr.corner_location, kCornerVarying);
        before = fmt::format("    if ({0}.x > 1.0 || {0}.y > 1.0) discard;\n", kCornerVarying);
    }
    if (reads_frag_coord) {
        // GL ES and WebGL 2 count gl_FragCoord's rows from the bottom and have no origin_upper_left:
        // their GLSL counts them from the top by outputSize (targets/glsl), which a stage that reads
        // nothing else of the block would not have. A read that never discards keeps it there.
        tr.out.builtins.insert(Builtin::OutputSize);
        before += fmt::format("    if ({}.x < 0.0) discard;  // never: outputSize kept for GL ES\n", builtin_name(Builtin::OutputSize));
    }
    if (!vertex && tr.context.opaque_output) {
        if (d.fragment_output.empty())
            return make_error("the fragment stage declares no vec4 output at location 0", file, 0, "fragment output");
        std::string output = d.fragment_output;
        if (auto r = renamed.find(output); r != renamed.end()) output = r->second;
        after = fmt::format("    {}.a = 1.0;\n", output);
    }
    const char* why = !before.empty() ? "<crtforge: the pass's main>" : "<crtforge: RetroArch's display ignores alpha>";
    if (!vertex && (!before.empty() || !after.empty()))
        result += fmt::format("\n#line 1 \"{}\"\nvoid main() {{\n{}    {}();\n{}}}\n", why, before, kShaderMain, after);
    if (vertex) {
        const Member& position = d.vertex_inputs[0];
        const Member& coord = d.vertex_inputs[1];
        auto from_corner = [](const std::string& type) {
            if (type == "vec4") return std::string("vec4(crtCorner, 0.0, 1.0)");
            if (type == "vec3") return std::string("vec3(crtCorner, 0.0)");
            return type + "(crtCorner)";
        };
        const std::string corner_out =
            tr.quad_moved ? fmt::format("layout(location = {}) out vec2 {};\n", tr.corner_location, kCornerVarying) : std::string();
        const std::string corner_store = tr.quad_moved ? fmt::format("    {} = crtCorner;\n", kCornerVarying) : std::string();
        result += fmt::format(
            "\n#line 1 \"<crtforge: RetroArch's quad as crtforge's full-screen triangle>\"\n"
            "{}"
            "void main() {{\n"
            "    vec2 crtCorner = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));\n"
            "    {} = {};\n"
            "    {} = {};\n"
            "{}"
            "    {}();\n"
            "}}\n",
            corner_out, position.name, from_corner(position.type), coord.name, from_corner(coord.type), corner_store, kShaderMain);
    }
    return result;
}

}  // namespace

Result<TranslatedProgram> translate_program(const SlangSource& source, const ProgramContext& context) {
    TranslatedProgram out;
    Translation tr{context, out};
    auto vertex = translate_stage(source.vertex, true, source.path, tr);
    if (!vertex.ok()) return vertex.error();
    auto fragment = translate_stage(source.fragment, false, source.path, tr);
    if (!fragment.ok()) return fragment.error();
    out.vertex = std::move(vertex.value());
    out.fragment = std::move(fragment.value());
    return out;
}

}  // namespace crtforge::retroarch
