// Golden reference images: which ones exist (the plan), their manifest, how they are regenerated
// (only by `crtforge golden update`, from the CPU reference renderer — never from a driver under
// test) and how a render is judged against one.
#pragma once

#include <string>
#include <vector>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/template_library.hpp"

namespace crtforge {

// Explicit per comparison. A render passes when all hold.
struct Tolerance {
    double max_rmse = 0;               // over all RGB samples
    double outlier_threshold = 0;      // a pixel is an outlier when its max channel diff exceeds this
    double max_outlier_fraction = 0;   // ... and at most this fraction of pixels may be outliers
    double min_ssim = 0;               // luma SSIM
    std::string why;                   // the justification, kept in the manifest
};

struct GoldenEntry {
    std::string id;        // "<preset>.<input>.<w>x<h>.f<frame>" — also the file stem
    std::string preset, input;
    int width = 0, height = 0;
    int input_width = 0, input_height = 0;
    int frame = 0;         // time = frame / 60 s
    Tolerance tolerance;
    std::string file() const { return id + ".png"; }
};

// An entry with its id ("<preset>.<input>.<w>x<h>.f<frame>") and the default tolerance.
GoldenEntry make_golden_entry(const std::string& preset, const std::string& input, int width, int height,
                              int input_width, int input_height, int frame);

// The goldens a golden directory plans: <dir>/plan.toml (see golden/plan.toml) expanded over the
// library's presets, in preset order, then plan order. Errors name plan.toml's line and field.
Result<std::vector<GoldenEntry>> golden_plan(const TemplateLibrary& library, const std::string& golden_dir);

Result<std::vector<GoldenEntry>> load_golden_manifest(const std::string& dir);

// Renders the plan's references on the CPU and writes <dir>/<id>.png (16-bit) + manifest.json.
// Only entries whose id contains `filter` (empty = all) are re-rendered; the manifest always lists
// the whole plan. Returns the number of images written.
struct GoldenUpdate {
    size_t written = 0;  // images rendered and written
    size_t planned = 0;  // entries in the plan (and the manifest)
};
Result<GoldenUpdate> update_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter);

// Renders one entry's reference image (CPU, double precision), clamped to 0..1 like a display.
Result<Image> render_golden_reference(const TemplateLibrary& library, const GoldenEntry& entry);

// The generated input of an entry.
Result<Image> golden_input(const GoldenEntry& entry);

struct Verdict {
    bool passed = false;
    ImageMetrics metrics;
    double outlier_fraction = 0;
    std::string reason;  // empty when passed; otherwise which bound failed, with numbers
};

// `render` is clamped to 0..1 first (the golden is what a display shows).
Result<Verdict> judge(const Image& render, const Image& golden, const Tolerance& tolerance);

}  // namespace crtforge
