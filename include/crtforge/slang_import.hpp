// RetroArch's shader presets (.slangp + .slang) as crtforge presets: `crtforge import`.
//
// An imported preset is a template overlay (TemplateLibrary::load on a folder without prelude.glsl):
//   stages/<stage>.toml            one program stage (kind = "program"): the preset's #pragma
//                                  parameters as params, one form per pass
//   stages/<stage>/passN.vert|frag each pass's program, rewritten to crtforge's bindings
//                                  (generator/retroarch/slang_program.hpp says how)
//   presets/<name>.toml            the scene: passes, scales, formats, textures and how each is
//                                  sampled, LUTs, parameter values
//   presets/<name>/<lut file>      the LUT images, as they were
// so `crtforge --templates DIR export --preset <name>` and every other command take it like a
// preset of crtforge's own. docs/retroarch.md maps each .slangp key and semantic onto the model.
#pragma once

#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"

namespace crtforge {

// What a .slangp does not say: RetroArch's settings, and where the result goes.
struct SlangImportOptions {
    std::string root;                     // no file read may leave this folder ("" = no limit)
    std::string name;                     // the crtforge preset's name ("" = from the file name)
    Filter unset_filter = Filter::Nearest;  // a texture whose filter the preset leaves unset: RetroArch's video_smooth (off)
    int source_width = 0, source_height = 0;  // [source] size (0: the input's own)
    DisplayFit fit = DisplayFit::Aspect;      // how the screen sits in the display (RetroArch: aspect-correct)
    double fps = 60.0;
};

struct ImportedFile {
    std::string path;  // relative to the overlay folder
    std::string data;
};

struct ImportedPreset {
    std::string name;                   // the crtforge preset
    std::string stage;                  // its program stage
    size_t passes = 0;                  // RetroArch's passes (the scene may add the copy to the viewport)
    std::vector<ImportedFile> files;
    std::vector<std::string> warnings;  // "file:line: warning: ..." (what RetroArch ignores or approximates)
    std::vector<std::string> inputs;    // every file read (.slangp chain, shaders, includes, LUTs)
};

// A preset name from a .slangp's file name: lower case, '-' for anything but letters, digits, '_';
// over 64 characters, its start and a hash of the whole.
std::string imported_preset_name(const std::string& slangp_path);

Result<ImportedPreset> import_slangp(const std::string& slangp_path, const SlangImportOptions& options);

// Writes the files under `dir` (created if missing), all or nothing: into a staging folder beside
// it first, then moved into place; a file that exists already is replaced.
Status write_imported_preset(const ImportedPreset& preset, const std::string& dir);

}  // namespace crtforge
