// Golden reference images: which ones exist (the plan), their manifest, how they are regenerated
// (only by `crtforge golden update`, from the CPU reference renderer — never from a driver under
// test) and how a render is judged against one.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

// Explicit per comparison. A render passes when all hold.
struct Tolerance {
    double max_rmse = 0;               // over all RGB samples
    // The per-pixel limit: a pixel is an outlier when its largest channel error exceeds this plus
    // the golden's own variation around it (max |difference| to its 8 neighbours: what a
    // sub-pixel shift of the sampling, another driver's rounding at a discontinuity, can move it).
    double outlier_threshold = 0;
    double max_outlier_fraction = 0;   // ... and at most this fraction of pixels may be outliers
    double min_ssim = 0;               // luma SSIM
    // RMS over every 16x16 tile of the per-pixel error beyond its edge allowance: one wrong row or
    // patch cannot hide in a mean.
    double max_tile_rmse = 0;
    std::string why;                   // the justification, kept in the manifest
};

// The bound every golden gets unless golden/plan.toml gives it another (its `why` has the figures).
Tolerance default_tolerance();

// One reference frame: a preset's scene over a generated input, shown on a display of width x
// height, at one frame of the sequence (time = frame / the scene's fps; a scene with feedback or
// history runs every frame before it).
struct GoldenEntry {
    std::string id;        // "<preset>.<input>.<w>x<h>[.<fit>].f<frame>" — also the file stem
    std::string preset, input;
    int width = 0, height = 0;              // the display
    int input_width = 0, input_height = 0;  // the input (the source)
    std::optional<DisplayFit> fit;          // how the screen fits the display; default: the preset's
    int frame = 0;
    // Stored goldens are files in the golden directory (see `hdr`). Large ones are not committed:
    // `validate` renders them with the reference when it needs them and checks the result still
    // hashes to `hash` (the pixels of `golden update` as the file would keep them), so a change of
    // the oracle shows.
    bool stored = true;
    std::string hash;
    // What the golden was made of (golden_inputs_hash at `golden update`): a golden whose inputs
    // changed since is stale, and validate fails it rather than trust it.
    std::string inputs_hash;
    Tolerance tolerance;
    // A golden whose reference leaves 0..1 (HDR inputs, bloom) is stored as half-float OpenEXR and
    // compared unclamped; the others as 16-bit PNG.
    bool hdr = false;
    // Made by `crtforge golden approve` from a render the user reviewed (a stage of their own,
    // which the reference has no model of), not by the reference.
    bool approved = false;
    // Pixels where the reference itself flips under a sub-pixel jitter of its sample points and a
    // tiny gain on the input (a discontinuity exactly at the sample: a mask cell edge on a pixel
    // centre, a quantiser threshold on an input value). There a driver's rounding may land on
    // either side, so the judge allows each one what the jitter moved it: <id>.unstable.png
    // (8-bit grey, rounded up), written when there is any.
    int unstable = 0;
    // The id of an entry with the same reference image (same preset, input, sizes, fit, frame,
    // param values and time: the variant options and the host change only what is judged) whose
    // files this one shares; empty when it owns its files.
    std::string shares;
    std::string unstable_file() const { return (shares.empty() ? id : shares) + ".unstable.png"; }
    // The configuration beyond the preset as it ships (the scene matrix, golden/plan.toml). The
    // reference follows overrides and start_time; uniforms and precision only change the variant
    // the targets compile, so their goldens are the reference of the same math.
    std::string config;                      // its tag in the id; empty: the preset as it ships
    std::map<std::string, Value> overrides;  // runtime param values the host sets
    UniformSelection uniforms;               // the variant's --uniforms
    Precision precision = Precision::High;   // the variant's --precision
    double start_time = 0.0;                 // seconds at frame 0; frame n shows start_time + n / fps
    bool full_matrix = false;                // only in the full matrix (validate --matrix full)
    std::vector<std::string> targets;        // only these targets judge it (empty: every target)
    // A known, tracked defect of the product on some targets: there a failing check is reported as
    // an expected failure (with this reason) and a passing one fails ("remove expect_fail").
    // How the host uses the target's files (SceneRenderRequest::host): "" its ready scene, one of
    // Godot's "defaults", "material", "screen", or a web framework adapter: "three", "pixi", "babylon".
    std::string host;
    std::vector<std::string> expect_fail_targets;
    std::string expect_fail_why;
    Tolerance expect_fail_bound;  // the defect's own measured size: worse than this still fails
    bool expected_to_fail(const std::string& target) const;
    std::string file() const { return (shares.empty() ? id : shares) + (hdr ? ".exr" : ".png"); }
    // Entries of one sequence render together: same preset, input, sizes, fit and configuration.
    std::string sequence() const;
    // The variant options its targets compile with.
    VariantOptions variant_options() const { return {uniforms, precision}; }
    // Whether `target` judges it.
    bool judged_by(const std::string& target) const;
};

