// crtforge bench [--preset NAME ...] [--size WxH,...] [--input NAME] [--frame N] [--draws N] [--supersample N]
//                [--repeats N] [--device NAME|INDEX] [--uniforms LIST] [--versus-retroarch] [--keep-going]
// Each pass of each preset's scene timed on Vulkan by GPU timestamps, as a ratio to a blit of the
// same sizes measured in the same run (crtforge/validate/bench.hpp). --versus-retroarch times each
// preset twice, as RetroArch compiles a .slang pass and as crtforge exports it, and reports the
// speed-up per preset and on average.
#include <algorithm>

#include <fmt/core.h>

#include "cli/cli_common.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/bench.hpp"

namespace crtforge::cli {

namespace {

// The default sizes: the three displays, a small one, HD and 4K (ratios to a blit move
// with the size: the source texture stays in cache while the target grows).
const std::vector<std::string> kDefaultSizes{"640x480", "1920x1080", "3840x2160"};
// Draws per timing when --draws is not given: as many pixels as 4 draws at 1280x960 (about 18 ms
// of blits on lavapipe at any size: 16 draws at 640x480, 2 at 1920x1080, 1 at 3840x2160, whose
// draw alone lasts 25 ms or more). Short timings catch the machine's fast spells as well as long
// ones (both sides keep their fastest), and keep the default run of every tier at three sizes
// under 10 minutes.
constexpr double kPixelsPerTiming = 4.0 * 1280 * 960;
int default_draws(int width, int height) {
    return std::clamp(static_cast<int>(std::lround(kPixelsPerTiming / (double(width) * height))), 1, 1000);
}
// Samples per axis of the supersampled reference when --supersample is not given: 4 x 4 up to
// 1920x1080, 2 x 2 above, where device pixels are small against the source's texels and a 4 x 4
// fp64 reference of every preset would take minutes.
int default_supersample(int width, int height) { return double(width) * height <= 1920.0 * 1080 ? 4 : 2; }

using Variants = std::vector<std::pair<std::string, VariantOptions>>;  // by their --uniforms label

// Each pass keeps the fastest of its two rounds' timings and the spread of both; its median and
// the scene's errors stay the first round's (the second round times only).
void keep_fastest(SceneTiming& kept, const SceneTiming& again) {
    for (size_t i = 0; i < kept.passes.size() && i < again.passes.size(); ++i) {
        PassTiming& p = kept.passes[i];
        const PassTiming& q = again.passes[i];
        const double slowest = std::max(p.ns * (1 + p.spread), q.ns * (1 + q.spread));
        p.ns = std::min(p.ns, q.ns);
        p.spread = p.ns > 0 ? slowest / p.ns - 1 : 0;
        p.own_blit_ns = std::min(p.own_blit_ns, q.own_blit_ns);
    }
    kept.retimed = kept.retimed || again.retimed;
    kept.rounds += again.rounds;
}

// One preset at one size: each tier (or the preset as written) in each variant, printed as timed.
// RetroArch's compile, when asked for, comes first: the others' frames are compared with its. Its
// variants are then timed a second time in the opposite order, each pass keeping its fastest, so a
// slow spell of the machine cannot favour whichever was timed first.
Result<std::vector<SceneTiming>> time_preset(BenchSession& session, const Preset& preset, bool tiered, bool stage_costs,
                                             const Variants& variants, BenchOptions options) {
    std::vector<PresetTier> tiers;
    if (tiered) tiers = preset_tiers(preset);
    else tiers.push_back({QualityTier::Point, preset, {}, "point", ""});
    const bool versus_retroarch =
        variants.size() > 1 && std::any_of(variants.begin(), variants.end(), [](const auto& v) { return v.first == "retroarch"; });
    std::vector<SceneTiming> out;
    for (size_t t = 0; t < tiers.size(); ++t) {
        auto time_variant = [&](const std::string& label, const VariantOptions& variant, bool timing_only) {
            BenchOptions o = options;
            o.variant = variant;
            o.uniforms_label = label;
            o.stage_costs = !timing_only && stage_costs && tiers[t].name == "point";
            if (timing_only) o.supersample = 0;  // the errors and stage costs are measured once
            return session.tier(tiers, t, o);
        };
        std::vector<SceneTiming> timed;
        std::optional<Image> retroarch_frame;  // this scene compiled as RetroArch does
        for (const auto& [label, variant] : variants) {
            auto timing = time_variant(label, variant, false);
            if (!timing.ok()) return timing.error();
            if (label == "retroarch") {
                retroarch_frame = session.last_frame();
            } else if (retroarch_frame) {
                auto same = compare_on_8bit_display(session.last_frame(), *retroarch_frame);
                if (!same.ok()) return same.error();
                timing.value().vs_retroarch_compile = same.value();
            }
            timed.push_back(std::move(timing.value()));
        }
        if (versus_retroarch)
            for (size_t v = variants.size(); v-- > 0;) {
                auto again = time_variant(variants[v].first, variants[v].second, true);
                if (!again.ok()) return again.error();
                keep_fastest(timed[v], again.value());
            }
        double retroarch_ns = 0;
        for (size_t v = 0; v < variants.size(); ++v)
            if (variants[v].first == "retroarch") retroarch_ns = timed[v].total_ns();
        for (SceneTiming& timing : timed) {
            if (timing.vs_retroarch_compile) timing.retroarch_compile_ns = retroarch_ns;
            fmt::print("{}{}{}\n", timing.retimed ? "timed twice (the blits beside the first timing all ran slow):\n" : "",
                       format_scene_timing(timing),
                       tiers[t].changes.empty() ? std::string() : "tier: " + join_list(tiers[t].changes) + "\n");
            std::fflush(stdout);
            out.push_back(std::move(timing));
        }
    }
    return out;
}

}  // namespace

Runner add_bench_command(CLI::App& app, const GlobalOptions& g) {
    auto* cmd = app.add_subcommand("bench", "Time every pass of presets on Vulkan (GPU timestamps) as ratios to a same-size blit");
    struct Options {
        std::vector<std::string> presets, sizes = kDefaultSizes;
        std::string input = "pixel_art", device;
        int frame = 1, draws = 0, repeats = 5, supersample = 4;  // draws 0: default_draws()
        std::string out;
        bool quick = false, no_tiers = false, stage_costs = false, versus_retroarch = false, keep_going = false;
        std::vector<std::string> uniforms{"default"};
    };
    auto o = std::make_shared<Options>();
    cmd->add_option("--preset", o->presets, "Presets to time (repeat or comma-separate; a RetroArch .slangp file is imported first; default: all)")->delimiter(',');
    cmd->add_option("--size", o->sizes, "Display sizes WIDTHxHEIGHT, each timed and measured (repeat or comma-separate)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--input", o->input, "Generated test input, at the preset's source size")->capture_default_str();
    // Earlier frames run first (a scene with feedback needs them): bounded, so a bench never runs for hours.
    cmd->add_option("--frame", o->frame, "Frame whose passes are timed (earlier frames run first)")
        ->check(CLI::Range(0, 10000))
        ->capture_default_str();
    auto* draws = cmd->add_option("--draws", o->draws, "Draws per timing (default: as many pixels as 4 draws at 1280x960: 16 at 640x480, 2 at 1920x1080, 1 at 3840x2160)")
                      ->check(CLI::Range(1, 100000));
    cmd->add_option("--repeats", o->repeats, "Timings per pass (the fastest is reported, the median and spread beside it; the blit takes the fastest of max(N, 5), beside the first of a size eight more)")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--device", o->device, "Vulkan device (see 'crtforge devices'); default: lavapipe");
    cmd->add_option("--out", o->out, "Also write bench.json, bench.md and bench.svg (error against cost, Pareto front) here");
    auto* uniforms = cmd->add_option("--uniforms", o->uniforms,
                    "Which params stay uniforms, one variant per entry: default, all, none, uber (one shader for every preset: every stage behind a runtime switch; e.g. none,default,all,uber: what each live param costs, and what specialising saves), or retroarch (every param a uniform and no optimisation: glslang's SPIR-V as it is, as RetroArch compiles a .slang pass)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_flag("--no-tiers", o->no_tiers, "Time each preset as written, not each of its quality tiers (point, each filtered stage alone, filtered)");
    cmd->add_flag("--stage-costs", o->stage_costs,
                  "Also time each pass once per stage with that stage off, on the point tier: what each stage costs");
    cmd->add_flag("--versus-retroarch", o->versus_retroarch,
                  "Time each preset as RetroArch compiles it (--uniforms retroarch) and as crtforge exports it (spirv-opt, pow "
                  "reduction, parameters baked: --uniforms none), untiered, and report the speed-up per preset and on average; "
                  "the two frames must look the same on an 8-bit display; both are timed in two rounds, the second in the "
                  "opposite order, each pass keeping its fastest")
        ->excludes(uniforms);
    cmd->add_flag("--keep-going", o->keep_going,
                  "A preset that fails to compile or render is reported on one line and the others are timed; exit 1 at the end");
    cmd->add_flag("--quick", o->quick, "320x240, 5 draws, 3 repeats, 2x2 supersampling: every preset in well under a minute");
    auto* supersample = cmd->add_option("--supersample", o->supersample,
                                        "Error against the point-sampled fp64 reference and an N x N supersampled one (0: no error "
                                        "columns; default: 4 up to 1920x1080, 2 above)")
                            ->check(CLI::Range(0, 16));
    return [&g, o, draws, supersample]() {
        int code = kExitOk;
        auto lib = load_library(g, code, &o->presets);
        if (!lib) return code;
        const bool draws_given = draws->count() > 0, supersample_given = supersample->count() > 0;
        if (o->versus_retroarch) {
            o->uniforms = {"retroarch", "none"};
            o->no_tiers = true;
        }
        if (o->quick) {
            o->sizes = {"320x240"};
            if (!draws_given) o->draws = 5;
            o->repeats = 3;
            o->supersample = std::min(supersample_given ? o->supersample : 2, 2);
        }
        drop_repeats(o->sizes);
        std::vector<std::pair<int, int>> sizes;
        for (const std::string& text : o->sizes) {
            auto size = parse_size(text);
            if (!size.ok()) return report(size.error());
            sizes.push_back(size.value());
        }
        if (o->frame < 0) return report(make_error("must be 0 or more", {}, 0, "--frame"));
        const auto& inputs = test_input_names();
        if (std::find(inputs.begin(), inputs.end(), o->input) == inputs.end())
            return report(make_error("'" + o->input + "' is not a generated test input (" + join_list(inputs) + ")", {}, 0, "--input"));
        std::vector<const Preset*> presets;
        if (o->presets.empty())
            for (const Preset& p : lib->presets())
                if (!p.test_only) presets.push_back(&p);
        for (const std::string& name : o->presets) {
            auto p = lookup_preset(*lib, name);
            if (!p.ok()) return report(p.error());
            presets.push_back(p.value());
        }
        BenchOptions options;
        options.input = o->input;
        options.frame = o->frame;
        options.repeats = o->repeats;
        options.vulkan.device = o->device;
        Variants variants;
        for (const std::string& u : o->uniforms) {
            if (u != "default" && u != "all" && u != "none" && u != "uber" && u != "retroarch")
                return report(make_error("'" + u + "' must be default, all, none, uber or retroarch", {}, 0, "--uniforms"));
            VariantFlags flags;
            flags.uniforms = u == "retroarch" ? "all" : u;
            auto parsed = flags.parse();
            if (!parsed.ok()) return report(parsed.error());
            parsed.value().optimize = u != "retroarch";
            if (std::none_of(variants.begin(), variants.end(), [&](const auto& v) { return v.first == u; }))
                variants.emplace_back(u, parsed.value());
        }
        // RetroArch's compile first: every other variant of the scene is compared with its frame.
        std::stable_partition(variants.begin(), variants.end(), [](const auto& v) { return v.first == "retroarch"; });
        std::vector<SceneTiming> timings;
        BenchSession session(*lib, options.vulkan);
        int failed = 0;
        for (const auto& [width, height] : sizes)
            for (const Preset* preset : presets) {
                options.width = width;
                options.height = height;
                options.draws = draws_given || o->quick ? o->draws : default_draws(width, height);
                options.supersample = supersample_given || o->quick ? o->supersample : default_supersample(width, height);
                auto timed = time_preset(session, *preset, !o->no_tiers, o->stage_costs, variants, options);
                if (timed.ok()) {
                    for (SceneTiming& timing : timed.value()) timings.push_back(std::move(timing));
                    continue;
                }
                if (!o->keep_going) return report(timed.error());
                report(timed.error());
                ++failed;
            }
        // The summary: every ratio against the run's fastest blit of its shape (the tables above
        // were printed with the fastest known when each scene ran).
        for (SceneTiming& timing : timings) session.rebase(timing);
        const std::string markdown = bench_markdown(timings);
        if (timings.size() > 1 || !o->out.empty()) fmt::print("{}", markdown);
        if (!o->out.empty()) {
            for (const auto& [name, text] : {std::pair<std::string, std::string>{"bench.json", bench_json(timings)},
                                             {"bench.md", markdown}, {"bench.svg", bench_svg(timings)}})
                if (auto s = write_file_atomic(o->out + "/" + name, text); !s.ok()) return report(s.error());
            fmt::print("bench: {} scenes into {}/bench.json, bench.md, bench.svg\n", timings.size(), o->out);
        }
        if (failed > 0) {
            fmt::print(stderr, "bench: {} of {} preset timings failed (above)\n", failed, presets.size() * sizes.size());
            return kExitValidation;
        }
        return kExitOk;
    };
}

}  // namespace crtforge::cli
