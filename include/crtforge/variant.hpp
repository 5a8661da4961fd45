// A variant: one pass of a resolved preset plus build options — which params are baked as
// constants and which stay runtime uniforms, and the float precision. A single-pass preset is one
// variant; a scene has one per pass.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/template_library.hpp"

namespace crtforge {

enum class Precision { High, Medium };
const char* precision_name(Precision precision);

// How params are split between baked constants and uniforms.
struct UniformSelection {
    // Uber: not a specialised shader at all — every stage of the library the pass can feed, each
    // behind its int switch uniform (StageSpec::stage_switch: 0 off, k its k-th form), every param
    // a uniform: one shader for every preset, branching at run time (what "only what the scene
    // needs" saves is measured against it).
    enum class Mode { Default, All, None, Names, Uber } mode = Mode::Default;
    std::vector<std::string> names;  // Mode::Names only

    // Parses the CLI syntax: "default", "all", "none", "uber" or "NAME,NAME,...".
    static Result<UniformSelection> parse(const std::string& text);
    std::string str() const;
};

struct VariantOptions {
    UniformSelection uniforms;
    Precision precision = Precision::High;
    // false: each pass as glslang makes it, with no spirv-opt and no pow reduction — how RetroArch
    // compiles a .slang pass (the baseline `crtforge bench --versus-retroarch` times export against).
    bool optimize = true;
    // Each SSA value keeps its template local's name (spirv_debug_names): what the text emitters
    // print. It costs spirv-opt a second run; a render from the SPIR-V alone (the Vulkan-only
    // sweep) needs no names and gets the same instructions without them.
    bool local_names = true;
    // A program's baked params as specialization constants (BakedParams::Specialized), for a
    // render from the SPIR-V alone (the Vulkan-only sweep): presets that share a pass's text then
    // share its optimisation. Where the program needs them as constants, it falls back.
    bool specialize_baked = false;
};

struct VariantParam {
    const ParamSpec* spec = nullptr;
    const StageSpec* stage = nullptr;
    Value value;        // the preset's value: the constant when baked, the default when uniform
    bool uniform = false;
};

// A stage as the shader holds it: one form in a specialised shader; in the uber-shader every form
// the pass can feed, chosen at run time by the stage's switch.
struct VariantStage {
    const StageSpec* stage = nullptr;
    std::vector<const FormSpec*> forms;
    bool switched = false;  // behind stage->stage_switch (the uber-shader)
    int switch_value(const FormSpec* form) const;  // 1 + index of `form` in the stage's forms
};

struct Variant {
    const Preset* preset = nullptr;
    const Pass* pass = nullptr;         // the pass this variant draws
    size_t pass_index = 0;
    VariantOptions options;
    std::vector<VariantParam> params;   // every param the enabled forms read, in pass order
    std::vector<Builtin> builtins;      // builtins in the uniform block, in declaration order
    std::vector<VariantStage> stages;    // what the shader holds, in pass order
    // Textures besides `source`, bound at 2, 3, ... in this order (the pass's texture_names()).
    std::vector<std::string> textures;

    bool has_uniform_block() const;
    bool uber() const { return options.uniforms.mode == UniformSelection::Mode::Uber; }
    // What the pass's files are named after: the preset ("classic") for a single-pass preset, the
    // preset and the pass alias ("super-win.trails") in a scene of several passes.
    std::string file_stem() const;
    // The filter the pass samples a texture with ("source" or a name in `textures`).
    Filter texture_filter(const std::string& name) const;
    std::vector<const VariantParam*> uniforms() const;
    std::vector<const VariantParam*> baked() const;
    // The param the time builtin is multiplied by (role = "angular_speed"), if the pass has one:
    // hosts reduce time by its period (shader_time() in uniforms.hpp). A pass has at most one.
    const VariantParam* angular_speed() const;
    // Whether a stage of the pass sets the output's alpha (a form with an alpha hook).
    bool writes_alpha() const;
    // The whole-program form (an imported RetroArch pass: its own vertex and fragment stage) the
    // pass is made of, or nullptr for a pass of snippet stages.
    const FormSpec* program_form() const;
    // The textures the pass samples clamp_to_border, by binding ("source" or a name in
    // `textures`): true where it samples them linearly. Targets without a border colour (WebGPU,
    // Godot) fade these samples in the shader.
    std::map<std::string, bool> clamp_to_border_inputs() const;
};

// Default: params whose spec says runtime = true stay uniforms, all others are baked.
// All: every runtime-capable param is a uniform. None: everything baked.
// Names: exactly the listed params are uniforms; each must be runtime-capable and used.
// Uber: every stage the pass can feed (its forms' textures bound by the pass), every param a uniform
// (runtime = true or not), and each stage's switch set to the pass's form (0 where it is off).
Result<Variant> make_variant(const TemplateLibrary& library, const Preset& preset,
                             const VariantOptions& options, size_t pass_index = 0);

}  // namespace crtforge
