// crtforge validate [--report DIR] [--preset P...] [--target T...] [--input I...] [--shard i/n] [-j N]
//                  [--device D] [--second-device auto|none|D] [--matrix main|full]
// crtforge report merge --out DIR SHARD_DIR...
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <optional>

#include <fmt/format.h>
#include <unistd.h>

#include "cli/cli_common.hpp"
#include "cli/github_actions.hpp"
#include "crtforge/runtime/dawn_engine.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/validate/validation.hpp"

namespace crtforge::cli {

namespace {
struct ValidateArgs {
    std::string report, shard = "1/1", golden, device, second_device = "auto", matrix = "main", run_id;
    bool strict = false;
    std::vector<std::string> presets, targets, inputs;
    unsigned jobs = 1;
    bool compile_only = false;
};

struct SecondDriver {
    std::string name, label;
};

// The second Vulkan driver: `choice` "none", "auto" (a SwiftShader device, when the loader lists
// one and it is not the first driver) or a device name; its label is the name's first word, lower case.
Result<std::optional<SecondDriver>> second_driver(const std::string& choice, const std::string& first) {
    if (choice == "none") return std::optional<SecondDriver>{};
    auto found = vulkan_device_named(choice == "auto" ? "SwiftShader" : choice, first);
    if (!found.ok()) return choice == "auto" ? Result<std::optional<SecondDriver>>(std::optional<SecondDriver>{}) : found.error();
    if (found.value().empty()) {
        if (choice == "auto") return std::optional<SecondDriver>{};
        return make_error("no Vulkan device matches '" + choice + "' (see 'crtforge devices')", {}, 0, "--second-device");
    }
    const std::string& name = found.value();
    std::string label;
    for (char c : name.substr(0, name.find(' ')))
        if (std::isalnum(static_cast<unsigned char>(c))) label += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return std::optional<SecondDriver>{SecondDriver{name, label}};
}

// What the arguments ask for that this machine cannot give is a usage error (exit 2) before
// anything runs, not a column of failed checks (exit 1): a --device no driver has, and Dawn
// (Node.js and the runner's npm package) when the WGSL target renders.
Status check_machine(const ValidateRequest& request, const std::string& device) {
    if (!device.empty()) {
        auto devices = list_vulkan_devices();
        if (!devices.ok()) return make_error(devices.error().message, {}, 0, "--device");
        bool found = false;
        const bool index = std::all_of(device.begin(), device.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
        auto lower = [](std::string t) {
            for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            return t;
        };
        for (size_t i = 0; i < devices.value().size(); ++i)
            found = found || (index ? device == std::to_string(i) : lower(devices.value()[i].name).find(lower(device)) != std::string::npos);
        if (!found)
            return make_error("no Vulkan device matches '" + device + "' (" + std::to_string(devices.value().size()) +
                                  " devices; see 'crtforge devices')",
                              {}, 0, "--device");
    }
    const bool wgsl = request.targets.empty() ||
                      std::find(request.targets.begin(), request.targets.end(), TargetId::Wgsl) != request.targets.end();
    if (wgsl)  // WGSL compile checks run in Dawn too
        if (auto dawn = DawnEngine::check_setup(); !dawn.ok()) return make_error(dawn.error().message, {}, 0, "--target wgsl");
    return Ok{};
}

// Plain lines when piped (CI logs), an in-place progress bar on a terminal.
ProgressFn make_progress() {
    const bool tty = ::isatty(STDOUT_FILENO);
    return [tty](size_t done, size_t total, const CheckResult& r) {
        if (!r.passed)
            fmt::print("{}FAIL {} {} {}: {}\n", tty ? "\r\033[K" : "", r.preset, r.target, r.check, r.message);
        if (tty) draw_progress_bar(done, total, fmt::format("{}/{}", done, total));
    };
}

// The one-screen summary: per target, checks passed/failed and the worst render metrics.
void print_summary(const ValidationReport& r) {
    // Targets in report order: each target, then the Vulkan-rendered ones on the second driver.
    std::vector<std::string> names;
    for (const auto& c : r.checks)
        if (std::find(names.begin(), names.end(), c.target) == names.end()) names.push_back(c.target);
    size_t width = 10;
    for (const std::string& n : names) width = std::max(width, n.size());
    fmt::print("{:<{}} {:>7} {:>7} {:>9} {:>10} {:>9} {:>9}  {}\n", "target", width, "passed", "failed", "unrendered", "max RMSE",
               "min SSIM", "max |d|", "consumer");
    for (const std::string& name : names) {
        size_t pass = 0, fail = 0, unrendered = 0, measured = 0;
        double rmse = 0, ssim = 1, maxabs = 0;
        for (const auto& c : r.checks) {
            if (c.target != name) continue;
            (c.passed ? pass : fail)++;
            unrendered += c.not_rendered;
            if (c.verdict) {
                ++measured;
                rmse = std::max(rmse, c.verdict->metrics.rmse);
                ssim = std::min(ssim, c.verdict->metrics.ssim);
                maxabs = std::max(maxabs, c.verdict->metrics.max_abs);
            }
        }
        std::string consumer;
        for (const auto& [n, desc] : r.consumers)
            if (n == name) consumer = desc;
        // Metrics only where something was measured: no render, no RMSE 0 / SSIM 1.
        const std::string metrics = measured ? fmt::format("{:>10.5f} {:>9.4f} {:>9.4f}", rmse, ssim, maxabs)
                                             : fmt::format("{:>10} {:>9} {:>9}", "-", "-", "-");
        fmt::print("{:<{}} {:>7} {:>7} {:>9} {}  {}\n", name, width, pass, fail, unrendered, metrics, consumer);
    }
}
}  // namespace

Runner add_validate_command(CLI::App& app, const GlobalOptions& g) {
    auto a = std::make_shared<ValidateArgs>();
    auto* cmd = app.add_subcommand("validate",
                                   "Compile every preset x target with its real consumer, render it there and compare with the goldens");
    cmd->add_option("--report", a->report, "Write report.json, junit.xml, report.html and pictures into this directory");
    cmd->add_option("--preset", a->presets, "Only these presets (a RetroArch .slangp file is imported first)")->delimiter(',');
    cmd->add_option("--target", a->targets, "Only these targets")->delimiter(',');
    cmd->add_option("--input", a->inputs, "Only goldens of these generated inputs")->delimiter(',');
    cmd->add_option("--shard", a->shard, "Run share i of n (1-based), for CI matrices")->capture_default_str();
    cmd->add_option("-j,--jobs", a->jobs, "Worker threads")->check(CLI::Range(1u, 64u))->capture_default_str();
    cmd->add_option("--golden-dir", a->golden, "Golden directory (default: the source tree's golden/)");
    cmd->add_option("--device", a->device, "Vulkan device name or index (default: lavapipe; see 'crtforge devices')");
    cmd->add_option("--second-device", a->second_device,
                    "A second Vulkan driver for the Vulkan-rendered targets (spirv, hlsl*): auto (SwiftShader when "
                    "installed), none, or a device name")
        ->capture_default_str();
    cmd->add_option("--matrix", a->matrix,
                    "Which goldens: main (the main job's) or full (also golden/plan.toml's matrix = \"full\" entries: odd, tiny "
                    "and 4K sizes, parameter draws, other variants, long times)")
        ->check(CLI::IsMember({"main", "full"}))
        ->capture_default_str();
    cmd->add_flag("--compile-only", a->compile_only, "Only the compile checks, no renders");
    cmd->add_flag("--strict", a->strict, "A preset x target that no golden judges fails (default: reported as not rendered, passing)");
    cmd->add_option("--run-id", a->run_id,
                    "Names the run in report.json (default: derived from what it checks); give every shard of a CI run the same one");
    return [&g, a]() {
        const auto start = std::chrono::steady_clock::now();
        int code = kExitOk;
        ValidateRequest request;
        for (const auto& name : a->targets) {
            auto t = lookup_target(name);
            if (!t.ok()) return report(t.error());
            request.targets.push_back(t.value()->id);
        }
        auto shard = Shard::parse(a->shard);
        if (!shard.ok()) return report(shard.error());
        request.shard = shard.value();
        request.presets = a->presets;
        request.inputs = a->inputs;
        drop_repeats(request.targets);
        drop_repeats(request.presets);
        drop_repeats(request.inputs);
        request.render = !a->compile_only;
        request.full_matrix = a->matrix == "full";
        request.golden_dir = a->golden.empty() ? default_golden_dir() : a->golden;
        request.report_dir = a->report;
        request.vulkan.device = a->device;
        auto second = second_driver(a->second_device, a->device);
        if (!second.ok()) return report(second.error());
        if (second.value()) {
            request.second_vulkan = EngineOptions{second.value()->name, request.vulkan.validation};
            request.second_label = second.value()->label;
        }
        request.jobs = a->jobs;
        if (auto machine = check_machine(request, a->device); !machine.ok()) return report(machine.error());
        request.run_id = a->run_id;
        request.strict = a->strict;
        std::optional<StagedReportDir> staged;
        if (!a->report.empty()) {
            auto opened = StagedReportDir::open(a->report);
            if (!opened.ok()) return report(opened.error());
            staged.emplace(std::move(opened.value()));
            request.report_dir = staged->path();
        }
        auto lib = load_library(g, code, &request.presets);
        if (!lib) return code;
        if (auto s = add_golden_presets(*lib, request.golden_dir); !s.ok()) return report(s.error());
        Cache cache = make_cache(g);
        auto result = run_validation(*lib, request, cache, make_progress());
        if (!result.ok()) return report(result.error());
        const ValidationReport& r = result.value();
        if (staged) {
            if (auto s = write_report(r, staged->path()); !s.ok()) return report(s.error());
            if (auto s = staged->commit(); !s.ok()) return report(s.error());
        }
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        print_summary(r);
        annotate_for_github(r, [&](const std::string& name) {
            const Preset* p = lib->find_preset(name);
            return p ? p->where : SourceLocation{};
        });
        const size_t unrendered = static_cast<size_t>(std::count_if(r.checks.begin(), r.checks.end(), [](const CheckResult& c) { return c.not_rendered; }));
        fmt::print("validate: {} passed, {} failed{} ({} checks over {} goldens of the {} matrix, shard {}/{}, {:.1f} s){}\n",
                   r.passed(), r.failed(), unrendered ? fmt::format(", {} not rendered (no golden{})", unrendered, a->strict ? ": failed under --strict" : "") : "",
                   r.checks.size(), r.goldens.size(), a->matrix, request.shard.index, request.shard.count, secs,
                   a->report.empty() ? "" : ", report: " + a->report + "/report.html");
        return r.failed() ? kExitValidation : kExitOk;
    };
}

Runner add_report_command(CLI::App& app, const GlobalOptions&) {
    auto* cmd = app.add_subcommand("report", "Work with validate reports");
    cmd->require_subcommand(1);
    auto* merge = cmd->add_subcommand("merge", "Merge shard reports (report.json files) into one report");
    auto out = std::make_shared<std::string>();
    auto dirs = std::make_shared<std::vector<std::string>>();
    merge->add_option("--out", *out, "Directory for the merged report")->required();
    merge->add_option("dirs", *dirs, "Shard report directories")->required();
    return [out, dirs]() {
        auto merged = merge_reports(*dirs);
        if (!merged.ok()) return report(merged.error());
        auto staged = StagedReportDir::open(*out);
        if (!staged.ok()) return report(staged.error());
        if (auto s = copy_report_images(*dirs, staged.value().path()); !s.ok()) return report(s.error());
        if (auto s = write_report(merged.value(), staged.value().path()); !s.ok()) return report(s.error());
        if (auto s = staged.value().commit(); !s.ok()) return report(s.error());
        print_summary(merged.value());
        annotate_for_github(merged.value(), {});
        fmt::print("report merge: {} passed, {} failed ({} checks from {} shards) into {}\n", merged.value().passed(),
                   merged.value().failed(), merged.value().checks.size(), dirs->size(), *out);
        return merged.value().failed() ? kExitValidation : kExitOk;
    };
}

}  // namespace crtforge::cli
