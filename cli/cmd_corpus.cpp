// crtforge corpus DIR [--root R] [--report OUT] [--only P,...] [--target T,...|--vulkan-only] [--shard i/n] [-j N]
//                [--source-size WxH] [--size WxH] [--frame N] [--min-psnr DB] [--smooth] [--retroarch DIR]
//                [--uniforms default|none|all|NAMES] [--optimised-jit] [--presets-per-process N] [--preset-timeout S]
// Every .slangp under DIR through import, SPIR-V, each target's emitter and consumer, a render by
// each consumer judged against Vulkan: the dashboard of validate/corpus_report.cpp.
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <chrono>
#include <filesystem>
#include <thread>

#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/paths.hpp"
#include "crtforge/validate/corpus.hpp"
#include "crtforge/validate/corpus_workers.hpp"

namespace crtforge::cli {

namespace {

// The machine's cores (at least 1): the default -j, and what a thread per core means.
unsigned cores() { return std::max(1u, std::thread::hardware_concurrency()); }

struct CorpusArgs {
    std::string dir, root, report, shard = "1/1", source_size = "160x120", size = "320x240", device, retroarch;
    std::vector<std::string> targets, only;
    bool vulkan_only = false, smooth = false, optimised_jit = false;
    std::string uniforms = "default";
    unsigned jobs = cores();
    int frame = 2;
    double min_psnr = 40.0, fail_under = 0.0;
    size_t presets_per_process = 50;
    double preset_timeout = 600;
    int rows_fd = -1;                           // a worker: its rows go here, as lines of JSON
    std::vector<std::string> worker_presets;    // a worker: its presets, relative to DIR
};

// A worker's command line: the same settings, these presets, its rows to `rows_fd`. Values go as
// --name=value and DIR after "--", so a path starting with '-' stays a value.
std::vector<std::string> worker_arguments(const CorpusArgs& a, const GlobalOptions& g, const std::string& root,
                                          const std::vector<std::string>& presets, int rows_fd) {
    std::vector<std::string> out;
    if (!g.cache_dir.empty()) out.push_back("--cache-dir=" + g.cache_dir);
    if (g.no_cache) out.push_back("--no-cache");
    out.push_back(fmt::format("--gpu-timeout={}", g.gpu_timeout));
    out.push_back("corpus");
    out.push_back("--root=" + root);
    if (a.vulkan_only) out.push_back("--vulkan-only");
    for (const std::string& t : a.targets) out.push_back("--target=" + t);
    out.push_back(fmt::format("--jobs={}", a.jobs));
    out.push_back("--source-size=" + a.source_size);
    out.push_back("--size=" + a.size);
    out.push_back(fmt::format("--frame={}", a.frame));
    out.push_back(fmt::format("--min-psnr={}", a.min_psnr));  // shortest text that reads back as the same double
    if (a.smooth) out.push_back("--smooth");
    if (!a.device.empty()) out.push_back("--device=" + a.device);
    if (!a.retroarch.empty()) out.push_back("--retroarch=" + a.retroarch);
    out.push_back("--uniforms=" + a.uniforms);
    if (a.optimised_jit) out.push_back("--optimised-jit");
    out.push_back(fmt::format("--rows-fd={}", rows_fd));
    for (const std::string& p : presets) out.push_back("--worker-preset=" + p);
    out.push_back("--");
    out.push_back(root);
    return out;
}

Result<std::vector<TargetId>> corpus_targets(const std::vector<std::string>& list, bool vulkan_only) {
    if (vulkan_only && !list.empty()) return make_error("give --target or --vulkan-only, not both", {}, 0, "--vulkan-only");
    std::vector<TargetId> out{TargetId::Spirv};  // the judge of the others, always first
    if (vulkan_only) return out;
    if (list.empty()) {
        for (const TargetInfo& t : all_targets())
            if (t.id != TargetId::Spirv) out.push_back(t.id);
        return out;
    }
    for (const std::string& name : list) {
        auto t = lookup_target(name);
        if (!t.ok()) return t.error();
        if (std::find(out.begin(), out.end(), t.value()->id) == out.end()) out.push_back(t.value()->id);
    }
    return out;
}

// A worker's run: each row, as it is done, a line of JSON on `fd` for the sweep that started it.
int run_as_worker(const CorpusRequest& request, const Cache& cache, int fd) {
    ::fcntl(fd, F_SETFD, FD_CLOEXEC);  // the consumers it starts must not hold the sweep's pipe open
    auto write_row = [fd](size_t, size_t, const CorpusRow& row) {
        const std::string line = corpus_row_line(row) + "\n";
        for (size_t at = 0; at < line.size();) {
            const ssize_t n = ::write(fd, line.data() + at, line.size() - at);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) std::_Exit(1);  // the sweep is gone: nobody reads the rest
            at += static_cast<size_t>(n);
        }
    };
    auto result = run_corpus(request, cache, write_row);
    if (!result.ok()) return report(result.error());
    return kExitOk;
}

// An in-place bar on a terminal; a line per 2 % (and per failed import) in a log.
CorpusProgress corpus_progress() {
    const bool tty = ::isatty(STDOUT_FILENO);
    const auto start = std::chrono::steady_clock::now();
    auto failing = std::make_shared<size_t>(0);
    return [tty, start, failing](size_t done, size_t total, const CorpusRow& row) {
        const bool vulkan_ok = row.targets.count("spirv") && row.targets.at("spirv").status == "agrees";
        *failing += !vulkan_ok;
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double eta = done ? secs / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
        const std::string status = fmt::format("{}/{} presets, {} not rendered on Vulkan, {:.0f} s, ~{:.0f} s left", done, total,
                                               *failing, secs, eta);
        report_progress(tty, done, total, "corpus", status, 50);
    };
}

}  // namespace

