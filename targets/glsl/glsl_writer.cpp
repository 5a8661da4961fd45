#include "targets/glsl/glsl_writer.hpp"

#include <algorithm>
#include <map>
#include <regex>

#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include <sstream>

#include "crtforge/uniforms.hpp"
#include "targets/cross_compile.hpp"
#include "targets/word_scan.hpp"

namespace crtforge::glsl {

namespace {

// The instance name SPIRV-Cross gives the block while flattening: no template name can take it.
constexpr const char* kPlainBlockMarker = "crtforge_plain_block";

// Desktop GL counts gl_FragCoord's rows from the bottom, Vulkan (the SPIR-V's meaning) from the
// top: a shader that reads it (RetroArch's masks and noise do) gets it redeclared top-down, after
// the #version and #extension lines. GLSL ES has no such layout (docs/retroarch.md, Not yet).
std::string with_fragcoord_from_top(const std::string& text) {
    static const std::regex use(R"(\bgl_FragCoord\b)");
    if (!std::regex_search(text, use)) return text;
    size_t at = 0;
    while (at < text.size() && text[at] == '#') {
        const size_t end = text.find('\n', at);
        if (end == std::string::npos) return text;
        at = end + 1;
    }
    return text.substr(0, at) + "layout(origin_upper_left) in vec4 gl_FragCoord;\n" + text.substr(at);
}

// GLSL ES has no origin_upper_left either: a shader that reads gl_FragCoord reads, in its place, a
// global that main() fills first with the row counted from the top of the pass's output, as
// Vulkan counts it, by `outputSize` (exact in every pass but a last pass the host letterboxes,
// whose rows then count from the picture's edge, not the display's). `declaration` declares
// what `output_size` names where the shader itself does not (empty: it does).
Result<std::string> with_es_fragcoord_from_top(const std::string& text, const std::string& output_size, const std::string& declaration) {
    bool reads = false;
    std::string out = detail::rewrite_words(text, [&](std::string_view word) -> std::optional<std::string> {
        if (word != "gl_FragCoord") return std::nullopt;
        reads = true;
        return std::string("crt_FragCoord");
    });
    if (!reads) return text;
    const std::string main = "\nvoid main()\n{\n";
    const size_t body = out.find(main);
    size_t at = 0;
    while (at < out.size() && (out[at] == '#' || out.compare(at, 10, "precision ") == 0)) {
        const size_t end = out.find('\n', at);
        if (end == std::string::npos) break;
        at = end + 1;
    }
    if (body == std::string::npos || at == 0 || body < at)
        return make_validation_error("SPIRV-Cross's GLSL ES fragment shader did not have the expected shape (gl_FragCoord from the top)");
    out.insert(body + main.size(), "    crt_FragCoord = vec4(gl_FragCoord.x, " + output_size + ".y - gl_FragCoord.y, gl_FragCoord.zw);\n");
    out.insert(at, declaration + "highp vec4 crt_FragCoord;  // gl_FragCoord with rows from the top, as in Vulkan\n");
    return out;
}

// The uniform block's declaration as SPIRV-Cross printed it in `text` (empty: none there).
std::string block_declaration(const std::string& text) {
    const size_t start = text.find(std::string("layout(std140) uniform ") + kUniformBlockName + "\n");
    const std::string end = std::string("} ") + kUniformInstanceName + ";\n";
    const size_t stop = start == std::string::npos ? start : text.find(end, start);
    return stop == std::string::npos ? std::string() : text.substr(start, stop + end.size() - start);
}

}  // namespace

std::string flatten_plain_uniform_block(const std::string& text, const std::string& instance) {
    const std::regex declaration(R"((^|\n)uniform (\w+) )" + instance + ";\n");
    std::smatch use;
    if (!std::regex_search(text, use, declaration)) return text;
    const std::string type = use[2].str();
    const std::regex definition(R"((^|\n)struct )" + type + R"(\n\{\n((?:    [^\n]*\n)*)\};\n\n?)");
    std::smatch def;
    if (!std::regex_search(text, def, definition)) return text;
    std::string uniforms;
    std::istringstream members(def[2].str());
    for (std::string line; std::getline(members, line);) uniforms += "uniform " + line.substr(4) + "\n";
    std::string out = text;
    // Replace the later declaration first, so the definition's position stays valid.
    out.replace(static_cast<size_t>(use.position(0)) + use[1].length(), use.length(0) - use[1].length(), uniforms);
    out.replace(static_cast<size_t>(def.position(0)) + def[1].length(), def.length(0) - def[1].length(), "");
    return detail::replace_block_access(out, instance, [](const std::string& member) { return member; });
}

Result<TargetOutput> generate(const TargetInput& input, const Options& options) {
    const std::string language = options.es ? fmt::format("GLSL ES {}", options.version) : fmt::format("GLSL {}", options.version);
    const Precision precision = input.variant->options.precision;
    std::map<uint32_t, std::string> vertex_outputs;  // location -> name, read while the vertex stage compiles
    auto out = detail::emit_both_stages(input, ".vert", ".frag", [&](const SpirvBinary& module, ShaderStage stage) {
        return detail::cross_compile<spirv_cross::CompilerGLSL>(module, stage, language, [&](spirv_cross::CompilerGLSL& c) {
            auto o = c.get_common_options();
            o.version = static_cast<uint32_t>(options.version);
            o.es = options.es;
            o.vulkan_semantics = false;
            o.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
            // ES needs a default float precision; medium-precision variants also carry
            // RelaxedPrecision decorations, which SPIRV-Cross prints as mediump.
            o.fragment.default_float_precision = precision == Precision::High
                ? spirv_cross::CompilerGLSL::Options::Highp : spirv_cross::CompilerGLSL::Options::Mediump;
            o.emit_uniform_buffer_as_plain_uniforms = options.plain_uniforms;
            c.set_common_options(o);
            // GLSL without explicit varying locations (ES 3.00, 3.30 without separate shader objects)
            // meets a vertex output and a fragment input by name, Vulkan by location: a RetroArch
            // pass may name them apart (scanline-classic's vTexCoord_out / vTexCoord_in), so the
            // fragment stage's input takes the name of the vertex output at its location
            // (emit_both_stages compiles the vertex stage first).
            const auto resources = c.get_shader_resources();
            for (const auto& io : stage == ShaderStage::Vertex ? resources.stage_outputs : resources.stage_inputs) {
                if (!c.has_decoration(io.id, spv::DecorationLocation)) continue;
                const uint32_t location = c.get_decoration(io.id, spv::DecorationLocation);
                if (stage == ShaderStage::Vertex) {
                    vertex_outputs[location] = c.get_name(io.id);
                } else if (auto name = vertex_outputs.find(location); name != vertex_outputs.end() && !name->second.empty()) {
                    c.set_name(io.id, name->second);
                }
            }
        }, options.plain_uniforms ? kPlainBlockMarker : nullptr, /*flat_arrays*/ options.es ? options.version < 310 : options.version < 430,
           /*lower_gathers*/ options.es ? options.version < 310 : options.version < 400, /*split_io_structs*/ options.es);
    });
    if (!out.ok()) return out;
    if (!options.es)
        for (OutputFile& f : out.value().files)
            if (f.stage == ShaderStage::Fragment) f.data = with_fragcoord_from_top(f.data);
    if (options.plain_uniforms) {
        for (OutputFile& f : out.value().files) {
            f.data = flatten_plain_uniform_block(f.data, kPlainBlockMarker);
            if (f.data.find(kPlainBlockMarker) != std::string::npos)
                return make_validation_error("SPIRV-Cross's plain uniform block did not have the expected shape (" + language + ", WebGL 2)");
        }
    }
    const auto& builtins = input.variant->builtins;
    if (options.es && std::find(builtins.begin(), builtins.end(), Builtin::OutputSize) != builtins.end()) {
        std::string vertex_block;
        for (const OutputFile& f : out.value().files)
            if (f.stage == ShaderStage::Vertex) vertex_block = block_declaration(f.data);
        for (OutputFile& f : out.value().files) {
            if (f.stage != ShaderStage::Fragment) continue;
            const std::string name = builtin_name(Builtin::OutputSize);
            std::string output_size = name, declaration;
            if (options.plain_uniforms) {
                // A plain uniform the fragment stage did not keep: the vertex stage's, if any, is
                // highp as this one (ES links uniforms of one name and precision across stages).
                if (f.data.find("uniform vec2 " + name + ";\n") == std::string::npos) declaration = "uniform highp vec2 " + name + ";\n";
            } else {
                output_size = std::string(kUniformInstanceName) + "." + name;
                // A fragment stage that reads no member has no block: the vertex stage's declaration,
                // the same text, links; none, or a mediump stage (whose members would differ in
                // precision), keeps gl_FragCoord as GL counts it (docs/retroarch.md, Not yet).
                if (block_declaration(f.data).empty()) {
                    const bool highp = f.data.find("precision highp float;") != std::string::npos;
                    if (vertex_block.empty() || !highp) continue;
                    declaration = vertex_block;
                }
            }
            auto flipped = with_es_fragcoord_from_top(f.data, output_size, declaration);
            if (!flipped.ok()) return flipped.error();
            f.data = std::move(flipped.value());
        }
    }
    if (options.plain_uniforms) {
        for (const VariantParam* p : input.variant->uniforms())
            out.value().bindings.push_back({p->spec->name, "plain uniform: set by name, e.g. glUniform*(glGetUniformLocation(program, \"" + p->spec->name + "\"), ...)"});
        for (Builtin b : input.variant->builtins)
            out.value().bindings.push_back({builtin_name(b), "plain uniform, set by the host each frame"});
        out.value().bindings.push_back({kSourceTextureName, "sampler2D: set with glUniform1i(glGetUniformLocation(program, \"source\"), unit)"});
        return out;
    }
    const bool explicit_bindings = options.version >= 420 && !options.es;
    if (input.variant->has_uniform_block())
        out.value().bindings.push_back({kUniformBlockName, explicit_bindings
            ? "layout(binding = 0) uniform block, std140"
            : "std140 uniform block: bind with glUniformBlockBinding(program, glGetUniformBlockIndex(program, \"CrtParams\"), 0)"});
    out.value().bindings.push_back({kSourceTextureName, explicit_bindings
        ? "layout(binding = 1) sampler2D"
        : "sampler2D: set with glUniform1i(glGetUniformLocation(program, \"source\"), unit)"});
    return out;
}

std::vector<TargetInfo> records() {
    // Bump a fingerprint whenever that target's output changes for the same SPIR-V.
    return {
        {TargetId::Glsl450, "glsl450", "GLSL 4.50 core (OpenGL 4.5)", {"vertex", "fragment"}, "gl",
         [](const TargetInput& in) { return generate(in, {450, false}); }, "glsl450/spirv-cross-2021.01.15/v4"},
        {TargetId::Glsl330, "glsl330", "GLSL 3.30 core (OpenGL 3.3)", {"vertex", "fragment"}, "gl",
         [](const TargetInput& in) { return generate(in, {330, false}); }, "glsl330/spirv-cross-2021.01.15/v6"},
        {TargetId::GlslEs300, "glsles300", "GLSL ES 3.00 (OpenGL ES 3.0 / WebGL 2)", {"vertex", "fragment"}, "gl-es",
         [](const TargetInput& in) { return generate(in, {300, true}); }, "glsles300/spirv-cross-2021.01.15/v6"},
        {TargetId::WebGl2, "webgl2", "WebGL 2 (GLSL ES 3.00, params as plain uniforms set by name)", {"vertex", "fragment"},
         "gl-es-plain", [](const TargetInput& in) { return generate(in, {300, true, true, true}); }, "webgl2/spirv-cross-2021.01.15/v5"},
    };
}

}  // namespace crtforge::glsl
