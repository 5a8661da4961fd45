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

Result<CompiledVariant> compile_variant(const TemplateLibrary& library, const Preset& preset,
                                        const VariantOptions& options, const Cache& cache);

// Emits one target (using the cache for the text).
Result<TargetOutput> emit_target(const CompiledVariant& compiled, TargetId target,
                                 const Cache& cache);

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

// Writes files under dir atomically per file; refuses to write anything if dir cannot be created.
Status write_files(const std::string& dir, const std::map<std::string, std::string>& files);

// Relative path of one exported file: "<target>/<preset><suffix>".
std::string export_path(const std::string& preset, TargetId target, const std::string& suffix);

}  // namespace crtforge
