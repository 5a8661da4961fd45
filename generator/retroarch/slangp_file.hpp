// One RetroArch `.slangp` preset with its `#reference` chain, read the way RetroArch reads it
// (libretro-common/file/config_file.c for the syntax, gfx/video_shader_parse.c for the meaning), with
// every problem a one-line Diagnostic at its file, line and key.
//
// Syntax (config_file.c: config_file_parse_line, config_file_strip_comment, config_file_extract_value):
//  - `key = value` lines; the key is a run of printable non-blank ASCII; the value is either a
//    double-quoted string (up to the next '"') or a run of printable non-blank characters. Blanks are
//    needed around '=' on the key's side: RetroArch reads `key=value` as a key without a value and
//    drops the line, so here it is an error. Lines without '=' are errors too (RetroArch drops them
//    silently; two corpus presets lose a parameter override that way).
//  - A line starting with '#' in the first column is a comment, except `#reference "path"` and
//    `#include "path"`. Elsewhere '#' starts a comment unless it lies inside a quoted value. `//`
//    lines and `/* ... */` blocks are comments here; RetroArch has no comment syntax besides '#' but
//    drops such lines because they are not `key = value` — a `key = value` line inside a block would
//    be read by RetroArch, so it is an error here. Text after a value is ignored, as by RetroArch,
//    with a warning unless it is a comment; so is a missing closing quote (the value runs to the end
//    of the line). An indented `#reference` (which RetroArch ignores) is an error.
//  - The same key twice in one file: the first wins (RetroArch's entry map keeps the first); the
//    later one is reported in `warnings`.
//  - Booleans are exactly `true`, `false`, `1` or `0` (RetroArch treats anything else as unset;
//    here it is an error). Numbers are in C float syntax; `shaders` and `frame_count_mod` are
//    unsigned integers as strtoul(…, 0) reads them (0x… hexadecimal, a leading 0 octal). An empty
//    value (`key = ""`) is the key not given, except where a value is required.
//  - `#include "path"` (relative to the file) reads that file's entries at that point, first value
//    still winning; its own `#reference` lines are ignored, as in RetroArch (reported in warnings).
//    Include nesting is bounded at 16 (RetroArch silently stops there; here it is an error).
//
// Keys read from the preset that holds the passes (see #reference below):
//   shaders (1..64), shaderN (N < shaders, required), aliasN, filter_linearN, wrap_modeN,
//   mipmap_inputN, float_framebufferN, srgb_framebufferN, frame_count_modN, scale_typeN,
//   scale_type_xN, scale_type_yN, scaleN, scale_xN, scale_yN, textures ("A;B", empty entries
//   skipped, at most 64), per texture NAME (its path, required), NAME_linear, NAME_mipmap,
//   NAME_wrap_mode. Values are kept as written; RetroArch's interpretation (video_shader_parse_pass):
//   scale_typeN, when given, sets both axes and hides scale_type_xN/_yN; with no scale type at all the
//   pass has no scale (RetroArch: source x1, the last pass the viewport) and scaleN/scale_xN/scale_yN
//   are ignored; scaleN, when given, hides scale_xN/scale_yN; an `absolute` scale is read as an
//   integer (strtol: "572.0" is 572). A bad scale_type is an error (as in RetroArch). A bad wrap mode
//   falls back to RetroArch's default, clamp_to_border, with a warning (RetroArch does the same; one
//   corpus preset writes `clamp`). Pass keys with N >= shaders are ignored (warned).
//   Ignored (RetroArch's slang drivers do not use them): `feedback_pass` (legacy GL/Cg feedback; the
//   slang way is the PassFeedback semantic) and `parameters` (the list RetroArch writes; on loading
//   it applies any `ID = value` whose ID is a shader parameter, listed or not).
//   Every other `key = value` whose value is a number is a candidate parameter override, matched by
//   the caller against the passes' #pragma parameters (RetroArch: video_shader_load_current_parameter_
//   values / video_shader_override_values apply an entry whose key is a parameter ID). Keys of the
//   forms above (e.g. `scale_type_0`, `texture_wrap_mode12`: typos RetroArch ignores) never are.
//
// #reference (video_shader_parse.c: video_shader_load_preset_into_shader and helpers):
//  - `#reference "path"` is relative to the file that has it. The preset holding the passes, the
//    "root", is found by following each file's FIRST #reference until a file without any; RetroArch
//    stops after 16 steps (SHADER_MAX_REFERENCE_DEPTH); here a cycle is named as such and more than
//    16 steps is an error. The root must have `shaders`. Its passes, pass settings and textures (with
//    their _linear/_mipmap/_wrap_mode) are the preset's: `shaders`, pass keys and texture settings in
//    a file that has a #reference are ignored (warned).
//  - Overrides: all files of the reference graph are visited depth first, each file's references in
//    order before the file itself (video_shader_gather_reference_path_list), and each one's values
//    applied in that order: parameter values, and texture paths for textures the root lists (resolved
//    relative to the file that gives them). So a file beats everything it references, and a later
//    #reference line beats an earlier one.
//  - Several #reference lines: the first leads to the passes; the others of the loaded file must lead
//    (through their first references) to presets without `shaders` — parameter/texture overrides
//    only; one leading to a full preset is an error, as in RetroArch.
//  - RetroArch replaces $WILDCARD$ tokens in paths (core name, game, rotation...) when the replaced
//    file exists; there is no such context here, so paths are taken literally.
// Every file named (references, includes, shaders, textures) must exist and resolve inside `root`.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spec.hpp"

