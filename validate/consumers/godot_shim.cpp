#include "validate/consumers/godot_shim.hpp"

#include <regex>
#include <sstream>

#include "crtforge/assembler.hpp"
#include "validate/consumers/consumer.hpp"

namespace crtforge::consumers {

Result<ShimShader> wrap_in_shim(const std::string& source, int version) {
    static const std::regex uniform_re(R"(^\s*uniform\s+(\w+)\s+(\w+)\s*(?::\s*([^=;]*))?\s*(?:=\s*([^;]*))?;\s*$)");
    ShimShader shim;
    std::string body, sampler;  // sampler: Godot 4's screen texture (hint_screen_texture)
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
    shim.screen_mode = source.find("SCREEN_UV") != std::string::npos;

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
    glsl += "};\n#line 1 \"<godot shader>\"\n" + body;
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
    return Ok{};
}

}  // namespace crtforge::consumers
