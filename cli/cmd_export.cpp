// crtforge export --out DIR [--preset P...] [--target T...]
#include <chrono>

#include <fmt/format.h>

#include "cli/cli_common.hpp"

namespace crtforge::cli {

namespace {
struct ExportArgs {
    std::string out;
    std::vector<std::string> presets, targets;
    VariantFlags flags;
    bool quiet = false;
};
}  // namespace

Runner add_export_command(CLI::App& app, const GlobalOptions& g) {
    auto args = std::make_shared<ExportArgs>();
    auto* cmd = app.add_subcommand("export", "Write every preset x target, plus manifest.json, into a directory");
    cmd->add_option("--out", args->out, "Output directory")->required();
    cmd->add_option("--preset", args->presets, "Only these presets (repeat or comma-separate; a RetroArch .slangp file is imported first); default all")
        ->delimiter(',');
    cmd->add_option("--target", args->targets, "Only these targets (repeat or comma-separate); default all")
        ->delimiter(',');
    cmd->add_flag("--quiet,-q", args->quiet, "Print nothing on success");
    args->flags.add_to(*cmd);
    return [&g, args]() {
        const auto start = std::chrono::steady_clock::now();
        int code = kExitOk;
        ExportRequest request;
        for (const auto& name : args->targets) {
            auto t = lookup_target(name);
            if (!t.ok()) return report(t.error());
            request.targets.push_back(t.value()->id);
        }
        auto options = args->flags.parse();
        if (!options.ok()) return report(options.error());
        request.options = options.value();
        request.presets = args->presets;
        drop_repeats(request.presets);
        drop_repeats(request.targets);
        auto lib = load_library(g, code, &request.presets);
        if (!lib) return code;
        Cache cache = make_cache(g);
        // Everything is produced in memory first: a failure leaves no partial output behind.
        auto result = run_export(*lib, request, cache);
        if (!result.ok()) return report(result.error());
        if (auto s = write_export(args->out, result.value().files); !s.ok()) return report(s.error());
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!args->quiet)
            fmt::print("exported {} presets x {} targets ({} files + manifest.json) to {} in {:.0f} ms "
                       "(cache: {} hits, {} misses)\n",
                       result.value().variants, request.targets.empty() ? all_targets().size() : request.targets.size(),
                       result.value().files.size() - 1, args->out, ms, cache.hits(), cache.misses());
        return kExitOk;
    };
}

}  // namespace crtforge::cli
