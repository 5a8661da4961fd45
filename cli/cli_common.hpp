// What every crtforge subcommand shares: global options, loading the template library, printing
// diagnostics as one line, and the exit-code convention (0 ok, 1 validation failure, 2 bad input).
#pragma once

#include <algorithm>

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "crtforge/crtforge.hpp"
#include "crtforge/runtime/gpu_watchdog.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitValidation = 1;
inline constexpr int kExitUsage = 2;

struct GlobalOptions {
    std::string templates;   // --templates
    std::string cache_dir;   // --cache-dir
    bool no_cache = false;   // --no-cache
    double gpu_timeout = kDefaultGpuTimeoutSeconds;  // --gpu-timeout
};

// Prints "crtforge: <diagnostic>" to stderr and returns the matching exit code.
int report(const Diagnostic& d);

// Loads the library named by --templates (or the default); nullptr after reporting on failure.
// With `presets`, a .slangp path among them (RetroArch's preset file) is imported first into a
// temporary overlay on the shipped templates, and replaced by the imported preset's name.
std::shared_ptr<TemplateLibrary> load_library(const GlobalOptions& g, int& exit_code, std::vector<std::string>* presets = nullptr);
Cache make_cache(const GlobalOptions& g);

// Shared variant options (--uniforms, --precision) for generate/export/assemble.
struct VariantFlags {
    std::string uniforms = "default";
    std::string precision = "high";
    void add_to(CLI::App& cmd);
    Result<VariantOptions> parse() const;
};

// Each subcommand registers itself and returns the function to run when it was chosen.
using Runner = std::function<int()>;
Runner add_list_command(CLI::App& app, const GlobalOptions& g);
Runner add_generate_command(CLI::App& app, const GlobalOptions& g);
Runner add_assemble_command(CLI::App& app, const GlobalOptions& g);
Runner add_export_command(CLI::App& app, const GlobalOptions& g);
Runner add_validate_command(CLI::App& app, const GlobalOptions& g);
Runner add_report_command(CLI::App& app, const GlobalOptions& g);
Runner add_render_command(CLI::App& app, const GlobalOptions& g);
Runner add_golden_command(CLI::App& app, const GlobalOptions& g);
Runner add_devices_command(CLI::App& app, const GlobalOptions& g);
Runner add_bench_command(CLI::App& app, const GlobalOptions& g);
Runner add_import_command(CLI::App& app, const GlobalOptions& g);
Runner add_corpus_command(CLI::App& app, const GlobalOptions& g);

// TemplateLibrary::lookup_preset, for symmetry with crtforge::lookup_target.
Result<const Preset*> lookup_preset(const TemplateLibrary& lib, const std::string& name);

// On a terminal, a progress bar drawn in place: "[#####.....] text", ended by a newline once
// done == total.
void draw_progress_bar(size_t done, size_t total, const std::string& text);
// A long run's progress: the bar on a terminal; in a log (`tty` false), "<label>: <text>" each
// time another 1/log_lines of the run is done, and at its end.
void report_progress(bool tty, size_t done, size_t total, const std::string& label, const std::string& text, size_t log_lines);

// Shared parsing helpers.
Result<std::pair<int, int>> parse_size(const std::string& text);   // "WxH"
// --fit: stretch, aspect or integer; empty: none given.
Result<std::optional<DisplayFit>> parse_fit(const std::string& text);

// Repeated --preset / --target entries name one thing once: the first of each is kept, in order.
template <typename T>
void drop_repeats(std::vector<T>& items) {
    std::vector<T> kept;
    for (const T& item : items)
        if (std::find(kept.begin(), kept.end(), item) == kept.end()) kept.push_back(item);
    items = std::move(kept);
}
std::string default_golden_dir();                                    // $CRTFORGE_GOLDEN or the source tree's golden/

}  // namespace crtforge::cli
