// crtforge: a thin command line over the crtforge library.
#include <cmath>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <new>
#include <set>
#include <iostream>

#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/process_memory.hpp"
#include "crtforge/slang_import.hpp"
#include "crtforge/version.hpp"

namespace crtforge::cli {

namespace {

// The overlay a command's .slangp arguments are imported into, and each imported preset's name and
// .slangp path: an error in a file of that temporary overlay (gone once crtforge exits) is told
// at the .slangp the user gave.
struct ImportedArguments {
    std::string overlay;
    std::vector<std::pair<std::string, std::string>> presets;  // imported name, .slangp path
};
ImportedArguments& imported_arguments() {
    static ImportedArguments imported;
    return imported;
}

// `d` with a file inside the temporary overlay named as the .slangp it came from, the overlay
// file and line kept in the message.
Diagnostic at_user_file(const Diagnostic& d) {
    const ImportedArguments& imported = imported_arguments();
    const std::string prefix = imported.overlay + "/";
    if (imported.overlay.empty() || imported.presets.empty() || d.file.compare(0, prefix.size(), prefix) != 0) return d;
    const std::string inside = d.file.substr(prefix.size());
    const std::string* slangp = &imported.presets.front().second;
    for (const auto& [name, path] : imported.presets)
        for (const std::string& start : {"presets/" + name + ".", "presets/" + name + "/", "stages/ra_" + name + ".", "stages/ra_" + name + "/"})
            if (inside.compare(0, start.size(), start) == 0) slangp = &path;
    Diagnostic out = d;
    out.file = *slangp;
    out.line = 0;
    out.column = 0;
    out.message += " (in its import: " + inside + (d.line > 0 ? ":" + std::to_string(d.line) : std::string()) + ")";
    return out;
}

}  // namespace

int report(const Diagnostic& d) {
    std::fprintf(stderr, "crtforge: %s\n", at_user_file(d).str().c_str());
    return d.kind == ErrorKind::Validation ? kExitValidation : kExitUsage;
}

namespace {

bool is_slangp(const std::string& arg) {
    return arg.size() > 7 && arg.compare(arg.size() - 7, 7, ".slangp") == 0;
}

// Imports every .slangp among `presets` (RetroArch's settings: crtforge import's defaults) into
// one overlay and replaces each by the imported preset's name. "" when there is none.
Result<std::string> import_preset_arguments(const GlobalOptions& g, std::vector<std::string>& presets) {
    if (std::none_of(presets.begin(), presets.end(), is_slangp)) return std::string();
    if (!g.templates.empty())
        return make_error("a .slangp preset is imported on top of the shipped templates: give it without --templates", {}, 0,
                          "--templates");
    // Removed when crtforge exits: the library reads the LUT files from it until then.
    static std::optional<TemporaryFolder> overlay;
    if (!overlay) {
        auto made = TemporaryFolder::create("crtforge-slangp");
        if (!made.ok()) return made.error();
        overlay.emplace(std::move(made.value()));
    }
    const std::string dir = (overlay->path() / "overlay").string();
    imported_arguments().overlay = dir;
    std::set<std::string> names;
    for (std::string& p : presets) {
        if (!is_slangp(p)) continue;
        auto imported = import_slangp(p, SlangImportOptions{});
        if (!imported.ok()) return imported.error();
        for (const std::string& w : imported.value().warnings) std::fprintf(stderr, "crtforge: %s\n", w.c_str());
        if (!names.insert(imported.value().name).second)
            return make_error("two .slangp presets import as '" + imported.value().name + "'; import them with crtforge import --name", p, 0,
                              "--preset");
        if (auto s = write_imported_preset(imported.value(), dir); !s.ok()) return s.error();
        imported_arguments().presets.emplace_back(imported.value().name, p);
        p = imported.value().name;
    }
    return dir;
}

}  // namespace

std::shared_ptr<TemplateLibrary> load_library(const GlobalOptions& g, int& exit_code, std::vector<std::string>* presets) {
    std::string dir = g.templates.empty() ? TemplateLibrary::default_dir() : g.templates;
    if (presets) {
        auto overlay = import_preset_arguments(g, *presets);
        if (!overlay.ok()) {
            exit_code = report(overlay.error());
            return nullptr;
        }
        if (!overlay.value().empty()) dir = overlay.value();
    }
    auto lib = TemplateLibrary::load(dir);
    if (!lib.ok()) {
        exit_code = report(lib.error());
        return nullptr;
    }
    for (const std::string& w : lib.value()->warnings()) std::fprintf(stderr, "crtforge: %s\n", w.c_str());
    // A broken preset stops a command over every preset, each broken one said on its line; a
    // command naming other presets runs (naming a broken one gets its error from lookup_preset).
    if ((!presets || presets->empty()) && !lib.value()->broken_presets().empty()) {
        for (const auto& [name, error] : lib.value()->broken_presets()) exit_code = report(error);
        return nullptr;
    }
    return lib.value();
}

Result<const Preset*> lookup_preset(const TemplateLibrary& lib, const std::string& name) {
    return lib.lookup_preset(name);
}

void draw_progress_bar(size_t done, size_t total, const std::string& text) {
    const int width = 30, filled = total ? static_cast<int>(width * done / total) : width;
    fmt::print("\r\033[K[{}{}] {}", std::string(filled, '#'), std::string(width - filled, '.'), text);
    if (done == total) fmt::print("\n");
    std::fflush(stdout);
}

void report_progress(bool tty, size_t done, size_t total, const std::string& label, const std::string& text, size_t log_lines) {
    if (tty) {
        draw_progress_bar(done, total, text);
    } else if (done == total || (total && done * log_lines / total != (done - 1) * log_lines / total)) {
        fmt::print("{}: {}\n", label, text);
        std::fflush(stdout);
    }
}

Cache make_cache(const GlobalOptions& g) {
    if (g.no_cache) return Cache();
    return Cache(g.cache_dir.empty() ? Cache::default_dir() : g.cache_dir);
}

void VariantFlags::add_to(CLI::App& cmd) {
    cmd.add_option("--uniforms", uniforms,
                   "Which params stay runtime uniforms: default (the spec's runtime params), all, none, NAME,NAME,..., or uber (the all-stages uber-shader: every stage behind an int switch uniform crtStage_<stage>, every param a uniform)")
        ->capture_default_str();
    cmd.add_option("--precision", precision, "Float precision of the variant: high or medium")
        ->check(CLI::IsMember({"high", "medium"}))
        ->capture_default_str();
}

Result<VariantOptions> VariantFlags::parse() const {
    VariantOptions options;
    auto sel = UniformSelection::parse(uniforms);
    if (!sel.ok()) return sel.error();
    options.uniforms = sel.value();
    options.precision = precision == "medium" ? Precision::Medium : Precision::High;
    return options;
}

}  // namespace crtforge::cli

