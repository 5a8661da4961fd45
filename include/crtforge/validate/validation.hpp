// crtforge validate: every preset x target is proven by something that consumes it — its compiler
// accepts it, and its render through the real consumer matches the golden reference images — and
// the results are gathered into a report (report.json, junit.xml, report.html) CI can fail on.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/cache.hpp"
#include "crtforge/diagnostic.hpp"
#include "crtforge/exit_cleanup.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

struct CheckResult {
    std::string preset;
    std::string target;
    std::string check;      // "compile:<role>" (vertex, fragment, shader, screenShader) or "render:<golden id>"
    bool passed = false;
    std::string message;    // one line: what failed and why
    std::optional<Verdict> verdict;  // render checks
    std::string golden_id;           // render checks
    // A rendering run found no golden for this preset on this target: nothing was rendered or
    // measured (check "render", no verdict). Passes unless --strict; never shown as RMSE 0.
    bool not_rendered = false;
};

struct ValidationReport {
    // Which run this is: shards of one run share the id (derived from what the run checks: the
    // goldens, presets, targets and inputs, or --run-id) and carry their index of the count, so
    // `report merge` refuses shards of other runs, repeated shards and missing ones.
    std::string run_id;
    unsigned shard_index = 1, shard_count = 1;
    std::vector<CheckResult> checks;              // fixed order: preset, target, check
    std::vector<GoldenEntry> goldens;             // the goldens this run rendered against
    std::vector<std::pair<std::string, std::string>> consumers;  // target -> consumer description
    size_t failed() const;
    size_t passed() const { return checks.size() - failed(); }
};

struct Shard {
    unsigned index = 1, count = 1;  // 1-based: "--shard 2/4" is index 2 of 4
    static Result<Shard> parse(const std::string& text);
};

struct ValidateRequest {
    std::vector<std::string> presets;  // empty = all
    std::vector<TargetId> targets;     // empty = all
    std::vector<std::string> inputs;   // golden inputs to render; empty = all
    bool render = true;                // false: compile checks only
    std::string golden_dir;            // where golden/manifest.json lives
    std::string report_dir;            // when set, render/golden/diff pictures go to <report_dir>/images
    EngineOptions vulkan;              // --device
    // A second Vulkan driver the Vulkan-rendered targets (spirv, hlsl*) render on
    // as well, judged alike and reported as "<target>@<label>" (SwiftShader beside lavapipe: two
    // independent implementations, so undefined behaviour one computes sensibly can show).
    std::optional<EngineOptions> second_vulkan;
    std::string second_label;          // e.g. "swiftshader"
    // The full scene matrix (golden/plan.toml entries with matrix = "full": large, odd and tiny
    // sizes, parameter draws, other variants, long times); the main job runs the rest.
    bool full_matrix = false;
    Shard shard;
    unsigned jobs = 1;                 // worker threads, each with its own engines
    std::string run_id;                // empty: derived from the request (ValidationReport::run_id)
    bool strict = false;               // a preset x target with no golden fails instead of passing
};

using ProgressFn = std::function<void(size_t done, size_t total, const CheckResult&)>;

Result<ValidationReport> run_validation(const TemplateLibrary& library, const ValidateRequest& request,
                                        const Cache& cache, const ProgressFn& progress = {});

// report.json, junit.xml and report.html into dir. No timestamps or timings: the same results give
// byte-identical files.
Status write_report(const ValidationReport& report, const std::string& dir);
// A report folder written all or nothing. The run writes into a staging folder beside `dir`
// (path()); commit() then removes the earlier report's entries (images/, report.json, junit.xml,
// report.html) and renames the staged ones into place, so nothing of another run stays beside
// this one. Until then `dir` keeps its earlier report untouched: a run that fails, is refused or
// runs out of disk leaves it as it was, and the staging folder goes with the object. A non-empty
// `dir` that holds no report.json is refused at open (it is not ours to empty).
class StagedReportDir {
public:
    static Result<StagedReportDir> open(const std::string& dir);
    StagedReportDir(StagedReportDir&& other) noexcept
        : dir_(std::move(other.dir_)), staging_(std::move(other.staging_)), cleanup_(std::move(other.cleanup_)) {
        other.staging_.clear();
    }
    StagedReportDir& operator=(StagedReportDir&&) = delete;
    StagedReportDir(const StagedReportDir&) = delete;
    ~StagedReportDir();
    const std::string& path() const { return staging_; }
    Status commit();

private:
    StagedReportDir(std::string dir, std::string staging) : dir_(std::move(dir)), staging_(std::move(staging)), cleanup_(staging_) {}
    std::string dir_, staging_;
    ExitCleanup cleanup_;  // the staging folder, should the process have to stop at once
};
// The pictures of shard reports (<dir>/images/<golden>/...) into one report folder, so the merged
// report.html shows them. Shards render disjoint (preset, target) pairs; a file two shards both
// hold (the input and golden pictures of a golden) is the same picture, and the first is kept.
Status copy_report_images(const std::vector<std::string>& shard_dirs, const std::string& out);

// Concatenates shard reports (their report.json files) into one report, in the full run's order.
Result<ValidationReport> merge_reports(const std::vector<std::string>& report_dirs);

}  // namespace crtforge
