#include "validate/consumers/godot_shim.hpp"

#include <regex>
#include <sstream>

#include "crtforge/assembler.hpp"
#include "validate/consumers/consumer.hpp"

namespace crtforge::consumers {

namespace {

// `text` without the function whose definition starts at `signature` (its body brace-matched);
// the function's lines become blank lines, so line numbers stay those of the shader.
std::string without_function(const std::string& text, const std::string& signature) {
    const size_t start = text.find(signature);
    if (start == std::string::npos) return text;
    size_t open = text.find('{', start), end = open;
    int depth = 0;
    for (; end < text.size(); ++end) {
        if (text[end] == '{') ++depth;
        if (text[end] == '}' && --depth == 0) break;
    }
    if (open == std::string::npos || end >= text.size()) return text;
    std::string out = text.substr(0, start);
    for (size_t i = start; i <= end; ++i)
        if (text[i] == '\n') out += '\n';
    return out + text.substr(end + 1);
}

}  // namespace

Result<ShimShader> wrap_in_shim(const std::string& source, int version) {
    static const std::regex uniform_re(R"(^\s*uniform\s+(\w+)\s+(\w+)\s*(?::\s*([^=;]*))?\s*(?:=\s*([^;]*))?;\s*$)");
    ShimShader shim;
    std::string body, sampler;  // sampler: Godot 4's screen texture (hint_screen_texture)
    std::string fragment_varyings, vertex_varyings;  // `varying` lines as each stage's in / out
    uint32_t next_location = 1;  // 0: UV
    bool saw_type = false, saw_fragment = false;
    std::istringstream lines(source);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        if (line.rfind("shader_type", 0) == 0) {
            if (line.find("canvas_item") == std::string::npos)
                return make_validation_error("the shim only knows canvas_item shaders", "<godot shader>", number);
            saw_type = true;
            body += "// " + line + "\n";
            continue;
        }
        // How Godot blends the output: nothing to check as GLSL (only known modes are kept).
        static const std::regex render_mode_re(R"(^render_mode\s+(blend_mix|blend_disabled|blend_premul_alpha|unshaded)\s*;\s*$)");
        if (std::regex_match(line, render_mode_re)) {
            body += "// " + line + "\n";
            continue;
        }
        // Godot 4's inspector headings: nothing for GLSL; Godot 3 has none.
        static const std::regex group_re(R"(^group_uniforms(\s+\w+(\.\w+)?)?\s*;\s*$)");
        if (std::regex_match(line, group_re)) {
            if (version < 4) return make_validation_error("group_uniforms is Godot 4 syntax; Godot 3 rejects it", "<godot shader>", number);
            body += "// " + line + "\n";
            continue;
        }
        std::smatch m;
        static const std::regex varying_re(R"(^varying\s+(flat\s+)?(\w+)\s+(\w+)\s*(\[\s*(\d+)\s*\])?\s*;\s*$)");
        if (std::regex_match(line, m, varying_re)) {
            const std::string decl = m[2].str() + " " + m[3].str() + m[4].str() + ";\n";
            const std::string at = "layout(location = " + std::to_string(next_location) + ") " + m[1].str();
            fragment_varyings += at + "in " + decl;
            vertex_varyings += at + "out " + decl;
            // A matrix or array takes a location per column or element.
            uint32_t slots = m[2].str().rfind("mat", 0) == 0 ? static_cast<uint32_t>(m[2].str().back() - '0') : 1;
            if (m[5].matched) slots *= static_cast<uint32_t>(std::stoul(m[5].str()));
            next_location += slots;
            body += "// " + line + "\n";
            continue;
        }
        if (std::regex_match(line, m, uniform_re)) {
            if (m[1] == "sampler2D") {
                if (m[3].str().find("hint_screen_texture") != std::string::npos) sampler = m[2];
                else shim.textures.push_back({m[2], kTextureBinding + 1 + static_cast<uint32_t>(shim.textures.size())});
                body += "// " + line + "\n";
                continue;
            }
            shim.uniforms.push_back({m[1], m[2], m[4]});
            body += "// " + line + "\n";
            continue;
        }
        if (line.find("void fragment()") != std::string::npos) {
            saw_fragment = true;
            line.replace(line.find("void fragment()"), 15, "void main()");
        }
        body += line + "\n";
    }
    if (!saw_type) return make_validation_error("no `shader_type canvas_item;` line", "<godot shader>", 1);
    if (!saw_fragment) return make_validation_error("no `void fragment()`", "<godot shader>", number);
    // A program pass's screen shader reads the screen texture at its own varyings, not SCREEN_UV.
    shim.screen_mode = source.find("SCREEN_UV") != std::string::npos || !sampler.empty() ||
                       (version < 4 && source.find("SCREEN_TEXTURE") != std::string::npos);

