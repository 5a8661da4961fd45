// Variant -> GLSL 450 source for glslang.
#include "crtforge/assembler.hpp"
#include "crtforge/identifier_chars.hpp"
#include "crtforge/inert_text.hpp"

#include <algorithm>
#include <regex>
#include <array>
#include <set>

#include <fmt/format.h>

#include "crtforge/scene.hpp"

namespace crtforge {

namespace {

// The comment beside each builtin in the generated block (part of every golden's inputs hash:
// changing a word here makes them stale).
const char* builtin_comment(Builtin b) {
    switch (b) {
        case Builtin::OutputSize: return "output size in pixels";
        case Builtin::SourceSize: return "source texture size in texels";
        case Builtin::Time: return "seconds since start";
        case Builtin::FrameCount: return "frames since start (modulo the pass's frame_count_mod)";
        case Builtin::ViewportSize: return "the screen's size in pixels (what the last pass draws)";
    }
    return "";
}


std::string line_directive(int line, const std::string& file) {
    return fmt::format("#line {} \"{}\"\n", line, inert_quoted(file));
}



// Whether `name` occurs in `text` as a whole identifier.
bool mentions(const std::string& text, const std::string& name) {
    for (size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1))
        if ((at == 0 || !detail::is_identifier_char(text[at - 1])) && (at + name.size() == text.size() || !detail::is_identifier_char(text[at + name.size()]))) return true;
    return false;
}

// The identifiers of `text`, but for its `#pragma` lines (an imported program keeps its
// `#pragma parameter` lines, which name every parameter of its includes). Comments, macros and
// the code an `#if` leaves out count: a superset is safe here.
std::set<std::string> identifiers_in(const std::string& text) {
    std::set<std::string> out;
    bool line_start = true;
    for (size_t at = 0; at < text.size();) {
        const char c = text[at];
        if (c == '\n') line_start = true;
        else if (line_start && c == '#') {
            size_t word = at + 1;
            while (word < text.size() && (text[word] == ' ' || text[word] == '\t')) ++word;
            if (text.compare(word, 6, "pragma") == 0) {
                at = std::min(text.find('\n', at), text.size());
                continue;
            }
            line_start = false;
        } else if (c != ' ' && c != '\t') line_start = false;
        if (!detail::is_identifier_char(c)) { ++at; continue; }
        size_t end = at;
        while (end < text.size() && detail::is_identifier_char(text[end])) ++end;
        if (!std::isdigit(static_cast<unsigned char>(text[at]))) out.emplace(text, at, end - at);
        at = end;
    }
    return out;
}

// The uniform block, baked constants and samplers. A snippet's fragment shader also gets its
// input and output; a program declares its own. `program_stage`: the text of a program's stage,
// which gets only the samplers it names (a vertex shader rarely samples).
std::string declarations(const Variant& variant, const std::string* program_stage = nullptr,
                         BakedParams as = BakedParams::Constants) {
    std::string out;
    if (!program_stage) {
        out += fmt::format("layout(location = 0) in vec2 {};\n", kTexCoordName);
        out += "layout(location = 0) out vec4 fragColor;\n";
    }
    if (!program_stage || mentions(*program_stage, kSourceTextureName))
        out += fmt::format("layout(set = {}, binding = {}) uniform sampler2D {};\n", kDescriptorSet,
                           kTextureBinding, kSourceTextureName);
    for (size_t i = 0; i < variant.textures.size(); ++i)
        if (!program_stage || mentions(*program_stage, variant.textures[i]))
            out += fmt::format("layout(set = {}, binding = {}) uniform sampler2D {};\n", kDescriptorSet,
                               kTextureBinding + 1 + i, variant.textures[i]);
    if (variant.has_uniform_block()) {
        out += fmt::format("\nlayout(std140, set = {}, binding = {}) uniform {} {{\n", kDescriptorSet,
                           kUniformBinding, kUniformBlockName);
        for (Builtin b : variant.builtins) {
            const char* type = builtin_glsl_type(b);
            out += fmt::format("    {} {};  // builtin: {}\n", type, builtin_name(b), builtin_comment(b));
        }
        for (const VariantParam* p : variant.uniforms()) {
            std::string range;
            if (p->spec->min) range = fmt::format(" [{}, {}]", *p->spec->min, *p->spec->max);
            out += fmt::format("    {} {};  // {}{} {}\n", glsl_type_for(p->spec->type), p->spec->name,
                               p->stage->name, range, inert_comment(p->spec->doc));
        }
        out += "};\n";
    }
    auto baked = variant.baked();
    // A program's stage gets the baked params it names, no others: a pass that two presets share
    // then compiles to the same module wherever the values it reads agree (a preset's stage
    // switch and its hundreds of other params would otherwise each leave a constant behind).
    if (program_stage) {
        const std::set<std::string> named = identifiers_in(*program_stage);
        baked.erase(std::remove_if(baked.begin(), baked.end(), [&](const VariantParam* p) { return !named.count(p->spec->name); }),
                    baked.end());
    }
    if (!baked.empty()) {
        const bool variables = as == BakedParams::Variables;
        out += variables ? "\n// Fixed by the preset: never written, folded away by the optimiser.\n"
               : as == BakedParams::Specialized ? "\n// Fixed by the preset: specialization constants, folded by the driver.\n"
                                               : "\n// Fixed by the preset: compile-time constants, folded away by the optimiser.\n";
        int spec_id = 0;
        for (const VariantParam* p : baked) {
            int index = p->spec->type == ParamType::Enum
                            ? p->spec->enum_index(std::get<std::string>(p->value)) : -1;
            std::string note = p->spec->type == ParamType::Enum ? "  // " + std::get<std::string>(p->value) : "";
            // A specialization constant is a scalar: a colour stays a constant.
            std::string qualifier = variables ? "" : "const ";
            if (as == BakedParams::Specialized && p->spec->type != ParamType::Color)
                qualifier = fmt::format("layout(constant_id = {}) const ", spec_id++);
            out += fmt::format("{}{} {} = {};{}\n", qualifier, glsl_type_for(p->spec->type), p->spec->name,
                               value_to_glsl(p->value, p->spec->type, index), note);
        }
    }
    return out;
}

// How the source picture's coordinate follows the screen's ([source] fit): a baked constant, and
// a function stages can call. Emitted only where main() or a stage's snippet uses it: even an
// unused function would renumber the optimised SPIR-V of every other shader.
std::string source_mapping(const Variant& variant) {
    const bool screen_pass = screen_pass_index(*variant.preset) == variant.pass_index;
    const auto scale = screen_pass ? source_uv_scale(*variant.preset) : std::array<double, 2>{1.0, 1.0};
    return fmt::format("\n// The source picture's coordinate at a screen coordinate ([source] fit).\n"
                       "const vec2 crtSourceScale = vec2({}, {});\n"
                       "vec2 crt_source_uv(vec2 uv) {{ return (uv - 0.5) * crtSourceScale + 0.5; }}\n",
                       float_literal(scale[0]), float_literal(scale[1]));
}

// The warp stages as one function: stages that sample at a screen-space point other than the
// fragment's own (the shadow mask's cell centre) warp it as main() warps the fragment. Emitted,
// like crt_source_uv, only where a snippet calls it; declared before the snippets, defined after.
constexpr const char* kWarpFunction = "crt_warp";

bool calls_warp(const Variant& variant) {
    for (const VariantStage& ss : variant.stages)
        if (ss.stage->glsl_source.find(kWarpFunction) != std::string::npos) return true;
    return false;
}

// The line of `text` where function `fn` is defined (a type, the name, its parameters), else 0.
int definition_line(const std::string& text, const std::string& fn) {
    const std::regex definition("(^|\n)[ \t]*\\w+[ \t]+" + fn + "[ \t]*\\(");
    std::smatch m;
    if (!std::regex_search(text, m, definition)) return 0;
    const auto start = text.begin() + m.position() + m[1].length();
    return 1 + static_cast<int>(std::count(text.begin(), start, '\n'));
}

// Stands where a generated file resumes after a call line attributed to a snippet; include()
// replaces it with the generated file's own line number.
constexpr std::string_view kResumeLine = "#line @resume\n";

// The calls of one hook in pass order, one statement each made from `pattern` ({} = the function).
// In the uber-shader each call runs only where its stage's switch selects a form that has it.
std::string hook_calls(const Variant& variant, Hook hook, const std::string& pattern) {
    std::string text;
    for (const VariantStage& ss : variant.stages) {
        // Forms that share a function share its call.
        std::vector<std::pair<std::string, std::vector<const FormSpec*>>> calls;
        for (const FormSpec* form : ss.forms) {
            const std::string& fn = form->functions[static_cast<int>(hook)];
            if (fn.empty()) continue;
            auto same = std::find_if(calls.begin(), calls.end(), [&](const auto& c) { return c.first == fn; });
            if (same == calls.end()) calls.push_back({fn, {form}});
            else same->second.push_back(form);
        }
        for (const auto& [fn, forms] : calls) {
            std::string names, condition;
            for (const FormSpec* form : forms) {
                names += (names.empty() ? "" : ", ") + form->name;
                condition += fmt::format("{}{} == {}", condition.empty() ? "" : " || ", ss.stage->stage_switch.name,
                                         ss.switch_value(form));
            }
            const std::string call = fmt::format(fmt::runtime(pattern), fn);
            // An error on the call line (the function's return or parameter types are not what
            // the form's hook calls) is the snippet's: glslang reports it at the definition.
            const int defined = definition_line(ss.stage->glsl_source, fn);
            if (defined) text += line_directive(defined, ss.stage->glsl_path);
            if (ss.switched) text += fmt::format("    if ({}) {}  // {} ({})\n", condition, call, ss.stage->name, names);
            else text += fmt::format("    {}  // {} ({})\n", call, ss.stage->name, names);
            if (defined) text += kResumeLine;
        }
    }
    return text;
}

std::string warp_function(const Variant& variant) {
    return fmt::format("// The warp stages in pass order, for stages that warp a point of their own.\nvec2 {}(vec2 uv) {{\n", kWarpFunction) +
           hook_calls(variant, Hook::Warp, "uv = {}(uv);") + "    return uv;\n}\n";
}

bool maps_source(const Variant& variant) {
    return screen_pass_index(*variant.preset) == variant.pass_index && source_uv_scale(*variant.preset) != std::array<double, 2>{1.0, 1.0};
}

// `text` (a generated file named `file`) with each kResumeLine a #line back to its own numbering:
// the lines attributed elsewhere and the directives do not count.
std::string resume_lines(const std::string& text, const std::string& file) {
    std::string out;
    int line = 0;
    for (size_t at = 0; at < text.size();) {
        const size_t end = std::min(text.find('\n', at), text.size() - 1) + 1;
        const std::string_view one(text.data() + at, end - at);
        if (one == kResumeLine) out += line_directive(line + 1, file);
        else {
            out += one;
            if (one.rfind("#line ", 0) != 0) ++line;
        }
        at = end;
    }
    return out;
}

// The fixed pass order: warp, sample position, fetch, colour stages, finish.
std::string main_body(const Variant& variant) {
    // Every output is finite, whatever the input holds (docs/hard-cases.md): NaN becomes 0 and
    // anything beyond half's range its largest value, so no consumer's framebuffer, and no later
    // pass, sees a NaN or an infinity. isnan() selects rather than clamp(), whose NaN result GLSL,
    // HLSL and WGSL leave undefined.
    const std::string finite = "vec4 crt_finite(vec4 c) { return mix(clamp(c, -65504.0, 65504.0), vec4(0.0), isnan(c)); }\n\n";
    std::string out = finite + "void main() {\n";
    if (variant.stages.empty()) {
        out += fmt::format("    fragColor = crt_finite(texture({}, {}));  // CRT off: plain passthrough blit\n",
                           kSourceTextureName, kTexCoordName);
        return out + "}\n";
    }
    auto calls = [&](Hook hook, const std::string& pattern) { return hook_calls(variant, hook, pattern); };
    // A supersampled pass shades n x n points of its pixel (crt_shade) and averages them, each
    // finite, as the reference does (render_reference's box_mean over the pass's points).
    const int n = variant.pass->supersample;
    const std::string coord = n > 1 ? "crtTexCoord" : kTexCoordName;
    std::string body;
    body += "    CrtFrag frag;\n";
    body += fmt::format("    frag.screenUv = {};\n", coord);
    body += fmt::format("    frag.pixel = {} * outputSize;\n", coord);
    body += fmt::format("    frag.uv = {};\n", coord);
    body += calls(Hook::Warp, "frag.uv = {}(frag.uv);");
    body += "    frag.centered = frag.uv * 2.0 - 1.0;\n";
    body += "    vec2 sampleUv = frag.uv;\n";
    body += calls(Hook::SampleUv, "sampleUv = {}(sampleUv, frag);");
    if (maps_source(variant)) body += "    sampleUv = crt_source_uv(sampleUv);  // the picture on the screen ([source] fit)\n";
    body += fmt::format("    vec3 color = texture({}, sampleUv).rgb;\n", kSourceTextureName);
    body += calls(Hook::Fetch, "color = {}(color, sampleUv);");
    body += calls(Hook::Color, "color = {}(color, frag);");
    body += calls(Hook::Finish, "color = {}(color, frag);");
    // Alpha only where a stage sets it, so every other shader stays as it was.
    const std::string alpha = calls(Hook::Alpha, "alpha = {}(alpha, frag);");
    const std::string result = alpha.empty() ? "crt_finite(vec4(color, 1.0))" : "crt_finite(vec4(color, alpha))";
    if (!alpha.empty()) body += "    float alpha = 1.0;\n" + alpha;
    if (n == 1) return out + body + "    fragColor = " + result + ";\n}\n";
    // Written out, not looped (Godot 3 refuses a loop's comma operator).
    std::string shade = fmt::format("vec4 crt_shade(vec2 {}) {{\n", coord) + body + "    return " + result + ";\n}\n\n";
    std::string sum;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            sum += fmt::format("{}crt_shade({} + vec2({:.6f}, {:.6f}) / outputSize)", sum.empty() ? "" : "\n        + ", kTexCoordName,
                               (x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5);
    return finite + shade + "void main() {\n" + fmt::format("    fragColor = ({}) / {}.0;\n}}\n", sum, n * n);
}

// A program form: its two files after the declarations, each with #line back to its file.
AssembledShader assemble_program(const std::string& header, const Variant& variant, const FormSpec& form, BakedParams baked) {
    AssembledShader out;
    out.fragment = header + declarations(variant, &form.fragment_source, baked) + "\n" + line_directive(1, form.fragment_path) +
                   form.fragment_source;
    out.vertex = header + declarations(variant, &form.vertex_source, baked) + "\n" + line_directive(1, form.vertex_path) +
                 form.vertex_source;
    return out;
}

}  // namespace

const char* builtin_glsl_type(Builtin builtin) {
    return builtin == Builtin::Time ? "float" : builtin == Builtin::FrameCount ? "int" : "vec2";
}

AssembledShader assemble(const TemplateLibrary& library, const Variant& variant, BakedParams baked) {
    const Preset& preset = *variant.preset;
    std::string src;
    src += "#version 450\n";
    src += "#extension GL_GOOGLE_cpp_style_line_directive : require\n";
    std::string lineage;
    for (const auto& n : preset.lineage) lineage += (lineage.empty() ? "" : " <- ") + n;
    src += fmt::format("// crtforge: preset {} ({}), precision {}, uniforms {}\n", preset.name, lineage,
                       precision_name(variant.options.precision), variant.options.uniforms.str());
    if (!preset.single_pass())
        src += fmt::format("// pass {} of {}: {}\n", variant.pass_index + 1, preset.passes.size(), variant.pass->alias);
    const Pass& pass = *variant.pass;
    if (variant.options.precision == Precision::Medium) src += "precision mediump float;\n";
    for (const VariantStage& ss : variant.stages)
        for (const FormSpec* form : ss.forms) src += fmt::format("#define CRT_FORM_{}_{} 1\n", ss.stage->name, form->name);
    if (const FormSpec* program = variant.program_form()) return assemble_program(src, variant, *program, baked);
    src += declarations(variant);

    // Each included file starts on its own line with a #line directive naming it, so glslang
    // reports errors at the template's file:line.
    auto include = [&src](const std::string& file, const std::string& text) {
        src += '\n';
        src += line_directive(1, file);
        src += resume_lines(text, file);
    };
    if (!variant.stages.empty()) {
        include(library.prelude_path(), library.prelude_source());
        bool used = maps_source(variant);
        for (const VariantStage& ss : variant.stages) used = used || ss.stage->glsl_source.find("crt_source_uv") != std::string::npos;
        if (used) src += source_mapping(variant);
        const bool warp = calls_warp(variant);
        if (warp) src += fmt::format("\nvec2 {}(vec2 uv);  // the warp stages, defined after the snippets\n", kWarpFunction);
        for (const VariantStage& ss : variant.stages) include(ss.stage->glsl_path, ss.stage->glsl_source);
        if (warp) include("<generated " + std::string(kWarpFunction) + " for preset " + preset.name + ">", warp_function(variant));
    }
    include("<generated main for preset " + preset.name + (preset.single_pass() ? "" : " pass " + pass.alias) + ">",
            main_body(variant));

    AssembledShader out;
    out.fragment = std::move(src);
    out.vertex = library.vertex_source();
    return out;
}

}  // namespace crtforge