// The id of an entry from its fields: "<preset>.<input>.<w>x<h>[.<fit>][.<config>].f<frame>".
std::string golden_id(const GoldenEntry& entry);

// An entry with its id and the default tolerance.
GoldenEntry make_golden_entry(const std::string& preset, const std::string& input, int width, int height,
                              int input_width, int input_height, int frame, std::optional<DisplayFit> fit = {});

// Adds a golden directory's stage-isolation presets (<dir>/stages/*.toml) to the library as test
// presets; the plan's `presets = "stages"` renders them. Call it right after loading the library.
Status add_golden_presets(TemplateLibrary& library, const std::string& golden_dir);

// The goldens a golden directory plans: <dir>/plan.toml (see golden/plan.toml) expanded over the
// library's presets, in preset order, then plan order. Errors name plan.toml's line and field.
Result<std::vector<GoldenEntry>> golden_plan(const TemplateLibrary& library, const std::string& golden_dir);

Result<std::vector<GoldenEntry>> load_golden_manifest(const std::string& dir);

// A hash of everything a golden follows from: the preset as resolved (scene, LUTs, passes, every
// stage's form and values), the specs and snippets of its stages, the prelude, the input, sizes and
// frame, and the oracle's own code (reference_source_hash).
Result<std::string> golden_inputs_hash(const TemplateLibrary& library, const GoldenEntry& entry);

// Renders the plan's references on the CPU and writes <dir>/<id>.png (16-bit) or .exr (half, where
// the reference leaves 0..1) + manifest.json.
// Only entries whose id contains `filter` (empty = all) are re-rendered; the manifest always lists
// the whole plan. Returns the number of images written.
// Entries whose preset uses a stage the reference has no model of are not rendered: an approved
// golden of theirs whose inputs are unchanged is kept, the others are listed in `unmodelled`.
struct GoldenUpdate {
    size_t written = 0;  // images rendered and written
    size_t planned = 0;  // entries in the plan (and the manifest)
    std::vector<std::string> unmodelled;  // ids that need `crtforge golden approve`
    std::string unmodelled_reason;        // the first of them's reason
};
Result<GoldenUpdate> update_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter);

// `crtforge golden approve`: renders the planned entries whose id contains `filter` (at least one
// must) with the SPIR-V on Vulkan (`vulkan`: lavapipe by default) and stores them as goldens marked
// approved in the manifest, for a user who has looked at them: the path for stages the reference
// has no model of. validate then judges every target against them and against this run's Vulkan
// render of the same SPIR-V (cross-target agreement). Returns the number written.
Result<GoldenUpdate> approve_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter,
                                     const EngineOptions& vulkan = {});

// Writes <dir>/manifest.json for `entries` (the plan, each with its hash, inputs hash, format and
// origin as they stand).
Status write_golden_manifest(const std::string& dir, const std::vector<GoldenEntry>& entries);

// The plan with each entry's stored state (hash, inputs hash, format, origin) from the existing
// manifest, where it has the entry.
Result<std::vector<GoldenEntry>> golden_plan_with_state(const TemplateLibrary& library, const std::string& dir);

// What a golden's file keeps of an image (16-bit codes of 0..1, or half floats where the image
// leaves 0..1): sets entry.hdr, quantises `image` and sets entry.hash.
void store_golden_pixels(GoldenEntry& entry, Image& image);

