// The export pipeline: presets x targets -> files in memory -> (only when everything succeeded)
// files on disk plus manifest.json. Also the single-variant path behind `crtforge generate`.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "crtforge/cache.hpp"
#include "crtforge/diagnostic.hpp"
#include "crtforge/reflection.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

// One compiled variant: its GLSL 450 assembly, SPIR-V pair and reflection.
struct CompiledVariant {
    Variant variant;
    std::string fragment_glsl;
    SpirvBinary fragment, vertex;
    Reflection reflection;
};

// One pass of a preset (the only pass of a single-pass preset).
Result<CompiledVariant> compile_variant(const TemplateLibrary& library, const Preset& preset,
                                        const VariantOptions& options, const Cache& cache, size_t pass_index = 0);

// Every pass of a preset, in order.
Result<std::vector<CompiledVariant>> compile_scene(const TemplateLibrary& library, const Preset& preset,
                                                   const VariantOptions& options, const Cache& cache);

// Emits one target (using the cache for the text).
Result<TargetOutput> emit_target(const CompiledVariant& compiled, TargetId target,
                                 const Cache& cache);

// Every pass of a compiled scene emitted for one target, in order.
Result<std::vector<TargetOutput>> emit_scene(const std::vector<CompiledVariant>& passes, TargetId target, const Cache& cache);

struct ExportRequest {
    std::vector<std::string> presets;  // empty = all
    std::vector<TargetId> targets;     // empty = all
    VariantOptions options;
};

// Everything an export writes, keyed by path relative to the output dir (sorted, so writing and
// listing are deterministic).
struct ExportResult {
    std::map<std::string, std::string> files;  // includes "manifest.json"
    unsigned variants = 0;
};

Result<ExportResult> run_export(const TemplateLibrary& library, const ExportRequest& request,
                                const Cache& cache);

// The npm package that `crtforge export --preset <name> --target wgsl` writes as npm/ (paths
// relative to it: package.json, index.mjs, crt-webgpu.mjs, manifest.json, wgsl/, luts/, ...), from
// the preset's compiled passes and their emitted WGSL: what validate's Dawn consumer loads.
Result<std::map<std::string, std::string>> preset_web_package(const Preset& preset, const std::vector<CompiledVariant>& passes,
                                                              const std::vector<TargetOutput>& wgsl);
// Writes files under dir atomically per file; refuses to write anything if dir cannot be created.
Status write_files(const std::string& dir, const std::map<std::string, std::string>& files);

// An export as a whole (generator/export_dir.cpp): `files` are written into a staging directory
// beside `out` and swapped in, so `out` holds exactly them (no stale file of an earlier export)
// or, on any failure, what it held before. A second export to the same `out` while one runs fails
// clearly (a lock the kernel releases if the process dies); an interrupted run's leftovers are
// cleaned, or put back, by the next. A non-empty `out` that is not an earlier export (no
// manifest.json) is refused rather than replaced. Nothing is written when `out` already holds
// exactly `files`.
Status write_export(const std::string& out, const std::map<std::string, std::string>& files);

// Relative path of one exported file: "<target>/<stem><suffix>" (stem: Variant::file_stem()).
std::string export_path(const std::string& stem, TargetId target, const std::string& suffix);

// A file LUT's path: as written when absolute, else relative to the preset file's folder.
std::string lut_file_path(const LutSpec& lut);

// A preset's LUT files by LUT name: generated ones as PNG, file ones as they are.
Result<std::map<std::string, std::string>> lut_files(const Preset& preset);

// The target's whole-scene files for a preset (TargetInfo::generate_scene; none when it has no
// scene generator), from every pass's variant and emitted files. Paths are under the target's folder.
Result<std::vector<OutputFile>> generate_target_scene(TargetId target, const Preset& preset,
                                                      const std::vector<CompiledVariant>& passes,
                                                      const std::vector<TargetOutput>& outputs,
                                                      const std::map<std::string, std::string>& luts);

// Relative path of a preset's LUT file: "luts/<preset>.<lut>.png" (or the source file's extension).
std::string lut_export_path(const Preset& preset, const LutSpec& lut);

}  // namespace crtforge
