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

// A varying of a program pass (an imported RetroArch shader): what its vertex stage writes at a
// location, which its fragment stage reads under the same name.
struct Varying {
    uint32_t location = 0;
    std::string declaration;  // "varying flat vec2 noise_div;"
    std::string name;
    // Godot 3 has no integer varyings: an int / uint (vector) travels as the float (vector) of its
    // value in `crt_carried_<name>`, and each stage keeps a local `<integer_type> <name>`.
    std::string integer_type;  // "int", "ivec2", "uint", ...: empty where the varying is carried as it is
    std::string carrier_type;  // "float", "vec2", ...
    std::string carrier() const { return "crt_carried_" + name; }
};

// The module rewritten into types Godot's language has (throws spirv_cross::CompilerError naming
// what cannot be): arrays of arrays flattened (spirv_flat_arrays), non-square matrices padded
// (spirv_square_matrices), and for Godot 3, loops unrolled where a vector is indexed by a variable
// (spirv_constant_indices). Run once per module; GodotCompiler takes its result.
std::vector<uint32_t> in_godot_types(std::vector<uint32_t> words, int godot_version);

class GodotCompiler : public spirv_cross::CompilerGLSL {
public:
    // `spirv`: a module in_godot_types() rewrote. `stage`: Fragment for fragment() (with the
    // header), Vertex for a program pass's vertex().
    GodotCompiler(std::vector<uint32_t> spirv, const Variant& variant, const godot::Options& options,
                  ShaderStage stage = ShaderStage::Fragment, std::vector<Varying> varyings = {});

    // The whole shader in Godot's dialect (may throw spirv_cross::CompilerError); for the vertex
    // stage, its functions only.
    std::string compile_godot();
    // Vertex stage: the varyings it writes, by location (valid after compile_godot()).
    const std::vector<Varying>& varyings() const { return varyings_; }
    // Vertex stage of a pass whose fragment stage reads gl_FragCoord: it hands on where the
    // shader's clip position put the corner (kCornerVarying), which the fragment stage's pixel
    // position is rebuilt from.
    void hand_on_corner() { hands_on_corner_ = true; }
    static constexpr const char* kCornerVarying = "crt_corner";

protected:
    void emit_header() override;
    void emit_function_prototype(spirv_cross::SPIRFunction& func, const spirv_cross::Bitset& return_flags) override;
    std::string builtin_to_glsl(spv::BuiltIn builtin, spv::StorageClass storage) override;

private:
    static constexpr const char* kBlockMarker = "crtforge_params_block";
public:
    // The time reduced by the host (shader_time()); negative (the default): TIME.
    static constexpr const char* kHostTime = "hostTime";
private:
    void prepare();  // remaps resources onto Godot builtins
    std::string uniform_declaration(const VariantParam& p) const;
    std::string builtin_expression(const std::string& member) const;
    std::string builtin_expression_fragment_size() const;
    std::string with_format_stored(std::string text) const;  // a pass format Godot's viewports lack
    static std::string with_screen_reads_flipped(const std::string& text);  // Godot 3's bottom-up screen
    bool screen_mode() const { return options_.mode == Mode::Screen; }
    std::string vertex_text(std::string text) const;  // vertex(): RetroArch's quad from UV, moved by the clip position
    // `statements` where vertex() (starting at `body`) ends; refused, saying it cannot `what`, if it returns early.
    static std::string with_vertex_end(std::string text, size_t body, const std::string& statements, const std::string& what);
    // Godot 3: each integer varying's local in vertex() and fragment(), and its float carrier.
    std::string with_integer_varyings_carried(std::string text) const;
    // clamp_to_border emulated in the shader: each read of such a texture times the share inside it.
    std::string with_border_emulated(const std::string& text) const;
    std::map<std::string, bool> border_textures() const;  // Godot name (TEXTURE for the source) -> linear
    // A texture from a pass drawn 2 pixels for 1 (godot::one_pixel_axes): its size queries say 1.
    std::string with_one_pixel_sizes(const std::string& text) const;
    // This pass drawn so: refused where its two pixels could differ (derivatives, mip chains).
    void check_one_pixel_pass() const;
    const Variant& variant_;
    godot::Options options_;
    ShaderStage stage_;
    bool program_ = false;           // the pass is a whole program: varyings, sizes from the host
    bool hands_on_corner_ = false;   // hand_on_corner()
    std::vector<Varying> varyings_;  // the vertex stage's outputs (given to the fragment stage)
    std::map<std::string, std::string> member_expressions_;  // block member -> Godot expression  // qualified: CompilerGLSL has its own nested Options
    std::vector<std::string> bool_members_;  // block members that are bool params (a uint in SPIR-V)
};

}  // namespace crtforge::godot