// The hash recorded for a golden image: of its pixels as its file stores them (16-bit codes of
// 0..1 for PNG, half floats for EXR).
std::string golden_hash(const Image& image, bool hdr = false);

// Fails a golden whose inputs changed since it was made ("stale: run crtforge golden update").
Status check_golden_current(const TemplateLibrary& library, const GoldenEntry& entry, const std::string& dir);

// An entry's golden image (after check_golden_current): read from the directory, or (not stored) rendered by the reference and
// checked against the entry's hash. `rendered` is the reference image when the caller has it.
Result<Image> load_golden_image(const TemplateLibrary& library, const GoldenEntry& entry, const std::string& dir);

// Renders one sequence's reference images (CPU, double precision), clamped to 0..1 like a display:
// the entries must share GoldenEntry::sequence(); the images come in their order.
Result<std::vector<Image>> render_golden_references(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence);
Result<Image> render_golden_reference(const TemplateLibrary& library, const GoldenEntry& entry);

// The generated input of an entry at a frame of its sequence.
Result<Image> golden_input(const GoldenEntry& entry, int frame);

// The request that renders one sequence (entries sharing GoldenEntry::sequence()) on a target:
// its display, fit, frames, param values, start time and host mode; `passes` compiled with the
// entries' variant options, `outputs` the target's files of them (null for spirv).
SceneRenderRequest golden_scene_request(const std::vector<const GoldenEntry*>& sequence, const Preset& preset,
                                        const std::vector<CompiledVariant>& passes, TargetId target,
                                        const std::vector<TargetOutput>* outputs = nullptr);

// Entries grouped by sequence, in first-appearance order.
std::vector<std::vector<const GoldenEntry*>> golden_sequences(const std::vector<const GoldenEntry*>& entries);

struct Verdict {
    bool passed = false;
    ImageMetrics metrics;
    double outlier_fraction = 0;   // pixels over the per-pixel limit (plus their edge allowance)
    double max_tile_rmse = 0;      // the worst 16x16 tile's RMS error beyond the edge allowance
    double flat_max = 0;           // the largest error where the golden is locally flat (no edge nearby)
    double alpha_outlier_fraction = 0;  // pixels whose alpha is off by more than 0.01 plus the golden's 3x3 alpha variation
    std::string reason;  // empty when passed; otherwise which bound failed, with numbers
};

// Compared unclamped (HDR goldens are floats); with an `output_quantum` (a display that clamps)
// both are clamped to 0..1 first. Alpha (a transparent bezel) is judged too, pixel by pixel, except
// with an `output_quantum`: a display composites alpha away. `output_quantum` is the
// step of the consumer's displayed values when it stores them coarser than half floats (Godot 3's
// 8-bit display: 1/255, truncated): the per-pixel limit grows by one step and the RMSE and tile
// limits by its RMS (step / sqrt(3) for truncation).
// `unstable` (optional, the golden's size): a per-pixel allowance (red channel) added where the
// reference flips under jitter (GoldenEntry::unstable).
// `t` for a render whose linear samples of 8-bit textures come back in whole steps of `step`
// (TargetRenderer::filtered_8bit_step): each such sample is off by up to half a step, RMS
// step / sqrt(12), which the RMSE and tile RMSE bounds gain (their why says so); 0: `t` itself.
Tolerance with_filter_step(Tolerance t, double step);

Result<Verdict> judge(const Image& render, const Image& golden, const Tolerance& tolerance, double output_quantum = 0,
                      const Image* unstable = nullptr);

// An entry's unstable-pixel allowance (GoldenEntry::unstable), or an empty image when it has none.
Result<Image> load_golden_unstable(const GoldenEntry& entry, const std::string& dir);

// The reference's own flips under jitter for one sequence (see GoldenEntry::unstable): per frame,
// an allowance image (red = green = blue = the largest change, 0 where below the noise).
Result<std::vector<Image>> render_golden_unstable(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence,
                                                  const std::vector<Image>& references);

}  // namespace crtforge
