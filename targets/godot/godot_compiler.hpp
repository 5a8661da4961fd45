// A SPIRV-Cross GLSL compiler that prints Godot's canvas_item dialect: no #version, layout, in/out,
// precision or uniform blocks; `void fragment()`; one `uniform` with inspector hints per runtime
// param; the source texture, the texture coordinate, the output colour and crtforge's builtins
// mapped to TEXTURE/SCREEN_TEXTURE, UV/SCREEN_UV, COLOR and TEXTURE_PIXEL_SIZE/SCREEN_PIXEL_SIZE/TIME.
#pragma once

#include <map>
#include <string>

#include <spirv_cross/spirv_glsl.hpp>

#include "crtforge/variant.hpp"
#include "targets/godot/godot_writer.hpp"

namespace crtforge::godot {

class GodotCompiler : public spirv_cross::CompilerGLSL {
public:
    GodotCompiler(std::vector<uint32_t> spirv, const Variant& variant, const godot::Options& options);

    // The whole shader in Godot's dialect (may throw spirv_cross::CompilerError).
    std::string compile_godot();

protected:
    void emit_header() override;
    void emit_function_prototype(spirv_cross::SPIRFunction& func, const spirv_cross::Bitset& return_flags) override;

private:
    static constexpr const char* kBlockMarker = "crtforge_params_block";
public:
    // The time reduced by the host (shader_time()); negative (the default): TIME.
    static constexpr const char* kHostTime = "hostTime";
private:
    void prepare();  // remaps resources onto Godot builtins
    std::string uniform_declaration(const VariantParam& p) const;
    std::string builtin_expression(const std::string& member) const;
    static std::string with_loop_increments(const std::string& text);  // Godot 3's for-loop syntax
    static std::string with_screen_reads_flipped(const std::string& text);  // Godot 3's bottom-up screen
    bool screen_mode() const { return options_.mode == Mode::Screen; }
    const Variant& variant_;
    godot::Options options_;
    std::map<std::string, std::string> member_expressions_;  // block member -> Godot expression  // qualified: CompilerGLSL has its own nested Options
    std::vector<std::string> bool_members_;  // block members that are bool params (a uint in SPIR-V)
};

}  // namespace crtforge::godot