namespace {

// The first value given to an option of `app` or of its subcommands (flags have none) for which
// `finding` says something; what it said, or empty.
template <typename Finding>
std::string find_in_option_values(const CLI::App& app, const Finding& finding) {
    for (const CLI::Option* option : app.get_options()) {
        if (option->get_type_size() == 0 || option->count() == 0) continue;  // a flag, or not given
        for (const std::string& value : option->results())
            if (std::string found = finding(app, *option, value); !found.empty()) return found;
    }
    for (const CLI::App* sub : app.get_subcommands())
        if (std::string found = find_in_option_values(*sub, finding); !found.empty()) return found;
    return {};
}

// The name of an option given an empty value (--templates "").
std::string empty_option_value(const CLI::App& app) {
    return find_in_option_values(app, [](const CLI::App&, const CLI::Option& option, const std::string& value) {
        return value.empty() ? option.get_name() : std::string();
    });
}

// "--preset --target glsl330": CLI11 takes an option's name as the value of the option before it
// (which then reports some other option missing). Found as a value that names an option of its
// command: "<option> has no value" instead.
std::string option_taken_as_value(const CLI::App& app) {
    return find_in_option_values(app, [](const CLI::App& command, const CLI::Option& option, const std::string& value) {
        if (value.size() > 1 && value[0] == '-' && command.get_option_no_throw(value) != nullptr)
            return option.get_name() + " has no value ('" + value + "' is an option of its own)";
        return std::string();
    });
}

}  // namespace