Runner add_corpus_command(CLI::App& app, const GlobalOptions& g) {
    auto a = std::make_shared<CorpusArgs>();
    auto* cmd = app.add_subcommand("corpus", "Every RetroArch .slangp under a folder through import, every target and its consumer: a dashboard");
    cmd->add_option("dir", a->dir, "The folder of .slangp presets (searched recursively)")->required();
    cmd->add_option("--root", a->root, "No file a preset reads may lie outside this folder (default: DIR)");
    cmd->add_option("--report", a->report, "Write corpus.json and corpus.html into this folder");
    cmd->add_option("--target", a->targets, "Targets (repeat or comma-separate; default: all); spirv (Vulkan) always runs: it judges the others")
        ->delimiter(',');
    cmd->add_option("--only", a->only, "Only these presets (paths relative to DIR; repeat or comma-separate)")->delimiter(',');
    cmd->add_flag("--vulkan-only", a->vulkan_only, "Only the spirv target on Vulkan (the quick whole-library sweep)");
    cmd->add_option("--shard", a->shard, "Run share i of n (1-based): every n-th preset")->capture_default_str();
    cmd->add_option("-j,--jobs", a->jobs,
                    "Worker threads (with --vulkan-only and a thread per core, lavapipe draws on them: LP_NUM_THREADS=0 unless set)")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    cmd->add_option("--source-size", a->source_size, "The generated input's size (pixel_art)")->capture_default_str();
    cmd->add_option("--size", a->size, "The display size")->capture_default_str();
    cmd->add_option("--frame", a->frame, "The frame judged (frames 0..N run)")->check(CLI::Range(0, 1000))->capture_default_str();
    cmd->add_option("--min-psnr", a->min_psnr, "A target agrees with Vulkan at or above this PSNR (dB)")->check(CLI::Range(0.0, 100.0))->capture_default_str();
    cmd->add_flag("--smooth", a->smooth, "Filter linearly where a preset leaves the filter unset (RetroArch's video_smooth)");
    cmd->add_option("--device", a->device, "Vulkan device name or index (default: lavapipe)");
    cmd->add_option("--retroarch", a->retroarch,
                    "A folder of RetroArch's renders of the judged frame (<dir>/<preset path>.png, at --size, from the same input): adds the RetroArch column");
    cmd->add_option("--uniforms", a->uniforms,
                    "Which params stay uniforms: default (every param, live, as export writes them), none (the preset's values baked: "
                    "smaller shaders, the quick sweep), all or NAME,NAME,...")
        ->capture_default_str();
    cmd->add_flag("--optimised-jit", a->optimised_jit,
                  "With --vulkan-only on lavapipe: let LLVM optimise each pipeline it compiles (by default the sweep sets "
                  "GALLIVM_PERF=nopt: three small frames per preset do not repay LLVM's optimisation of Mega Bezel's shaders)");
    cmd->add_option("--presets-per-process", a->presets_per_process,
                    "Run the presets in worker processes of this many each (0: all in this one). A fresh process gives back what "
                    "the Vulkan driver keeps (lavapipe grows ~90 MB per large preset); a preset that crashes its worker gets a row saying so")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    cmd->add_option("--preset-timeout", a->preset_timeout,
                    "Seconds a worker may go without finishing a preset before it is stopped and the preset gets a 'timeout' row "
                    "(0: no limit; not with --presets-per-process 0)")
        ->check(CLI::Range(0.0, 86400.0))
        ->capture_default_str();
    // How the sweep runs its workers; not for users.
    cmd->add_option("--rows-fd", a->rows_fd)->group("")->check(CLI::Range(3, 1023));
    cmd->add_option("--worker-preset", a->worker_presets)->group("");
    cmd->add_option("--fail-under", a->fail_under, "Exit 1 when fewer than this percentage of the presets render on Vulkan")
        ->check(CLI::Range(0.0, 100.0));
    return [&g, a]() {
        const std::string root = a->root.empty() ? a->dir : a->root;
        auto targets = corpus_targets(a->targets, a->vulkan_only);
        if (!targets.ok()) return report(targets.error());
        auto shard = Shard::parse(a->shard);
        if (!shard.ok()) return report(shard.error());
        auto source = parse_size(a->source_size);
        if (!source.ok()) return report(make_error(source.error().message, {}, 0, "--source-size"));
        auto display = parse_size(a->size);
        if (!display.ok()) return report(display.error());
        const bool worker = a->rows_fd >= 0;
        if (worker != !a->worker_presets.empty()) return report(make_error("give both or neither", {}, 0, "--rows-fd"));
        if (worker && ::fcntl(a->rows_fd, F_GETFL) < 0)
            return report(make_error(fmt::format("descriptor {} is not open", a->rows_fd), {}, 0, "--rows-fd"));
        // A worker is given its presets; the sweep lists DIR's.
        auto found = worker ? Result<std::vector<std::string>>(a->worker_presets) : list_corpus_presets(a->dir);
        if (!found.ok()) return report(found.error());
        if (!a->only.empty() && !worker) {  // a curated set: each named preset must be one the folder holds
            std::vector<std::string> chosen;
            for (const std::string& name : a->only) {
                const std::string wanted = std::filesystem::path(name).lexically_normal().generic_string();
                if (!std::binary_search(found.value().begin(), found.value().end(), wanted))
                    return report(make_error("no preset '" + name + "' under " + a->dir, {}, 0, "--only"));
                chosen.push_back(wanted);
            }
            std::sort(chosen.begin(), chosen.end());
            chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
            found.value() = std::move(chosen);
        }
        std::error_code ec;
        const auto root_abs = std::filesystem::weakly_canonical(root, ec), dir_abs = std::filesystem::weakly_canonical(a->dir, ec);
        const std::string under = std::filesystem::relative(dir_abs, root_abs, ec).generic_string();
        if (ec || under.empty() || under.rfind("..", 0) == 0)
            return report(make_error("DIR must lie inside --root", a->dir, 0, "--root"));
        CorpusRequest request;
        request.root = root;
        for (const std::string& p : found.value()) request.presets.push_back(under == "." ? p : under + "/" + p);
        if (request.presets.empty()) return report(make_error("has no .slangp presets", a->dir, 0, "corpus"));
        request.targets = targets.value();
        request.shard = shard.value();
        request.jobs = a->jobs;
        std::tie(request.source_width, request.source_height) = source.value();
        std::tie(request.display_width, request.display_height) = display.value();
        request.frame = a->frame;
        request.min_psnr = a->min_psnr;
        request.smooth = a->smooth;
        request.vulkan.device = a->device;
        request.retroarch_dir = a->retroarch;
        auto uniforms = UniformSelection::parse(a->uniforms);
        if (!uniforms.ok()) return report(make_error(uniforms.error().message, {}, 0, "--uniforms"));
        if (uniforms.value().mode == UniformSelection::Mode::Uber)
            return report(make_error("the uber-shader is not a corpus variant: give default, none, all or names", {}, 0, "--uniforms"));
        request.uniforms = uniforms.value();
        if (a->optimised_jit && !a->vulkan_only) return report(make_error("only with --vulkan-only", {}, 0, "--optimised-jit"));
        // lavapipe JIT-compiles every pipeline with LLVM, optimising by default: for a sweep that draws
        // three small frames per preset, that compile is most of the run. A GALLIVM_PERF the user
        // set is theirs; the loader has not read it yet (no Vulkan instance exists before the run).
        if (a->vulkan_only && !a->optimised_jit) ::setenv("GALLIVM_PERF", "nopt", /*overwrite*/ 0);
        // With a sweep thread per core the cores are busy with presets: lavapipe's rasterizer threads
        // would only hand each draw over and wait for it (measured: Mega Bezel presets 7 % quicker
        // drawn on the thread that asks, the other families the same).
        if (a->vulkan_only && a->jobs >= cores())
            ::setenv("LP_NUM_THREADS", "0", /*overwrite*/ 0);
        if (!a->retroarch.empty() && !std::filesystem::is_directory(a->retroarch, ec))
            return report(make_error("is not a folder", a->retroarch, 0, "--retroarch"));
        // Check the output folder before the long run, not after it.
        if (!a->report.empty() && std::filesystem::exists(a->report, ec) && !std::filesystem::is_directory(a->report, ec))
            return report(make_error("exists and is not a folder", a->report, 0, "--report"));

        const auto start = std::chrono::steady_clock::now();
        if (worker) return run_as_worker(request, make_cache(g), a->rows_fd);
        auto mine = corpus_shard_presets(request);
        if (!mine.ok()) return report(mine.error());
        Result<CorpusReport> result = make_error("not run");
        if (a->presets_per_process == 0) {
            result = run_corpus(request, make_cache(g), corpus_progress());
        } else {
            CorpusWorkers workers;
            workers.executable = running_executable();
            if (workers.executable.empty()) return report(make_error("cannot find this program to start its workers", {}, 0, "corpus"));
            workers.presets_per_process = a->presets_per_process;
            workers.preset_timeout_s = a->preset_timeout;
            workers.arguments = [a, &g, root](const std::vector<std::string>& presets, int fd) {
                return worker_arguments(*a, g, root, presets, fd);
            };
            result = run_corpus_in_workers(request, workers, corpus_progress());
        }
        if (!result.ok()) return report(result.error());
        const CorpusReport& r = result.value();
        if (!a->report.empty())
            if (auto s = write_corpus_report(r, a->report); !s.ok()) return report(s.error());
        size_t imported = 0, vulkan = 0;
        for (const CorpusRow& row : r.rows) {
            imported += row.import_error.empty();
            vulkan += row.targets.at("spirv").status == "agrees";
        }
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const size_t n = r.rows.size();
        fmt::print("corpus: {} presets (shard {}/{}): {} imported ({:.1f}%), {} rendered on Vulkan ({:.1f}%), {:.1f} s{}\n", n,
                   r.shard_index, r.shard_count, imported, n ? 100.0 * imported / n : 0.0, vulkan, n ? 100.0 * vulkan / n : 0.0,
                   secs, a->report.empty() ? "" : "; dashboard: " + a->report + "/corpus.html");
        for (size_t t = 1; t < r.targets.size(); ++t) {
            size_t agrees = 0;
            for (const CorpusRow& row : r.rows) agrees += row.targets.at(r.targets[t]).status == "agrees";
            fmt::print("  {:<10} {} agree with Vulkan ({:.1f}%)\n", r.targets[t], agrees, n ? 100.0 * agrees / n : 0.0);
        }
        if (a->fail_under > 0 && n && 100.0 * static_cast<double>(vulkan) / static_cast<double>(n) < a->fail_under) return kExitValidation;
        return kExitOk;
    };
}

}  // namespace crtforge::cli