namespace crtforge::retroarch {

constexpr int kMaxShaderPasses = 64;     // RetroArch's GFX_MAX_SHADERS
constexpr int kMaxTextures = 64;         // GFX_MAX_TEXTURES
constexpr int kMaxReferenceDepth = 16;   // SHADER_MAX_REFERENCE_DEPTH
constexpr int kMaxPresetIncludeDepth = 16;  // config_file.c's MAX_INCLUDE_DEPTH

struct SlangpPass {
    std::string shader;  // resolved path of shaderN (relative to the .slangp that named it)
    std::string alias;
    std::optional<bool> filter_linear, mipmap_input, float_framebuffer, srgb_framebuffer;
    std::optional<std::string> wrap_mode;  // clamp_to_border | clamp_to_edge | repeat | mirrored_repeat
    std::optional<int> frame_count_mod;
    std::optional<std::string> scale_type, scale_type_x, scale_type_y;  // source | viewport | absolute
    std::optional<double> scale, scale_x, scale_y;
    SourceLocation where;                             // where shaderN was given
    std::map<std::string, SourceLocation> key_lines;  // e.g. "scale_type" -> where scale_type0 was given
};

struct SlangpTexture {
    std::string name, path;  // path resolved relative to the file that gave it (a referencing file may override it)
    std::optional<bool> linear, mipmap;
    std::optional<std::string> wrap_mode;
    SourceLocation where;  // where the path was given
};

struct SlangpPreset {
    std::string path;
    std::vector<SlangpPass> passes;
    std::vector<SlangpTexture> textures;  // in `textures = "A;B"` order
    // Candidate parameter value overrides, in order of first appearance, each id once, after the
    // whole #reference chain; the caller keeps those that name a #pragma parameter of a pass (a
    // value may be inf or nan: RetroArch's strtod reads them; the caller refuses them).
    std::vector<std::pair<std::string, double>> parameters;
    std::map<std::string, SourceLocation> parameter_lines;
    // Keys written with an empty value (`P1 =`) that are no preset key: if one names a shader
    // parameter, the importer refuses it (an empty value is a mistake, not the value left out).
    std::map<std::string, SourceLocation> empty_values;
    std::vector<std::string> files;      // every preset file read (the chain, and #include'd files)
    // What RetroArch accepts but ignores or replaces by a default. Diagnostic::str() says "error:";
    // a caller printing these words them as warnings itself.
    std::vector<Diagnostic> warnings;
};

Result<SlangpPreset> load_slangp(const std::string& path, const std::string& root);

}  // namespace crtforge::retroarch
