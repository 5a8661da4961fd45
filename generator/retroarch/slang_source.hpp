// One RetroArch `.slang` shader file, read the way RetroArch reads it (gfx/drivers_shader/
// glslang_util.c: glslang_read_shader_file; slang_process.cpp: glslang_parse_meta and
// build_stage_source), with every problem a one-line Diagnostic at its file and line.
//
// What RetroArch does, and what this does:
//  - Every '\r' is removed (CRLF files read as LF); a UTF-8 byte order mark is dropped (RetroArch
//    would refuse the file: its first line would not start with "#version ").
//  - The first line must start with "#version " (field "version").
//  - A line starting, in its first column, with `#include "file"` or `#pragma include_optional
//    "file"` is replaced by that file's lines, resolved relative to the including file, recursively;
//    an included file has no #version line. A missing optional include is skipped; a missing
//    #include is an error at the #include's line (field "include"). RetroArch does not consider
//    the preprocessor (an #include inside `#if 0` is still read) and loops forever on a cycle;
//    here a cycle, nesting over kMaxIncludeDepth, a file over 4 MiB, an expansion over
//    kMaxExpandedBytes and a file outside `root` are errors. An indented `#include` is not expanded
//    (RetroArch leaves it to glslang, which refuses it).
//  - Metadata pragmas are read from every line (stage sections do not matter), each only in its
//    first column and with a space after the keyword, as RetroArch matches them:
//      #pragma name NAME           one per file, one word; the pass's alias when the preset gives none
//      #pragma format FORMAT       one per file; one of RetroArch's 30 formats (R8G8B8A8_UNORM ...)
//      #pragma parameter ID "DESCRIPTION" INITIAL MINIMUM MAXIMUM [STEP]
//    A parameter's ID is 1..63 characters without blanks and its description (possibly empty) at most
//    63 bytes between double quotes — RetroArch refuses longer ones. Each number is the longest
//    prefix strtod() reads (so "1.0'" is 1.0 and "0.0.001" is 0.0 followed by .001), blanks between
//    them optional; text after the fourth number is ignored; a missing or unreadable STEP is
//    0.1 * (MAXIMUM - MINIMUM) (has_step false). The same ID twice is kept once when description and
//    numbers (compared as RetroArch's floats) match, and an error naming both places otherwise.
//  - `#pragma stage vertex` / `#pragma stage fragment` (the whole line, exactly) switch the stage
//    the following lines belong to; lines before the first belong to both, and several sections of
//    one stage concatenate. Any other `#pragma stage ...` line is an error here (RetroArch silently
//    drops the code after it from both stages). A stage with no section is an error.
//  - Stage text: the #version line, `#extension GL_GOOGLE_cpp_style_line_directive : require`, then
//    the stage's lines with `#line N "file"` directives so that glslang reports the original file
//    and line. The stage, name, format and parameter pragmas are left out; other pragmas stay.
//    glslang reads the #line file name verbatim (no escapes), so a path containing '"' or a control
//    character is refused. RetroArch also defines _HAS_ORIGINALASPECT_UNIFORMS,
//    _HAS_FRAMETIME_UNIFORMS and _HAS_SENSOR_UNIFORMS after #version; this does not (a caller that
//    provides those uniforms adds the defines).
#pragma once

#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spec.hpp"

namespace crtforge::retroarch {

constexpr int kMaxIncludeDepth = 32;
constexpr size_t kMaxExpandedBytes = 16u << 20;

struct SlangParameter {
    std::string id, description;
    // As written (strtod's doubles); RetroArch keeps floats, which is how duplicates are compared.
    double initial = 0, minimum = 0, maximum = 0, step = 0;
    bool has_step = false;  // false: step is RetroArch's default 0.1 * (maximum - minimum)
    SourceLocation where;   // the .slang (or included) file and line of the pragma
};

struct SlangSource {
    std::string path;              // as given
    std::string vertex, fragment;  // GLSL for glslang, one per stage
    std::string name;              // #pragma name (empty if none)
    std::string format;            // #pragma format (empty if none), e.g. "R16G16B16A16_SFLOAT"
    std::vector<SlangParameter> parameters;  // in order of appearance, each id once
    // Every file read (the shader, then its includes in the order first read), for staleness hashes.
    std::vector<std::string> files;
    // `#pragma include_optional` files that were absent (skipped): a staleness check must also notice
    // one of them appearing.
    std::vector<std::string> missing_optional;
};

// `root`: no file read (the shader or an #include) may resolve outside this folder (after resolving
// `..` and symlinks); "" = no limit.
Result<SlangSource> load_slang_source(const std::string& path, const std::string& root);

}  // namespace crtforge::retroarch
