// One RetroArch pass as a crtforge program form: the .slang's two stages rewritten to crtforge's
// binding conventions, so the pass runs on every host crtforge has, with nothing RetroArch-specific
// left for a host to know.
//
// What changes (token by token; everything else, macros included, stays as written):
//  - The push-constant block and the UBO go. Each member read becomes an expression of what crtforge
//    provides: a #pragma parameter -> the preset's param of that name (a uniform or a baked constant);
//    MVP -> the constant orthographic matrix RetroArch passes (0..1 onto clip space);
//    SourceSize, OutputSize, FinalViewportSize -> vec4(size, 1 / size) of the sourceSize, outputSize,
//    viewportSize builtins; FrameCount -> the frameCount builtin (already reduced by the pass's
//    frame_count_mod); <texture>Size -> the size of that texture, read with textureSize() (the
//    texture is bound to the pass for it); FrameDirection, CurrentSubFrame, TotalSubFrames -> 1;
//    Rotation -> 0; OriginalFPS, FrameTimeDelta -> the scene's fps; OriginalAspect(Rotated) -> the
//    original's width / height; any other member -> 0 of its type (RetroArch leaves it unset).
//  - Sampler declarations go: crtforge declares the pass's textures. `Source` is the main input
//    (crtforge's `source`); any other sampler must name a texture the preset provides.
//  - The vertex stage's inputs (location 0: the position, 1: the texture coordinate, whatever their
//    names) become globals that a generated main() sets for crtforge's full-screen triangle before
//    calling the shader's own main(): the quad RetroArch draws, as one triangle over the same plane.
//  - The pass that draws what RetroArch shows writes alpha 1 (ProgramContext::opaque_output).
//  - Identifiers the rewrite introduces (source, the builtins, the params) are renamed where the
//    shader already used them for something else.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spec.hpp"
#include "generator/retroarch/slang_source.hpp"

namespace crtforge::retroarch {

struct ProgramContext {
    // The textures the preset provides to the pass by RetroArch's names (Original, OriginalHistory#,
    // PassOutput#, PassFeedback#, aliases, <alias>Feedback, LUTs): name -> crtforge source.
    const std::map<std::string, std::string>& textures;
    // Every parameter of the preset: RetroArch id -> crtforge param name.
    const std::map<std::string, std::string>& params;
    double fps = 60.0;
    // The pass draws the picture RetroArch shows: its alpha is set to 1, as RetroArch's display
    // ignores it (crtforge's display keeps it).
    bool opaque_output = false;
};

struct TranslatedProgram {
    std::string vertex, fragment;     // crtforge program texts (no #version: the assembler adds it)
    std::vector<std::string> params;  // RetroArch ids the pass reads, in first-use order
    std::set<Builtin> builtins;
    std::vector<std::string> textures;  // textures besides Source, in first-use order
};

Result<TranslatedProgram> translate_program(const SlangSource& source, const ProgramContext& context);

}  // namespace crtforge::retroarch
