// crtforge generate --preset P --target T [--out DIR]   and   crtforge assemble --preset P
#include <fmt/format.h>

#include "cli/cli_common.hpp"

namespace crtforge::cli {

namespace {

struct GenerateArgs {
    std::string preset, target, out;
    VariantFlags flags;
};

}  // namespace

Runner add_generate_command(CLI::App& app, const GlobalOptions& g) {
    auto args = std::make_shared<GenerateArgs>();
    auto* cmd = app.add_subcommand("generate", "Generate one preset for one target");
    cmd->add_option("--preset", args->preset, "Preset name (see 'crtforge list presets')")->required();
    cmd->add_option("--target", args->target, "Target name (see 'crtforge list targets')")->required();
    cmd->add_option("--out", args->out,
                    "Write the files into this directory; without it the fragment shader is printed "
                    "(SPIR-V as disassembly)");
    args->flags.add_to(*cmd);
    return [&g, args]() {
        int code = kExitOk;
        auto found = lookup_target(args->target);
        if (!found.ok()) return report(found.error());
        const TargetInfo* target = found.value();
        auto options = args->flags.parse();
        if (!options.ok()) return report(options.error());
        auto lib = load_library(g, code);
        if (!lib) return code;
        auto preset_found = lookup_preset(*lib, args->preset);
        if (!preset_found.ok()) return report(preset_found.error());
        const Preset* preset = preset_found.value();
        Cache cache = make_cache(g);
        auto compiled = compile_variant(*lib, *preset, options.value(), cache);
        if (!compiled.ok()) return report(compiled.error());
        auto out = emit_target(compiled.value(), target->id, cache);
        if (!out.ok()) return report(out.error());
        if (args->out.empty()) {
            if (target->id == TargetId::Spirv) {
                fmt::print("{}", disassemble_spirv(compiled.value().fragment));
            } else {
                for (const auto& f : out.value().files)
                    if (f.manifest_role() == "fragment" || f.manifest_role() == "shader") fmt::print("{}", f.data);
            }
            return kExitOk;
        }
        std::map<std::string, std::string> files;
        for (const auto& f : out.value().files) files[f.path.empty() ? preset->name + f.suffix : f.path] = f.data;
        if (auto s = write_files(args->out, files); !s.ok()) return report(s.error());
        for (const auto& [path, data] : files) fmt::print("{}/{}\n", args->out, path);
        return kExitOk;
    };
}

Runner add_assemble_command(CLI::App& app, const GlobalOptions& g) {
    auto args = std::make_shared<GenerateArgs>();
    auto* cmd = app.add_subcommand("assemble",
                                   "Print the GLSL 450 that crtforge feeds to glslang for a preset (before SPIR-V)");
    cmd->add_option("--preset", args->preset, "Preset name")->required();
    args->flags.add_to(*cmd);
    return [&g, args]() {
        int code = kExitOk;
        auto options = args->flags.parse();
        if (!options.ok()) return report(options.error());
        auto lib = load_library(g, code);
        if (!lib) return code;
        auto preset = lookup_preset(*lib, args->preset);
        if (!preset.ok()) return report(preset.error());
        auto variant = make_variant(*lib, *preset.value(), options.value());
        if (!variant.ok()) return report(variant.error());
        fmt::print("{}", assemble(*lib, variant.value()).fragment);
        return kExitOk;
    };
}

}  // namespace crtforge::cli
