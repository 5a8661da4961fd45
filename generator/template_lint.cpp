#include "generator/template_lint.hpp"

#include <regex>
#include <sstream>

namespace crtforge::detail {

namespace {

constexpr unsigned long kMaxSnippetArray = 4096;

int line_at(const std::string& text, size_t offset) {
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// Line `line` (1-based) of the raw snippet, comments included.
std::string raw_line(const std::string& text, int line) {
    std::istringstream in(text);
    std::string out;
    for (int i = 0; i < line && std::getline(in, out); ++i) {}
    return out;
}

const ParamSpec* float_param(const StageSpec& stage, const std::string& name) {
    const ParamSpec* p = stage.find_param(name);
    return p && p->type == ParamType::Float && p->min && p->max ? p : nullptr;
}

}  // namespace

std::string without_comments(const std::string& text) {
    std::string out = text;
    for (size_t i = 0; i + 1 < out.size(); ++i) {
        if (out[i] == '/' && out[i + 1] == '/') {
            while (i < out.size() && out[i] != '\n') out[i++] = ' ';
        } else if (out[i] == '/' && out[i + 1] == '*') {
            for (; i + 1 < out.size() && !(out[i] == '*' && out[i + 1] == '/'); ++i)
                if (out[i] != '\n') out[i] = ' ';
            if (i + 1 < out.size()) out[i] = out[i + 1] = ' ';
        }
    }
    return out;
}

Status lint_stage_source(const StageSpec& stage) {
    const std::string text = without_comments(stage.glsl_source);
    auto fail = [&](size_t at, const std::string& message) -> Status {
        return make_error(message, stage.glsl_path, line_at(text, at), "glsl");
    };
    // A snippet declares no resources of its own: the generated code declares every texture (the
    // form's `textures`) and uniform (the params) for each target; a sampler the snippet declared
    // would compile in GLSL and reach a target (Godot, WGSL) that never binds it.
    static const std::regex resource(R"(\b(uniform|buffer|layout)\b)");
    if (std::smatch m; std::regex_search(text, m, resource))
        return fail(static_cast<size_t>(m.position()), "a snippet declares no '" + m[1].str() +
                                                            "' resources: the textures it reads are its form's `textures`, "
                                                            "its values are the spec's params");
    // Nor does it switch language features on: an `#extension` (GL_EXT_debug_printf, say) reaches
    // only the SPIR-V, which then fails validation far from the snippet, and no other target has it.
    static const std::regex extension(R"((^|\n)[ \t]*#[ \t]*extension\b)");
    if (std::smatch m; std::regex_search(text, m, extension))
        return fail(static_cast<size_t>(m.position()) + m[1].length(),
                    "a snippet enables no GLSL extensions (#extension): the generated code is the same GLSL for every target");
    // An array beyond a few thousand elements is no CRT stage's, and past 65535 words one SPIR-V
    // instruction cannot hold its constant (glslang then writes a broken module).
    static const std::regex array_size(R"(\[\s*(\d+)\s*\])");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), array_size); it != std::sregex_iterator(); ++it)
        if ((*it)[1].length() > 6 || std::stoul((*it)[1]) > kMaxSnippetArray)
            return fail(static_cast<size_t>(it->position()), "an array of " + (*it)[1].str() + " elements; a snippet's arrays hold at most " +
                                                                   std::to_string(kMaxSnippetArray));
    static const std::regex array_constructor(R"(\[\s*\d*\s*\]\s*\()");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), array_constructor); it != std::sregex_iterator(); ++it) {
        size_t elements = 1;
        int depth = 0;
        for (size_t i = static_cast<size_t>(it->position() + it->length()); i < text.size() && depth >= 0; ++i) {
            if (text[i] == '(') ++depth;
            else if (text[i] == ')') --depth;
            else if (text[i] == ',' && depth == 0) ++elements;
        }
        if (elements > kMaxSnippetArray)
            return fail(static_cast<size_t>(it->position()), "an array constructor of " + std::to_string(elements) +
                                                                 " elements; a snippet's arrays hold at most " + std::to_string(kMaxSnippetArray));
    }
    const std::string number = R"(([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))";
    static const std::regex smoothstep(R"(\bsmoothstep\s*\(\s*)" + number + R"(\s*,\s*)" + number + R"(\s*,)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), smoothstep); it != std::sregex_iterator(); ++it)
        if (std::stod((*it)[1]) >= std::stod((*it)[2]))
            return fail(static_cast<size_t>(it->position()),
                        "smoothstep(" + (*it)[1].str() + ", " + (*it)[2].str() + ", x) has its edges reversed or equal: undefined in "
                        "GLSL and HLSL and an error in WGSL; write 1.0 - smoothstep(" + (*it)[2].str() + ", " + (*it)[1].str() + ", x)");
    // Edges from a param: reversed or equal at some value of its range.
    static const std::regex smoothstep_param(R"(\bsmoothstep\s*\(\s*(\w+|)" + number + R"()\s*,\s*(\w+|)" + number + R"()\s*,)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), smoothstep_param); it != std::sregex_iterator(); ++it) {
        const std::string a = (*it)[1], b = (*it)[3];
        const ParamSpec* pa = float_param(stage, a);
        const ParamSpec* pb = float_param(stage, b);
        const bool reversible = (pa && !pb && std::isdigit(static_cast<unsigned char>(b.back())) && *pa->max >= std::stod(b)) ||
                                (pb && !pa && std::isdigit(static_cast<unsigned char>(a.back())) && *pb->min <= std::stod(a)) ||
                                (pa && pb && *pa->max >= *pb->min);
        if (reversible)
            return fail(static_cast<size_t>(it->position()),
                        "smoothstep(" + a + ", " + b + ", x): the params' ranges let the edges meet or cross, which is undefined "
                        "in GLSL and HLSL; keep the ranges apart");
    }
    static const std::regex pow_negative(R"(\bpow\s*\(\s*-\s*(?:\d|\.\d))");
    if (std::smatch m; std::regex_search(text, m, pow_negative))
        return fail(static_cast<size_t>(m.position()), "pow() of a negative constant base is undefined (NaN on most GPUs)");
    static const std::regex divide_zero(R"(/\s*0*\.?0+(?:[eE][-+]?\d+)?\b(?![.\d]))");
    if (std::smatch m; std::regex_search(text, m, divide_zero))
        return fail(static_cast<size_t>(m.position()), "division by a literal zero");
    for (const ParamSpec& p : stage.params) {
        if (p.type != ParamType::Float || !p.min || !p.max || !(*p.min <= 0.0 && *p.max >= 0.0)) continue;
        const std::regex divide_param(R"(/\s*)" + p.name + R"(\b(?!\s*[-+]))");
        for (auto it = std::sregex_iterator(text.begin(), text.end(), divide_param); it != std::sregex_iterator(); ++it) {
            const size_t at = static_cast<size_t>(it->position());
            // A division the code guards says so on its line: "// guarded: <why>".
            if (raw_line(stage.glsl_source, line_at(text, at)).find("guarded:") != std::string::npos) continue;
            return fail(at, "divides by " + p.name + ", whose range includes 0 (" + p.where.file + ":" + std::to_string(p.where.line) +
                                "): guard it (max(" + p.name + ", eps), or a test with \"// guarded: why\" on the line) or start the range above 0");
        }
    }
    return Ok{};
}

}  // namespace crtforge::detail