    const std::string texture = shim.screen_mode ? (version >= 4 ? sampler : std::string("SCREEN_TEXTURE")) : "TEXTURE";
    if (texture.empty()) return make_validation_error("screen mode without a hint_screen_texture sampler", "<godot shader>", 1);
    std::string glsl = "#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n";
    glsl += "// crtforge Godot shim: what Godot provides to a canvas_item fragment(), as Vulkan resources.\n";
    glsl += std::string("layout(location = 0) in vec2 ") + (shim.screen_mode ? "SCREEN_UV" : "UV") + ";\n";
    glsl += "layout(location = 0) out vec4 crtforge_shim_color;\n";
    glsl += "#define COLOR crtforge_shim_color\n";
    glsl += "layout(set = 0, binding = " + std::to_string(kTextureBinding) + ") uniform sampler2D " + texture + ";\n";
    for (const auto& t : shim.textures)
        glsl += "layout(set = 0, binding = " + std::to_string(t.binding) + ") uniform sampler2D " + t.name + ";\n";
    glsl += "layout(std140, set = 0, binding = " + std::to_string(kUniformBinding) + ") uniform GodotShim {\n";
    glsl += "    vec2 TEXTURE_PIXEL_SIZE;\n    vec2 SCREEN_PIXEL_SIZE;\n    float TIME;\n";
    for (const auto& u : shim.uniforms) glsl += "    " + u.type + " " + u.name + ";\n";
    glsl += "};\n";
    const bool has_vertex = body.find("void vertex()") != std::string::npos;
    if (has_vertex) {
        std::string vertex = glsl;  // the same prelude, less the colour output
        const std::string color = "layout(location = 0) out vec4 crtforge_shim_color;\n";
        vertex.replace(vertex.find(color), color.size(), "");
        const std::string screen_uv = "in vec2 SCREEN_UV;";  // a vertex() reads the node's UV in both modes
        if (const size_t at = vertex.find(screen_uv); at != std::string::npos) vertex.replace(at, screen_uv.size(), "in vec2 UV;");
        vertex += "vec2 VERTEX;  // the node's corner in its own pixels, which vertex() may move\n";
        std::string vertex_body = without_function(body, "void main()");  // fragment(), renamed above
        vertex_body.replace(vertex_body.find("void vertex()"), 13, "void main()");
        shim.vertex_glsl = vertex + vertex_varyings + "#line 1 \"<godot shader>\"\n" + vertex_body;
        body = without_function(body, "void vertex()");
    }
    glsl += fragment_varyings;
    glsl += "#define FRAGCOORD gl_FragCoord\n";
    glsl += "#line 1 \"<godot shader>\"\n" + body;
    shim.glsl = std::move(glsl);
    return shim;
}

Status compile_through_shim(const std::string& godot_shader, int godot_version, ConsumerEngines& engines) {
    auto shim = wrap_in_shim(godot_shader, godot_version);
    if (!shim.ok()) return shim.error();
    CompileOptions options;
    options.optimize = false;
    options.source_name = "<godot shader>";
    auto module = engines.front_end(shim.value().glsl, options);
    if (!module.ok()) return module.error();
    if (shim.value().vertex_glsl.empty()) return Ok{};
    options.stage = ShaderStage::Vertex;
    auto vertex = engines.front_end(shim.value().vertex_glsl, options);
    if (!vertex.ok()) return vertex.error();
    return Ok{};
}

}  // namespace crtforge::consumers
