// Versioned preset files. Format 2 is the current layout (stages, passes, scene tables). Format 1
// is the Glitch layout the CRT-effect document migrates from ("Migration from Glitch"): a
// [glitch] table with the CRT features Glitch used to carry. A format-1 file is read into the
// format-2 model, with one warning per migrated key naming the file, line and key.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

#include "crtforge/preset.hpp"
#include "crtforge/template_library.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge::detail {

constexpr int kPresetFormat = 2;

// The file's format: `format = N` when given (1..kPresetFormat), else 1 when it has a [glitch]
// table, else the current one.
Result<int> preset_format(const TomlReader& r, const toml::table& root);

// Fills `file` (name and doc already read) from a format-1 file's [glitch] table:
//   crtEnabled + curvature       -> stages.curvature (crt_effect form) with curvature
//   vignetteEnabled              -> stages.vignette (crt_effect form, the document's exponent)
//   overlayMode = "scanlines" + overlayIntensity, overlaySpacing
//                                -> stages.scanlines (crt_effect form) with scanlineIntensity, scanlineSpacing
// on top of the CRT effect's defaults (base "crt-shadow-mask") with the stages Glitch did not
// have (the phosphor mask, the pulse) off, so the migrated preset looks as it did. Glitch's own
// effects (analog, digital, vhs, datamosh, slices, bands, block mask, jitter, block multiply)
// stay with Glitch: crtforge has none, and says so.
Status migrate_glitch_preset(const TomlReader& r, const toml::table& root, const TemplateLibrary* library, PresetFile& file);

}  // namespace crtforge::detail
