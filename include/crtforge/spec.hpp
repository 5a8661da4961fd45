// The effect-spec model: stages, their formula variants ("forms") and their params.
// Loaded from templates/stages/<stage>.toml; the GLSL lives beside it in <stage>.glsl.
#pragma once

#include <optional>
#include <map>
#include <string>
#include <vector>

#include "crtforge/value.hpp"

namespace crtforge {

struct SourceLocation {
    std::string file;
    int line = 0;
};

// What a param means to code outside its stage, declared in the spec (`role = "..."`) so that no
// emitter has to recognise a param by its name.
enum class ParamRole {
    None,
    // A rate in radians per second that the stage multiplies by the time builtin: a host whose
    // clock wraps (Godot's TIME) keeps the phase continuous by rounding the rate to whole turns
    // per wrap. Float params of a form that reads `time` only.
    AngularSpeed,
};
const char* param_role_name(ParamRole role);  // "", "angular_speed"

struct ParamSpec {
    std::string name;                      // valid GLSL identifier, unique across all stages
    ParamType type = ParamType::Float;
    std::optional<double> min, max;        // float/int only
    std::optional<double> step;            // optional UI step (Godot hint_range)
    std::vector<std::string> enum_values;  // enum only
    Value default_value;
    std::string unit;                      // "px", "uv", "" ...
    std::string doc;                       // one line
    bool runtime = false;                  // may stay a runtime uniform (modulation candidate)
    ParamRole role = ParamRole::None;
    SourceLocation where;

    int enum_index(const std::string& name) const;  // -1 if not a value of this enum
};

// The hooks of the fixed pass order in the generated main(): each form may provide one function
// per hook. Order inside a hook follows StageSpec::order. Signatures:
//   warp:      vec2 f(vec2 uv)                 — moves the texture coordinate (curvature)
//   sample_uv: vec2 f(vec2 uv, CrtFrag frag)   — where the source is read (mask cell quantising)
//   fetch:     vec3 f(vec3 color, vec2 uv)     — reads the source (aberration, bloom taps)
//   color:     vec3 f(vec3 color, CrtFrag frag) — shapes the colour (scanlines, mask, vignette...)
//   finish:    vec3 f(vec3 color, CrtFrag frag) — runs after every color hook (bezel clamp)
//   alpha:     float f(float alpha, CrtFrag frag) — the output's alpha, 1 unless a stage sets it
//              (a transparent bezel); straight, not premultiplied
enum class Hook { Warp, SampleUv, Fetch, Color, Finish, Alpha };
const char* hook_name(Hook hook);
constexpr Hook kAllHooks[] = {Hook::Warp, Hook::SampleUv, Hook::Fetch, Hook::Color, Hook::Finish, Hook::Alpha};
constexpr int kHookCount = 6;

// Values the generated code reads from the host besides params.
//   outputSize  vec2   the pass's output size in pixels (the screen's rectangle for the last pass)
//   sourceSize  vec2   the main input's size in texels
//   time        float  seconds since the first frame: frame / fps
//   frameCount  int    frames since the first, modulo the pass's frame_count_mod when it has one
//   viewportSize vec2  the screen's rectangle in the display, in pixels: what the last pass draws
//                      (RetroArch's FinalViewportSize), the same in every pass
enum class Builtin { OutputSize, SourceSize, Time, FrameCount, ViewportSize };
constexpr Builtin kAllBuiltins[] = {Builtin::OutputSize, Builtin::SourceSize, Builtin::Time, Builtin::FrameCount, Builtin::ViewportSize};
const char* builtin_name(Builtin builtin);  // the uniform member name: outputSize, sourceSize, time, frameCount, viewportSize
const char* builtin_doc(Builtin builtin);   // one line for generated code and the manifest
bool parse_builtin(const std::string& text, Builtin& out);

struct FormSpec {
    std::string name;                      // e.g. "atari"
    std::string doc;                       // which document and formula
    std::vector<std::string> params;       // params this form reads (besides always-on stage params)
    std::vector<Builtin> builtins;         // builtins this form reads (outputSize is always present)
    // Textures this form samples besides `source` (the pass's main input): each a sampler2D of
    // that name, bound by the preset's pass to a pass output, feedback, history or LUT.
    std::vector<std::string> textures;
    // The size a texture must have, where the form's code reads it as a fixed layout (a 32^3 cube
    // stored 1024 x 32): a LUT of another size bound to it is refused, not sampled as garbage.
    std::map<std::string, std::pair<int, int>> texture_sizes;
    std::string functions[kHookCount];     // indexed by Hook; empty = none
    // The point-sampled form this one is the filtered quality tier of (empty: none): the same params
    // meaning the same picture, averaged over each output pixel's footprint so that fine patterns do
    // not alias. Presets select it like any form; bench and budget mode offer it as the "filtered" tier.
    std::string quality_of;
    // A program form (its stage's `kind = "program"`): a whole vertex + fragment program instead of
    // hook functions, each file GLSL 450 without #version, declaring its own inputs and outputs and
    // reading the pass's uniform block, constants and samplers as a snippet does (the assembler
    // declares them). An imported RetroArch pass is one (crtforge import).
    std::string vertex_path, vertex_source, fragment_path, fragment_source;
    bool program() const { return !fragment_path.empty(); }
    SourceLocation where;
};

struct StageSpec {
    std::string name;             // e.g. "scanlines"
    std::string doc;
    int order = 0;                // position in the CRT-effect document's pass order
    std::string selector;         // enum param choosing the form; empty when there is one form
    std::vector<std::string> common_params;  // params every form of this stage reads
    std::vector<ParamSpec> params;
    std::vector<FormSpec> forms;
    // "program": each form is a whole program (FormSpec::vertex_source/fragment_source), a pass
    // runs it alone, and the stage has no place in the pass order (`order` 0). Its params are its
    // own namespace (another program stage may use the same names: they never share a shader).
    bool program = false;
    std::string glsl_path;        // the snippet file
    std::string glsl_source;      // its text
    SourceLocation where;
    // The uber-shader's (--uniforms uber) int uniform choosing what the stage does at run time:
    // 0 off, k the k-th form. Made by the loader ("crtStage_<name>"); no specialised shader has it.
    ParamSpec stage_switch;

    const ParamSpec* find_param(const std::string& name) const;
    const FormSpec* find_form(const std::string& name) const;
};

}  // namespace crtforge
