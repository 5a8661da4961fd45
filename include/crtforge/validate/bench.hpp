// Speed on a real device: each pass of a preset's scene timed on Vulkan (lavapipe by default) by
// GPU timestamps, against a blit — one texture read, one write — of the same input and output
// size and format, measured in the same run, so the ratios compare across machines. The jobs are
// exactly what validation renders for that frame (the pass's inputs as the scene gives them).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <optional>

#include "crtforge/preset.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

struct BenchOptions {
    int width = 1280, height = 960;  // the display
    std::string input = "pixel_art";  // a generated test input (at the preset's source size, or 320x240)
    int frame = 1;                    // the frame whose passes are timed (earlier ones run first)
    int draws = 40;                   // draws per timing
    int repeats = 5;                  // timings per pass, the fastest kept; a blit takes the fastest of max(repeats, 5)
    // Error of the timed frame against the two double-precision references: point-sampled
    // (arithmetic error) and `supersample` x `supersample` box-filtered (also aliasing). 0: none.
    int supersample = 4;
    bool point_reference = true;  // false: only the supersampled reference (budget mode)
    VariantOptions variant;       // which params stay uniforms (--uniforms), precision
    std::string uniforms_label;   // how --uniforms was written, for the report
    // Also time each pass once per enabled stage with that stage turned off: what each stage costs.
    bool stage_costs = false;
    EngineOptions vulkan;  // the device bench_scene() opens (a BenchSession is given its own)
};

// What a fragment shader does per pixel, counted statically in its SPIR-V (after crtforge's
// optimisation): instructions in its functions' blocks, texture reads (sample, fetch, gather) and
// transcendental calls (GLSL.std.450 sin .. log2, pow). A read inside a loop counts once; a module
// that does not parse counts nothing.
struct ShaderCost {
    int instructions = 0, samples = 0, transcendentals = 0;
};
ShaderCost spirv_cost(const std::vector<uint32_t>& words);

struct PassTiming {
    std::string alias;
    int width = 0, height = 0;       // the pass's output
    int input_width = 0, input_height = 0;
    std::string format;              // the pass's framebuffer format
    double ns = 0;                   // device nanoseconds per draw (the fastest timing)
    double median_ns = 0;            // the median timing
    double blit_ns = 0;              // a blit of the same sizes and format: the session's fastest
    double own_blit_ns = 0;          // the fastest of the blits timed beside this pass
    double spread = 0;               // (max - min) / min of the pass's timings
    ShaderCost cost;                 // of the pass's fragment shader
    double ratio() const { return blit_ns > 0 ? ns / blit_ns : 0; }
};

// What one stage costs: its pass's time minus the same pass's time with the stage turned off (the
// rest of the scene as it was). Stages interact (curvature gives the bezel test its work), so the
// stages' costs need not add up to the pass's.
struct StageCost {
    std::string pass, stage, form;
    double ns = 0;       // device nanoseconds per draw the stage adds (fastest against fastest)
    double blit_ns = 0;  // the pass's blit
    double ratio() const { return blit_ns > 0 ? ns / blit_ns : 0; }
};

struct SceneTiming {
    std::string preset, device;
    std::string tier;                       // the quality tier timed ("point", "filtered"; empty: the preset has none)
    std::string uniforms;                   // the variant's --uniforms selection ("default", "all", "none")
    std::vector<std::string> tier_changes;  // the forms the tier swapped (quality_tiers.hpp)
    std::string label() const {
        return (tier.empty() ? preset : preset + "@" + tier) + (uniforms.empty() || uniforms == "default" ? "" : " uniforms=" + uniforms);
    }
    ShaderCost cost() const;  // summed over the passes
    double ratio() const { return display_blit_ns > 0 ? total_ns() / display_blit_ns : 0.0; }  // the scene's cost in blits
    int width = 0, height = 0, frame = 0, draws = 0;
    std::vector<PassTiming> passes;
    double display_blit_ns = 0;      // a blit of the source onto the whole display
    int source_width = 0, source_height = 0;
    std::vector<StageCost> stage_costs;  // with BenchOptions::stage_costs
    bool retimed = false;                // timed a second time: the blits beside the first all ran slow
    // Rounds each pass was timed in, keeping its fastest: 2 with --versus-retroarch (its variants
    // timed again in the opposite order, so a slow spell cannot favour the one timed first).
    int rounds = 1;
    double total_ns() const;
    // The Vulkan frame against the point-sampled reference and the supersampled one (when measured).
    std::optional<ImageMetrics> vs_point, vs_supersampled;
    int supersample = 0;
    // Rows of the display the errors were measured on (evenly spaced bands above 1280x960
    // pixels); 0: every row.
    int error_rows = 0;
    // Pixels of those rows whose point sample sits exactly on a discontinuity (the point reference
    // flips under a jitter of 1/16384 px): each judged against the nearest of the three renders.
    int point_ties = 0;
    // With `crtforge bench --versus-retroarch`: this variant's frame against the same scene compiled
    // as RetroArch compiles it (shown on an 8-bit display: a speed-up only counts when the picture
    // is the same), and that compile's scene time.
    std::optional<ImageMetrics> vs_retroarch_compile;
    double retroarch_compile_ns = 0;
    double speedup_vs_retroarch() const { return retroarch_compile_ns > 0 && total_ns() > 0 ? retroarch_compile_ns / total_ns() : 0; }
};

