// `crtforge corpus DIR`: every RetroArch .slangp under a folder through the whole pipeline — import,
// SPIR-V per pass, each target's emitter and consumer compile per pass, a render of the scene by each
// target's consumer, and that render judged against the Vulkan (SPIR-V) render of the same scene —
// one row per preset, for a dashboard (validate/corpus_report.cpp). Rows hold no timings, so the
// same corpus gives the same report.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "crtforge/cache.hpp"
#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/variant.hpp"
#include "crtforge/validate/validation.hpp"

namespace crtforge {

struct CorpusRequest {
    std::string root;                   // the library's folder (no file read may leave it)
    std::vector<std::string> presets;   // .slangp paths relative to root (list_corpus_presets()), in report order
    std::vector<TargetId> targets;      // spirv first when present: the others are judged against it
    Shard shard;                        // every count-th preset, from index - 1
    unsigned jobs = 1;                  // worker threads
    int source_width = 160, source_height = 120;   // the generated input (pixel_art)
    int display_width = 320, display_height = 240;
    int frame = 2;                      // the frame judged (frames 0..frame run: feedback and history fill)
    double min_psnr = 40.0;             // a target agrees with Vulkan at or above this PSNR
    EngineOptions vulkan;
    bool smooth = false;                // RetroArch's video_smooth for filters the presets leave unset
    std::string retroarch_dir;          // RetroArch's renders (<dir>/<preset path>.png), "" = none
    UniformSelection uniforms;          // which params stay uniforms in every pass (default: all of a preset's, live)
};

// One target's outcome for one preset. The status is the furthest step reached:
//   "refused"  the emitter refused a pass (reason names the construct and its line)
//   "compile"  a pass's file was rejected by the target's consumer
//   "render"   every pass compiled, the scene did not render
//   "differs"  rendered, below min_psnr against Vulkan
//   "agrees"   rendered, at or above it (Vulkan itself: rendered, every pixel finite)
//   "skipped"  an earlier step of the preset failed (import or SPIR-V)
//   "crashed"  the worker process running the preset died (a signal: a driver crash, the OOM killer)
//   "timeout"  the worker running the preset alone wrote no row within the sweep's --preset-timeout
struct CorpusTargetResult {
    std::string status = "skipped";
    size_t passes_compiled = 0;  // passes whose files the consumer accepted
    double psnr = 0;             // against Vulkan, when rendered
    std::string reason;          // the first failure, one line
};

struct CorpusRow {
    std::string preset;              // relative to the root, '/'-separated
    std::string folder;              // its first folder ("." at the top)
    size_t passes = 0;               // RetroArch passes
    std::string import_error;        // "" = imported
    std::string spirv_error;         // "" = every pass compiled to SPIR-V (first failing pass otherwise)
    size_t passes_spirv = 0;         // passes that compiled to SPIR-V
    size_t warnings = 0;             // import warnings (what is ignored or approximated)
    std::map<std::string, CorpusTargetResult> targets;  // by target name
    std::string retroarch = "not run";  // "agrees", "differs", "render" (crtforge's Vulkan failed), "not run"
    double retroarch_psnr = 0;
};

struct CorpusReport {
    std::string root;
    std::vector<std::string> targets;  // names, in column order
    unsigned shard_index = 1, shard_count = 1;
    size_t total_presets = 0;          // in the whole corpus (all shards)
    CorpusRequest settings;
    std::vector<CorpusRow> rows;
};

// Every *.slangp under root (recursively, regular files only, symlinks not followed), relative and
// sorted, so every shard sees the same order.
Result<std::vector<std::string>> list_corpus_presets(const std::string& root);

// (done, total, the row just finished): progress.
using CorpusProgress = std::function<void(size_t, size_t, const CorpusRow&)>;

Result<CorpusReport> run_corpus(const CorpusRequest& request, const Cache& cache, const CorpusProgress& progress = {});

// The presets of the request's shard, in report order; an error when the shard is not 1..count.
Result<std::vector<std::string>> corpus_shard_presets(const CorpusRequest& request);

// A report with no rows yet: the request's root, shard, targets and settings.
CorpusReport empty_corpus_report(const CorpusRequest& request);

// A row of `preset` with every target "skipped": what a run starts from.
CorpusRow corpus_row_for(const CorpusRequest& request, const std::string& preset);

// The dashboard: corpus.json (every row) and corpus.html (a summary per folder and per target, the
// failures grouped by reason, a row per preset), written all or nothing.
std::string corpus_json(const CorpusReport& report);
std::string corpus_html(const CorpusReport& report);
Status write_corpus_report(const CorpusReport& report, const std::string& dir);

// A failure's reason with its location and the numbers and names that vary taken out, so the same
// construct in different shaders groups together ("...: 'X' undeclared identifier").
std::string corpus_reason_class(const std::string& reason);

// One row as one line of JSON (the fields of corpus.json's rows), and back: how worker processes
// hand their rows to the sweep (validate/corpus_workers.cpp). An infinite PSNR travels as null.
std::string corpus_row_line(const CorpusRow& row);
Result<CorpusRow> corpus_row_from_line(const std::string& line);

}  // namespace crtforge
