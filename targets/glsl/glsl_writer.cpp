#include "targets/glsl/glsl_writer.hpp"

#include <regex>

#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include <sstream>

#include "crtforge/uniforms.hpp"
#include "targets/cross_compile.hpp"

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
        }, options.plain_uniforms ? kPlainBlockMarker : nullptr, /*flat_arrays*/ options.es ? options.version < 310 : options.version < 430);
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
         [](const TargetInput& in) { return generate(in, {450, false}); }, "glsl450/spirv-cross-2021.01.15/v3"},
        {TargetId::Glsl330, "glsl330", "GLSL 3.30 core (OpenGL 3.3)", {"vertex", "fragment"}, "gl",
         [](const TargetInput& in) { return generate(in, {330, false}); }, "glsl330/spirv-cross-2021.01.15/v4"},
        {TargetId::GlslEs300, "glsles300", "GLSL ES 3.00 (OpenGL ES 3.0 / WebGL 2)", {"vertex", "fragment"}, "gl-es",
         [](const TargetInput& in) { return generate(in, {300, true}); }, "glsles300/spirv-cross-2021.01.15/v3"},
        {TargetId::WebGl2, "webgl2", "WebGL 2 (GLSL ES 3.00, params as plain uniforms set by name)", {"vertex", "fragment"},
         "gl-es-plain", [](const TargetInput& in) { return generate(in, {300, true, true, true}); }, "webgl2/spirv-cross-2021.01.15/v2"},
    };
}

}  // namespace crtforge::glsl
