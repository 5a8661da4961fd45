// crtforge generate --preset P --target T [--out DIR] [--resolution WxH --max-error E --max-cost C]
// and crtforge assemble --preset P
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/validate/bench.hpp"

namespace crtforge::cli {

namespace {

struct GenerateArgs {
    std::string preset, target, out, tier;
    VariantFlags flags;
    // Budget mode: the tier to generate is measured at this display size.
    std::string resolution, device;
    double max_error = -1, max_cost = -1;
    CLI::Option *max_error_given = nullptr, *max_cost_given = nullptr;
    int supersample = 4;
};

// Why a tier's masks alias or not: the width of their stripes in output pixels (masks follow
// output pixels; the CRT-effect document warns about masks under 4 px).
std::string mask_note(const Preset& preset) {
    std::string note;
    for (const Pass& pass : preset.passes) {
        const ResolvedStage* mask = pass.find_stage("mask");
        if (!mask || !mask->form || !mask->values.count("maskSize")) continue;
        const std::string form = mask->form->quality_of.empty() ? mask->form->name : mask->form->quality_of;
        if (form != "shadow" && form != "grille") continue;
        const double* size = std::get_if<double>(&mask->values.at("maskSize"));
        if (!size) continue;
        const double stripe = form == "shadow" ? *size / 3.0 : *size;
        note += fmt::format("; the {} mask's stripes are {:.2f} px wide{}", form, stripe,
                            stripe < 4.0 ? " (under 4 px a point-sampled mask shows moire)" : "");
    }
    return note;
}

// Budget mode: the cheapest quality tier of `preset` whose error against the supersampled
// reference at the given size is at most --max-error and whose measured GPU cost is at most
// --max-cost (ratio to a blit), each tier rendered on Vulkan. Tiers are ordered by the work they
// do (point, each filtered stage alone, all filtered), so the choice under --max-error alone does
// not depend on timing noise. The reasoning goes to stderr; the chosen tier is returned.
Result<PresetTier> choose_tier(const TemplateLibrary& lib, const Preset& preset, const GenerateArgs& a, int width, int height) {
    std::vector<PresetTier> tiers = preset_tiers(preset);
    BenchOptions options;
    options.width = width;
    options.height = height;
    options.draws = 10;
    options.repeats = 3;
    options.supersample = a.max_error >= 0 ? a.supersample : 0;
    options.point_reference = false;
    EngineOptions vulkan;
    vulkan.device = a.device;
    BenchSession session(lib, vulkan);
    std::vector<std::string> misses;
    for (size_t i = 0; i < tiers.size(); ++i) {
        PresetTier& tier = tiers[i];
        auto timing = session.tier(tiers, i, options);
        if (!timing.ok()) return timing.error();
        const SceneTiming& t = timing.value();
        const double cost = t.ratio();
        const double error = t.vs_supersampled ? t.vs_supersampled->rmse : 0.0;
        std::string figures = fmt::format("cost {:.2f}x blit", cost);
        if (t.vs_supersampled) figures = fmt::format("RMSE {:.5f} against the {}x{} supersampled reference, ", error, a.supersample, a.supersample) + figures;
        const std::string what = tier.changes.empty() ? "as written" : join_list(tier.changes);
        std::string over;
        if (a.max_error >= 0 && error > a.max_error) over += fmt::format(" error over {}", a.max_error);
        if (a.max_cost >= 0 && cost > a.max_cost) over += fmt::format(" cost over {}", a.max_cost);
        if (!over.empty()) {
            fmt::print(stderr, "budget: tier '{}' ({}) at {}x{}: {}:{}\n", tier.name, what, width, height, figures, over);
            misses.push_back(fmt::format("'{}' {}", tier.name, figures));
            continue;
        }
        fmt::print(stderr, "budget: chose tier '{}' ({}) at {}x{}: {}, within budget{}{}\n", tier.name, what, width,
                   height, figures, misses.empty() ? " and the cheapest tier" : ", the cheapest tier that is", mask_note(tier.preset));
        return std::move(tier);
    }
    return make_validation_error("no quality tier of '" + preset.name + "' meets the budget at " + std::to_string(width) + "x" +
                                 std::to_string(height) + ": " + join_list(misses, "; "));
}

}  // namespace

Runner add_generate_command(CLI::App& app, const GlobalOptions& g) {
    auto args = std::make_shared<GenerateArgs>();
    auto* cmd = app.add_subcommand("generate", "Generate one preset for one target");
    cmd->add_option("--preset", args->preset, "Preset name (see 'crtforge list presets'), or a RetroArch .slangp file (imported first)")->required();
    cmd->add_option("--target", args->target, "Target name (see 'crtforge list targets')")->required();
    cmd->add_option("--out", args->out,
                    "Write the files into this directory; without it the fragment shader is printed "
                    "(SPIR-V as disassembly)");
    cmd->add_option("--tier", args->tier,
                    "Generate this quality tier of the preset (crtforge bench lists them: point, filtered, filtered:<stage>, a tier "
                    "the preset declares, <tier>+filtered)");
    cmd->add_option("--resolution", args->resolution,
                    "Budget mode: generate the cheapest quality tier (point, each filtered stage alone, all filtered) that meets --max-error and/or "
                    "--max-cost at this display size WIDTHxHEIGHT, each measured on Vulkan");
    args->max_error_given = cmd->add_option("--max-error", args->max_error, "Budget mode: largest RMSE against the supersampled fp64 reference")
                                ->check(CLI::Range(0.0, 1.0));
    args->max_cost_given = cmd->add_option("--max-cost", args->max_cost, "Budget mode: largest GPU time per frame as a ratio to a blit")
                               ->check(CLI::Range(0.0, 1e6));
    cmd->add_option("--supersample", args->supersample, "Budget mode: N x N samples per pixel in the reference")
        ->check(CLI::Range(2, 16))
        ->capture_default_str();
    cmd->add_option("--device", args->device, "Budget mode: the Vulkan device measured (default: lavapipe)");
    args->flags.add_to(*cmd);
    return [&g, args]() {
        int code = kExitOk;
        // NaN passes CLI11's range check (every comparison with it is false): refuse it here.
        if (args->max_error_given->count() && !(args->max_error >= 0 && args->max_error <= 1))
            return report(make_error(fmt::format("'{}' must be a number from 0 to 1", args->max_error), {}, 0, "--max-error"));
        if (args->max_cost_given->count() && !(args->max_cost >= 0 && args->max_cost <= 1e6))
            return report(make_error(fmt::format("'{}' must be a number from 0 to 1000000", args->max_cost), {}, 0, "--max-cost"));
        const bool budget = args->max_error_given->count() || args->max_cost_given->count();
        if (budget && args->resolution.empty())
            return report(make_error("budget mode needs the display size it is measured at", {}, 0, "--resolution"));
        if (!budget && !args->resolution.empty())
            return report(make_error("needs --max-error or --max-cost (budget mode)", {}, 0, "--resolution"));
        std::pair<int, int> resolution{0, 0};
        if (budget) {
            auto size = parse_size(args->resolution);
            if (!size.ok()) {
                Diagnostic d = size.error();
                d.field = "--resolution";
                return report(d);
            }
            resolution = size.value();
        }
        auto found = lookup_target(args->target);
        if (!found.ok()) return report(found.error());
        const TargetInfo* target = found.value();
        auto options = args->flags.parse();
        if (!options.ok()) return report(options.error());
        std::vector<std::string> named{args->preset};
        auto lib = load_library(g, code, &named);
        if (!lib) return code;
        auto preset_found = lookup_preset(*lib, named.front());
        if (!preset_found.ok()) return report(preset_found.error());
        const Preset* preset = preset_found.value();
        std::optional<PresetTier> chosen;
        if (!args->tier.empty()) {
            if (budget) return report(make_error("give a tier or a budget (--max-error / --max-cost), not both", {}, 0, "--tier"));
            auto tier = find_tier(*preset, args->tier);
            if (!tier.ok()) return report(tier.error());
            chosen = std::move(tier.value());
            preset = &chosen->preset;
        }
        if (budget) {
            auto tier = choose_tier(*lib, *preset, *args, resolution.first, resolution.second);
            if (!tier.ok()) return report(tier.error());
            chosen = std::move(tier.value());
            preset = &chosen->preset;
        }
        Cache cache = make_cache(g);
        // Every pass of the scene (one for a single-pass preset), as export writes them.
        auto compiled = compile_scene(*lib, *preset, options.value(), cache);
        if (!compiled.ok()) return report(compiled.error());
        auto emitted = emit_scene(compiled.value(), target->id, cache);
        if (!emitted.ok()) return report(emitted.error());
        const std::vector<TargetOutput>& outputs = emitted.value();
        const bool several = outputs.size() > 1;
        if (args->out.empty()) {
            for (size_t i = 0; i < outputs.size(); ++i) {
                const CompiledVariant& pass = compiled.value()[i];
                if (several)
                    fmt::print("{} pass {} of {}: {}\n", target->id == TargetId::Spirv ? ";" : "//", i + 1, outputs.size(), pass.variant.pass->alias);
                if (target->id == TargetId::Spirv) {
                    fmt::print("{}", disassemble_spirv(pass.fragment));
                } else {
                    for (const auto& f : outputs[i].files)
                        if (f.manifest_role() == "fragment" || f.manifest_role() == "shader") fmt::print("{}", f.data);
                }
            }
            return kExitOk;
        }
        std::map<std::string, std::string> files;
        for (size_t i = 0; i < outputs.size(); ++i)
            for (const auto& f : outputs[i].files)
                files[f.path.empty() ? compiled.value()[i].variant.file_stem() + f.suffix : f.path] = f.data;
        if (several || !preset->luts.empty()) {
            // The scene's own files (a host script, a scene) and the LUTs they load, as export has them.
            auto luts = lut_files(*preset);
            if (!luts.ok()) return report(luts.error());
            auto scene = generate_target_scene(target->id, *preset, compiled.value(), outputs, luts.value());
            if (!scene.ok()) return report(scene.error());
            for (const auto& f : scene.value()) files[f.path] = f.data;
            // A target with scene files packs the LUTs it loads among them; for the others, beside the shaders.
            if (scene.value().empty())
                for (const LutSpec& lut : preset->luts) files[lut_export_path(*preset, lut)] = luts.value().at(lut.name);
        }
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
        std::vector<std::string> named{args->preset};
        auto lib = load_library(g, code, &named);
        if (!lib) return code;
        auto preset = lookup_preset(*lib, named.front());
        if (!preset.ok()) return report(preset.error());
        auto variant = make_variant(*lib, *preset.value(), options.value());
        if (!variant.ok()) return report(variant.error());
        fmt::print("{}", assemble(*lib, variant.value()).fragment);
        return kExitOk;
    };
}

}  // namespace crtforge::cli
