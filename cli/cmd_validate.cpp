// crtforge validate [--report DIR] [--preset P...] [--target T...] [--shard i/n]
#include <chrono>
#include <cstdio>

#include <fmt/format.h>
#include <unistd.h>

#include "cli/cli_common.hpp"
#include "crtforge/validation.hpp"

namespace crtforge::cli {

namespace {
struct ValidateArgs {
    std::string report, shard = "1/1";
    std::vector<std::string> presets, targets;
    VariantFlags flags;
};

// Plain lines when piped (CI logs), an in-place progress bar on a terminal.
ProgressFn make_progress() {
    const bool tty = ::isatty(STDOUT_FILENO);
    return [tty](size_t done, size_t total, const CheckResult& r) {
        if (!r.passed)
            fmt::print("{}FAIL {} {} {}: {}\n", tty ? "\r\033[K" : "", r.preset, r.target, r.check, r.message);
        if (tty) {
            const int width = 30, filled = total ? static_cast<int>(width * done / total) : width;
            fmt::print("\r[{}{}] {}/{}", std::string(filled, '#'), std::string(width - filled, '.'), done, total);
            if (done == total) fmt::print("\n");
            std::fflush(stdout);
        }
    };
}
}  // namespace

Runner add_validate_command(CLI::App& app, const GlobalOptions& g) {
    auto args = std::make_shared<ValidateArgs>();
    auto* cmd = app.add_subcommand("validate", "Prove every preset x target with its real consumer and write a report");
    cmd->add_option("--report", args->report, "Write report.json and junit.xml into this directory");
    cmd->add_option("--preset", args->presets, "Only these presets")->delimiter(',');
    cmd->add_option("--target", args->targets, "Only these targets")->delimiter(',');
    cmd->add_option("--shard", args->shard, "Run share i of n (1-based), for CI matrices")->capture_default_str();
    args->flags.add_to(*cmd);
    return [&g, args]() {
        const auto start = std::chrono::steady_clock::now();
        int code = kExitOk;
        ValidateRequest request;
        for (const auto& name : args->targets) {
            const TargetInfo* t = find_target(name);
            if (!t) return report(make_error("unknown target '" + name + "'", {}, 0, "--target"));
            request.targets.push_back(t->id);
        }
        auto shard = Shard::parse(args->shard);
        if (!shard.ok()) return report(shard.error());
        request.shard = shard.value();
        auto options = args->flags.parse();
        if (!options.ok()) return report(options.error());
        request.options = options.value();
        request.presets = args->presets;
        auto lib = load_library(g, code);
        if (!lib) return code;
        Cache cache = make_cache(g);
        auto result = run_validation(*lib, request, cache, make_progress());
        if (!result.ok()) return report(result.error());
        const ValidationReport& r = result.value();
        if (!args->report.empty())
            if (auto s = write_report(r, args->report); !s.ok()) return report(s.error());
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // A one-screen summary: per target, how many checks passed.
        fmt::print("{:<10} {:>7} {:>7}\n", "target", "passed", "failed");
        for (const TargetInfo& t : all_targets()) {
            size_t pass = 0, fail = 0;
            for (const auto& c : r.checks)
                if (c.target == t.name) (c.passed ? pass : fail)++;
            if (pass + fail) fmt::print("{:<10} {:>7} {:>7}\n", t.name, pass, fail);
        }
        fmt::print("validate: {} passed, {} failed ({} checks, shard {}/{}, {:.1f} s){}\n", r.passed(), r.failed(),
                   r.checks.size(), request.shard.index, request.shard.count, secs,
                   args->report.empty() ? "" : ", report in " + args->report);
        return r.failed() ? kExitValidation : kExitOk;
    };
}

}  // namespace crtforge::cli
