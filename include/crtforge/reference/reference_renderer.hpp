// The oracle for goldens: a CPU renderer in double precision that evaluates every stage from its
// documented formula (not from the GLSL), with Vulkan's sampling rules (texel centres at +0.5,
// clamp-to-edge / repeat / mirrored-repeat, nearest or bilinear), and runs a scene's passes the way
// the scene model defines them. It shares no code with the drivers under test, nor with the
// pipeline hosts in validate/.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/scene.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

struct ReferenceTexture {
    Image image;
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
};

// One pass.
struct ReferenceJob {
    const Variant* variant = nullptr;        // the pass: stages, forms and values
    std::map<std::string, Value> overrides;  // param values replacing the variant's (e.g. uniforms)
    Image input;                             // the pass's main input ("source")
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    std::map<std::string, ReferenceTexture> textures;  // every other texture the pass reads, by name
    int width = 0, height = 0;
    double time = 0.0;                       // seconds
    long long frame_count = 0;               // already reduced by the pass's frame_count_mod
    // Moves every pixel's sample point by this many pixels: a discontinuity that falls exactly on
    // a pixel centre shows as a change (golden update's jittered renders).
    std::array<double, 2> jitter{0.0, 0.0};
    // Moves every texture read by this many texels on both axes: a computed sample point exactly
    // on a texel edge (a warped mask-cell centre under nearest filtering) shows as a change.
    double texel_jitter = 0.0;
    // Samples per pixel side: 1 is the point-sampled reference (what a perfect fp32 shader gives:
    // its distance measures arithmetic error); n > 1 box-filters n x n samples over each pixel's
    // footprint (its distance also measures aliasing: mask and scanline moire). 1..16.
    int supersample = 1;
    // Rows to shade, as [first, end) ranges; every other row stays transparent black. Empty: all.
    // (A benchmark measures the error of a 4K frame on evenly spaced bands of rows.)
    std::vector<std::pair<int, int>> rows;
};

// Renders one pass's math. A stage or form the reference has no model for is an error, never a
// silently wrong image.
Result<Image> render_reference(const ReferenceJob& job);

// A scene over a sequence of frames: every pass in order each frame, each pass's output stored in
// its format (8-bit, sRGB or half) before the next pass reads it, feedback from the previous
// frame's outputs (black before the first), the original's history (black before it exists), the
// LUTs, and the last pass drawn into the screen's rectangle of a width x height display over
// opaque black.
struct ReferenceSceneJob {
    const TemplateLibrary* library = nullptr;
    const Preset* preset = nullptr;
    std::map<std::string, Value> overrides;               // param -> value, in every pass that reads it
    std::function<Result<Image>(int frame)> source;       // the original at each frame
    int width = 0, height = 0;                            // the display
    std::optional<DisplayFit> fit;                        // default: the preset's
    std::vector<int> frames;                              // the frames whose display image is returned
    std::map<std::string, SharedImage> file_luts;         // images of the preset's file LUTs, by name
    double start_time = 0.0;                              // seconds at frame 0 (frame n: + n / fps)
    // Perturbations that find the pixels where the math is discontinuous exactly at the sample
    // (a mask cell edge on a pixel centre, a quantiser threshold on an input value): every pass's
    // sample points move by `jitter` pixels and the original's RGB is scaled by `input_gain`.
    std::array<double, 2> jitter{0.0, 0.0};
    double texel_jitter = 0.0;  // ReferenceJob::texel_jitter, for every pass
    double input_gain = 1.0;
    int supersample = 1;        // ReferenceJob::supersample, for every pass (each the anti-aliased picture of its inputs)
    // Display rows to render of the last pass in the last frame, [first, end) ranges (the rest of
    // the display black); every earlier pass and frame is rendered whole. Empty: all.
    std::vector<std::pair<int, int>> display_rows;
};

// The jittered renders that tell a discontinuity exactly at a sample (a mask cell edge on a pixel
// centre, a palette tie on a texel edge) from an error: sample points move by kJitterPixels (of the
// order of fp32's rounding of a pixel position near 1000, ulp 6e-5), texture reads by
// kJitterTexels (fp32's rounding of a coordinate computed through a dozen operations: a warped
// mask-cell centre) and the original's RGB by a factor 1 + kJitterGain (a few times fp32's
// relative step). Larger would also flag a quantiser's near-ties, which every driver rounds alike.
inline constexpr double kJitterPixels = 1.0 / 16384.0;
inline constexpr double kJitterTexels = 1.0 / 4096.0;
inline constexpr double kJitterGain = 1.0 / 1048576.0;

// `job` with every perturbation above applied in direction `sign` (+1 or -1), the sample points
// moved by `sign` across and `sign_y` down (a sample on a corner of four texels needs both
// diagonals to meet each of them). Texture reads move along the diagonal only, so an anti-diagonal
// render moves its sample points alone (the reads follow them, by kJitterPixels over the scale).
inline ReferenceSceneJob jittered(ReferenceSceneJob job, double sign, double sign_y) {
    job.jitter = {sign * kJitterPixels, sign_y * kJitterPixels};
    job.texel_jitter = sign == sign_y ? sign * kJitterTexels : 0.0;
    job.input_gain = 1.0 + sign * kJitterGain;
    return job;
}

// Test-only: injects a fault into the oracle, to prove that validate notices a wrong reference
// (tests/mutations.toml): "scale:<param>:<factor>" (the param reads scaled), "skip:<stage>" (the
// stage is left out), "sampler-shift:<texels>" (every texture read moves right); "" removes it.
// Process-wide; set it only while nothing renders.
Status set_reference_fault(const std::string& fault);

// The content hash of the code goldens come from (the reference renderer, the test inputs, the LUT
// generators, the scene geometry), fixed at build time: part of every golden's inputs hash.
const char* reference_source_hash();

// Whether the oracle has a model of every stage form the preset uses; the error names the first
// it lacks (a user's own stage: validate it against goldens approved with `crtforge golden approve`).
Status reference_models(const Preset& preset);

// A scene's last pass in its last frame with every input it read, as the scene resolved them:
// render_display_pass() draws that pass again, perturbed, without the passes and frames before it
// (a benchmark's tie check of a six-pass scene at 4K: one pass of one frame instead of twelve).
struct ReferenceDisplayPass {
    Variant variant;                     // the pass
    ReferenceJob job;                    // its inputs, unperturbed (job.variant is set on use)
    std::vector<std::string> originals;  // the inputs that are the frame's original ("source": the main one)
    PixelRect screen;                    // where it lies on the display
    int display_width = 0, display_height = 0;
};

// The display images of job.frames, in that order. Frames before the last kept one are rendered
// too when the scene keeps state between frames (feedback, history); otherwise only the kept ones.
// Given `display_pass`, the last pass of the last frame is kept there as well.
Result<std::vector<Image>> render_reference_scene(const ReferenceSceneJob& job, ReferenceDisplayPass* display_pass = nullptr);

// The display image of `pass` under `perturbation`'s jitter, texel jitter, input gain (on the
// inputs that are the original), supersampling and display rows; its other fields are not read.
// Earlier passes keep their unperturbed pictures: only a discontinuity at this pass's own sample
// points shows.
Result<Image> render_display_pass(const ReferenceDisplayPass& pass, const ReferenceSceneJob& perturbation);

}  // namespace crtforge
