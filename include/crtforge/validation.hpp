// crtforge validate: every preset x target is proven by something that consumes it, and the results
// are gathered into a report (report.json, junit.xml) that CI can fail on.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/cache.hpp"
#include "crtforge/diagnostic.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

struct CheckResult {
    std::string preset;
    std::string target;
    std::string check;      // "compile:<vert|frag>" — what was proven
    bool passed = false;
    std::string message;    // one line: what the consumer said on failure
};

struct ValidationReport {
    std::vector<CheckResult> checks;  // in a fixed order: preset, target, check
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
    VariantOptions options;
    Shard shard;
};

// Called after each check, for progress display.
using ProgressFn = std::function<void(size_t done, size_t total, const CheckResult&)>;

Result<ValidationReport> run_validation(const TemplateLibrary& library, const ValidateRequest& request,
                                        const Cache& cache, const ProgressFn& progress = {});

// report.json and junit.xml into dir (created if needed). No timestamps or timings: the same
// results give byte-identical files.
Status write_report(const ValidationReport& report, const std::string& dir);

}  // namespace crtforge