// One benchmark run: the Vulkan engine, the blit it compares against and the reference pictures
// are made once and shared by every scene it measures (a reference is keyed by the preset's
// content, size, frame, input and samples, so the point tier's supersampled picture serves every
// tier and --uniforms variant of a preset at a size).
class BenchSession {
public:
    BenchSession(const TemplateLibrary& library, EngineOptions vulkan = {});
    ~BenchSession();
    BenchSession(const BenchSession&) = delete;
    BenchSession& operator=(const BenchSession&) = delete;

    // `preset`'s passes timed, and its frame's error against its own references.
    Result<SceneTiming> scene(const Preset& preset, const BenchOptions& options);
    // Tier `index` of `tiers` (preset_tiers()), named in the timing when there are several, its
    // error measured against the point tier supersampled: the picture every tier approximates (a
    // filtered tier against itself supersampled would be filtered twice, a declared tier's cheaper
    // scene would be its own yardstick).
    Result<SceneTiming> tier(const std::vector<PresetTier>& tiers, size_t index, const BenchOptions& options);
    // How many reference pictures the session has rendered (each distinct one once).
    size_t reference_renders() const;
    // The frame the last scene()/tier() rendered (the timed frame on Vulkan, as drawn).
    const Image& last_frame() const;
    // `timing`'s blits set to the fastest the session has measured of each shape: a scene timed
    // early in a run is compared against the same baseline as one timed late.
    void rebase(SceneTiming& timing) const;
    // Whether every pass of `timing` was timed while the machine ran blits at their fastest (within
    // 50 % of the session's fastest of the shape); scene() and tier() time a scene that was not
    // once more.
    bool quiet(const SceneTiming& timing) const;

private:
    // measure_once(), and once more when quiet() says the machine was slow throughout.
    Result<SceneTiming> measure(const Preset& timed, const Preset& supersampled, const BenchOptions& options);
    Result<SceneTiming> measure_once(const Preset& timed, const Preset& supersampled, const BenchOptions& options);
    struct Reference;
    // The reference picture, rendered once for every tier and variant of a preset at a size (the
    // session keeps those of one preset and size at a time: 4K pictures are 130 MB each).
    Result<const Reference*> reference(const Preset& preset, const BenchOptions& options, int supersample);
    // `point`'s picture with each tie of `frame` replaced by the nearest jittered render; none when
    // no pixel is a tie (the picture as it is, not copied: 130 MB at 4K).
    Result<std::optional<Image>> tie_tolerant(const Reference& point, const BenchOptions& options, const Image& frame, int& ties);
    Result<std::vector<StageCost>> stage_costs(const Preset& preset, const SceneTiming& timed, const BenchOptions& options);
    struct State;
    const TemplateLibrary& library_;
    std::unique_ptr<State> state_;
};

// One scene in a session of its own.
Result<SceneTiming> bench_scene(const TemplateLibrary& library, const Preset& preset, const BenchOptions& options);

// A fixed-width table: one row per pass (size, format, ns per draw, blit, ratio), then the scene.
std::string format_scene_timing(const SceneTiming& timing);

// The files of `crtforge bench --out DIR` (validate/bench_report.cpp): every figure as JSON, a
// markdown table, and an SVG plot of error (against the supersampled reference, log scale) against
// cost (ratio to a blit), each preset's Pareto front over its tiers and variants marked (errors
// compare within a preset, each being against that preset's own picture).
std::string bench_json(const std::vector<SceneTiming>& timings);
// Per preset with several tiers and per display size measured, the one to pick at that size: the filtered tier where it
// lowers the error against the supersampled reference by at least a tenth, else the cheaper point tier.
struct TierPick {
    std::string preset;
    int width = 0, height = 0;  // the display it was measured at (one pick per preset and size)
    std::string tier, why;
};
std::vector<TierPick> pick_tiers(const std::vector<SceneTiming>& timings);
std::string bench_markdown(const std::vector<SceneTiming>& timings);
std::string bench_svg(const std::vector<SceneTiming>& timings);
// Two renders of one scene on an 8-bit display (values clamped to 0..1, a NaN shown as 0, 1/255
// steps) compared: how `--versus-retroarch` checks that a compile changed the speed, not the picture.
Result<ImageMetrics> compare_on_8bit_display(const Image& test, const Image& reference);

}  // namespace crtforge
