// Golden reference images: which ones exist (the plan), their manifest, how they are regenerated
// (only by `crtforge golden update`, from the CPU reference renderer — never from a driver under
// test) and how a render is judged against one.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/template_library.hpp"

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
    std::string file() const { return id + (hdr ? ".exr" : ".png"); }
    // Entries of one sequence render together: same preset, input, sizes and fit.
    std::string sequence() const;
};

// An entry with its id and the default tolerance.
GoldenEntry make_golden_entry(const std::string& preset, const std::string& input, int width, int height,
                              int input_width, int input_height, int frame, std::optional<DisplayFit> fit = {});

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
struct GoldenUpdate {
    size_t written = 0;  // images rendered and written
    size_t planned = 0;  // entries in the plan (and the manifest)
};
Result<GoldenUpdate> update_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter);

// The hash recorded for a golden image: of its pixels as its file stores them (16-bit codes of
// 0..1 for PNG, half floats for EXR).
std::string golden_hash(const Image& image, bool hdr = false);

// An entry's golden image: read from the directory, or (not stored) rendered by the reference and
// checked against the entry's hash. `rendered` is the reference image when the caller has it.
Result<Image> load_golden_image(const TemplateLibrary& library, const GoldenEntry& entry, const std::string& dir);

// Renders one sequence's reference images (CPU, double precision), clamped to 0..1 like a display:
// the entries must share GoldenEntry::sequence(); the images come in their order.
Result<std::vector<Image>> render_golden_references(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence);
Result<Image> render_golden_reference(const TemplateLibrary& library, const GoldenEntry& entry);

// The generated input of an entry at a frame of its sequence.
Result<Image> golden_input(const GoldenEntry& entry, int frame);

// Entries grouped by sequence, in first-appearance order.
std::vector<std::vector<const GoldenEntry*>> golden_sequences(const std::vector<const GoldenEntry*>& entries);

struct Verdict {
    bool passed = false;
    ImageMetrics metrics;
    double outlier_fraction = 0;   // pixels over the per-pixel limit (plus their edge allowance)
    double max_tile_rmse = 0;      // the worst 16x16 tile's RMS error beyond the edge allowance
    double flat_max = 0;           // the largest error where the golden is locally flat (no edge nearby)
    std::string reason;  // empty when passed; otherwise which bound failed, with numbers
};

// Compared unclamped (HDR goldens are floats); with an `output_quantum` (a display that clamps)
// both are clamped to 0..1 first. `output_quantum` is the
// step of the consumer's displayed values when it stores them coarser than half floats (Godot 3's
// 8-bit display: 1/255, truncated): the per-pixel limit grows by one step and the RMSE and tile
// limits by its RMS (step / sqrt(3) for truncation).
Result<Verdict> judge(const Image& render, const Image& golden, const Tolerance& tolerance, double output_quantum = 0);

}  // namespace crtforge
