// crtforge import FILE.slangp --out DIR: a RetroArch preset as a crtforge template overlay
// (crtforge/slang_import.hpp), used with `crtforge --templates DIR ... --preset NAME`.
#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/slang_import.hpp"

namespace crtforge::cli {

namespace {
struct ImportArgs {
    std::string file, out, root, name, source_size, fit = "aspect";
    bool smooth = false, quiet = false;
};
Result<SlangImportOptions> slang_import_options(const std::string& root, const std::string& name, bool smooth,
                                                const std::string& source_size, const std::string& fit) {
    SlangImportOptions options;
    options.root = root;
    options.name = name;
    if (!name.empty() && !is_preset_name(name))
        return make_error("'" + name + "' must be 1 to 64 lower-case letters, digits, '-' or '_', starting with a letter or digit", {}, 0, "--name");
    options.unset_filter = smooth ? Filter::Linear : Filter::Nearest;
    if (!source_size.empty()) {
        auto size = parse_size(source_size);
        if (!size.ok()) return make_error(size.error().message, {}, 0, "--source-size");
        options.source_width = size.value().first;
        options.source_height = size.value().second;
    }
    auto parsed_fit = parse_fit(fit);
    if (!parsed_fit.ok()) return parsed_fit.error();
    options.fit = parsed_fit.value().value_or(DisplayFit::Aspect);
    return options;
}

}  // namespace

Runner add_import_command(CLI::App& app, const GlobalOptions&) {
    auto args = std::make_shared<ImportArgs>();
    auto* cmd = app.add_subcommand("import", "Import a RetroArch .slangp preset as a crtforge template overlay");
    cmd->add_option("file", args->file, "The .slangp preset")->required();
    cmd->add_option("--out", args->out, "The overlay folder to write (stages/, presets/); use it with --templates")->required();
    cmd->add_option("--root", args->root, "No file the preset reads may lie outside this folder (default: no limit)");
    cmd->add_option("--name", args->name, "The crtforge preset's name (default: from the file name)");
    cmd->add_flag("--smooth", args->smooth, "Sample textures whose filter the preset leaves unset linearly (RetroArch's video_smooth)");
    cmd->add_option("--source-size", args->source_size, "The source picture's size WxH (default: the input's own)");
    cmd->add_option("--fit", args->fit, "How the screen sits in the display: stretch, aspect (default), integer");
    cmd->add_flag("--quiet,-q", args->quiet, "Print nothing on success");
    return [args]() {
        auto options = slang_import_options(args->root, args->name, args->smooth, args->source_size, args->fit);
        if (!options.ok()) return report(options.error());
        auto imported = import_slangp(args->file, options.value());
        if (!imported.ok()) return report(imported.error());
        for (const std::string& w : imported.value().warnings) fmt::print(stderr, "crtforge: {}\n", w);
        if (auto s = write_imported_preset(imported.value(), args->out); !s.ok()) return report(s.error());
        if (!args->quiet)
            fmt::print("imported {} as preset '{}' ({} passes, {} files) into {}: use --templates {} --preset {}\n", args->file,
                       imported.value().name, imported.value().passes, imported.value().files.size(), args->out, args->out, imported.value().name);
        return kExitOk;
    };
}

}  // namespace crtforge::cli