int main(int argc, char** argv) {
    crtforge::keep_freed_memory();  // before anything allocates an image
    crtforge::set_lut_picture_decoder(&crtforge::read_lut_picture);  // exports ship JPEG LUTs as PNG
    // A file-size limit (ulimit -f) would kill the process by signal mid-write, leaving a partial
    // file: ignored, the write fails with EFBIG instead and the error paths clean up as on a full disk.
    std::signal(SIGXFSZ, SIG_IGN);
    using namespace crtforge::cli;
    CLI::App app{"crtforge: generate, cross-compile and export CRT shader variants"};
    app.set_version_flag("--version", std::string("crtforge ") + CRTFORGE_VERSION);
    app.require_subcommand(1);
    GlobalOptions g;
    app.add_option("--templates", g.templates, "Template directory (stages/, presets/); default: the shipped templates");
    app.add_option("--cache-dir", g.cache_dir, "Compile cache directory; default: $CRTFORGE_CACHE or ~/.cache/crtforge");
    app.add_flag("--no-cache", g.no_cache, "Compile everything afresh and store nothing");
    app.add_option("--gpu-timeout", g.gpu_timeout,
                   "Seconds one submission of GPU work may take before the run stops with an error naming the draw (a shader "
                   "loop that never ends); 0: no limit")
        ->check(CLI::Validator(
            [](std::string& v) {
                double s = 0;
                const bool read = CLI::detail::lexical_cast(v, s);
                return read && std::isfinite(s) && s >= 0 && s <= 1e6 ? std::string() : "a number of seconds from 0 to 1000000";
            },
            "SECONDS"))
        ->capture_default_str();

    std::vector<std::pair<CLI::App*, Runner>> commands;
    auto track = [&](Runner r) { commands.emplace_back(app.get_subcommands({}).back(), std::move(r)); };
    track(add_list_command(app, g));
    track(add_generate_command(app, g));
    track(add_assemble_command(app, g));
    track(add_export_command(app, g));
    track(add_validate_command(app, g));
    track(add_report_command(app, g));
    track(add_render_command(app, g));
    track(add_golden_command(app, g));
    track(add_devices_command(app, g));
    track(add_bench_command(app, g));
    track(add_import_command(app, g));
    track(add_corpus_command(app, g));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string msg = option_taken_as_value(app);
        if (msg.empty()) msg = e.what();
        for (char& c : msg) if (c == '\n') c = ' ';
        std::fprintf(stderr, "crtforge: error: %s (see 'crtforge --help')\n", msg.c_str());
        return kExitUsage;
    }
    // An option given with an empty value (--templates "", --size "") is a mistake, not the
    // option left out: refused, naming the option, before any command runs.
    if (const std::string taken = option_taken_as_value(app); !taken.empty()) {
        std::fprintf(stderr, "crtforge: error: %s (see 'crtforge --help')\n", taken.c_str());
        return kExitUsage;
    }
    if (const std::string empty = empty_option_value(app); !empty.empty()) {
        std::fprintf(stderr, "crtforge: error: %s has an empty value (give a value, or leave the option out)\n", empty.c_str());
        return kExitUsage;
    }
    crtforge::set_gpu_timeout(g.gpu_timeout);
    // The cache folder, from --cache-dir or the environment: set but empty, or something other than
    // a folder (a file, /dev/null), is refused rather than quietly read and written as a cache.
    if (!g.no_cache) {
        const char* env = std::getenv("CRTFORGE_CACHE");
        if (g.cache_dir.empty() && env && !*env) return crtforge::cli::report(crtforge::make_error("is set but empty (give a folder, or unset it)", {}, 0, "CRTFORGE_CACHE"));
        const std::string cache = g.cache_dir.empty() ? crtforge::Cache::default_dir() : g.cache_dir;
        std::error_code ec;
        if (!cache.empty() && std::filesystem::exists(cache, ec) && !std::filesystem::is_directory(cache, ec))
            return crtforge::cli::report(crtforge::make_error("is not a folder (the compile cache is one)", cache, 0,
                                     !g.cache_dir.empty() ? "--cache-dir" : env && *env ? "CRTFORGE_CACHE" : "cache folder"));
    }
    // Every failure is meant to arrive as a Diagnostic; this is the last line of defence, so an
    // exception that escapes anyway is still one line and exit 2, never an abort.
    try {
        for (auto& [cmd, run] : commands)
            if (cmd->parsed()) return run();
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "crtforge: error: out of memory (an input beyond what this machine holds?)\n");
        return kExitUsage;
    } catch (const std::exception& e) {
        std::string msg = e.what();
        for (char& c : msg) if (c == '\n') c = ' ';
        std::fprintf(stderr, "crtforge: internal error: %s (a crtforge bug: please report it with the command line)\n", msg.c_str());
        return kExitUsage;
    }
    return kExitUsage;
}
