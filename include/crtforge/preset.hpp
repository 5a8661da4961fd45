// Presets: a scene of one or more passes, each a list of stages with one form each and param
// values. A preset may inherit from another (base = "classic") and override;
// templates/presets/<name>.toml. docs/scenes.md describes the file format.
//
// The scene model says what a RetroArch .slangp preset says — per pass: scale type and factor per
// axis (source, viewport, absolute), framebuffer format (8-bit, sRGB, float), input filter, wrap
// mode and mipmaps, an alias, frame-count modulo; inputs by name: the original frame, earlier
// passes, the previous frame of any pass (feedback), the original's history, lookup textures —
// plus what a CRT scene needs above a shader chain: the source's size and pixel aspect, how the
// picture fits the screen and the screen the display, and the frame rate.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/spec.hpp"

namespace crtforge {

// Largest source or pass size a preset may name (the engines' largest image).
inline constexpr int kMaxSceneDimension = 16384;
// A preset's name: 1..64 of lower-case letters, digits, '-' and '_', starting with a letter or digit.
bool is_preset_name(const std::string& name);

// Deepest history of the original a pass may read (original@N).
inline constexpr int kMaxHistory = 15;

enum class Filter { Linear, Nearest };
const char* filter_name(Filter filter);

// How a texture is addressed outside 0..1.
enum class Wrap { ClampToEdge, ClampToBorder, Repeat, MirroredRepeat };
const char* wrap_name(Wrap wrap);  // clamp_to_edge, clamp_to_border, repeat, mirrored_repeat

// A pass's framebuffer: what its output is quantised to before the next pass reads it. The last
// four are RetroArch's R32G32B32A32_SFLOAT, A2B10G10R10_UNORM_PACK32 (10 bits a colour channel,
// 2 for alpha), R16_SFLOAT and R16G16_SFLOAT: a reader sees the channels a format lacks as 0
// (colour) and 1 (alpha).
enum class PixelFormat { Rgba8, Rgba8Srgb, Rgba16F, Rgba32F, Rgb10A2, R16F, Rg16F };
const char* pixel_format_name(PixelFormat format);  // rgba8, rgba8_srgb, rgba16f, rgba32f, rgb10a2, r16f, rg16f
// Whether the format stores 8 bits a channel (rgba8, rgba8_srgb): what GPUs filter in coarse steps.
inline bool stores_bytes(PixelFormat format) { return format == PixelFormat::Rgba8 || format == PixelFormat::Rgba8Srgb; }

// A pass's output size on one axis: a factor of its source (main input), of the viewport (the
// screen's rectangle in the display), or an absolute number of pixels.
struct PassScale {
    enum class Type { Source, Viewport, Absolute } type = Type::Viewport;
    double factor = 1.0;  // Absolute: pixels
};
const char* scale_type_name(PassScale::Type type);  // source, viewport, absolute

// Where a pass input comes from, written "original", "original@3" (3 frames back), "<alias>"
// (an earlier pass's output this frame), "<alias>@previous" (a pass's output of the previous
// frame: feedback) or "lut:<name>".
struct TextureSource {
    enum class Kind { Original, Pass, Feedback, Lut } kind = Kind::Original;
    std::string name;     // the pass alias (Pass, Feedback) or the LUT name
    int frames_back = 0;  // Original: 0 = this frame, N = the original of N frames ago
    std::string str() const;
};

// One texture a pass reads: its main input ("source") or a texture a stage's form declares.
struct PassInput {
    std::string binding;  // "source", or the name in the stage's `textures`
    TextureSource from;
    Filter filter = Filter::Linear;
    Wrap wrap = Wrap::ClampToEdge;
    bool mipmap = false;  // sampled through a full mip chain (docs/scenes.md)
    int line = 0;
    // With mipmap, how levels blend: linear (trilinear with a linear filter) or the nearest level.
    // Default: the filter. RetroArch blends a pass output's levels only when the reading pass's own
    // output has a chain too (`mipmap_input` of the pass after the reader): the import says so.
    Filter mip_filter = Filter::Linear;
};

// A preset's own settings for one stage, as written in its file (before inheritance).
struct PresetStageEntry {
    std::string stage;
    bool enabled = true;
    int line = 0;
    std::map<std::string, Value> values;     // param name -> value (already type-checked)
    std::map<std::string, int> value_lines;  // param name -> line in the preset file
};

// How a pass samples one of its textures, where the preset says so ({ from, filter, wrap, mipmap }):
// an imported RetroArch pass samples another pass's output as that pass's producer declares.
struct TextureSampling {
    std::optional<Filter> filter;
    std::optional<Wrap> wrap;
    std::optional<bool> mipmap;
    std::optional<Filter> mip_filter;
};

// One [[pass]] as written.
struct PassEntry {
    std::string alias;
    std::string preset;  // start from this single-pass preset's stages and filter ("" = none)
    std::vector<PresetStageEntry> stages;
    std::optional<PassScale> scale_x, scale_y;
    std::optional<PixelFormat> format;
    std::optional<std::string> input;  // the main input, as written (default: the previous pass)
    std::optional<Filter> filter;
    std::optional<Wrap> wrap;
    std::optional<bool> mipmap;
    std::optional<Filter> mip_filter;
    std::map<std::string, std::string> textures;  // binding -> source, as written
    std::map<std::string, int> texture_lines;
    std::map<std::string, TextureSampling> texture_sampling;  // binding -> as written in its inline table
    std::optional<int> frame_count_mod;
    std::optional<int> supersample;
    int line = 0;
};

// A lookup texture, generated from params ("generator") or read from an image file.
struct LutSpec {
    std::string name;
    std::string generator;                 // "yiq_grade", "atari_ntsc" (generator/luts.hpp), or ""
    std::string file;                      // with no generator: an image, relative to the preset file
    // A file LUT's bytes as the library read and checked them at load (read_lut_file), so export
    // and the golden hash do not read the file again; null for a LUT resolved outside a library.
    std::shared_ptr<const std::string> bytes;
    std::map<std::string, double> params;  // the generator's params, defaults filled in
    Filter filter = Filter::Linear;        // how passes sample it
    Wrap wrap = Wrap::ClampToEdge;
    SourceLocation where;
};

// How the picture goes onto the screen when their aspects differ.
enum class SourceFit {
    Stretch,  // fill the screen, distorting
    Width,    // fill the screen's width: crop (or bar) top and bottom (Super Win the Game)
    Height,   // fill the screen's height: crop (or bar) left and right
    Contain,  // all of the picture, bars where the aspects differ
};
// How the screen goes into the display.
enum class DisplayFit {
    Stretch,  // the whole display
    Aspect,   // the largest rectangle of the screen's aspect, centred (letterbox / pillarbox)
    Integer,  // as Aspect, with the source's rows at a whole number of display rows
};
const char* source_fit_name(SourceFit fit);
const char* display_fit_name(DisplayFit fit);

struct SceneSettings {
    int source_width = 0, source_height = 0;  // 0: the input's own size
    int pixel_aspect_x = 1, pixel_aspect_y = 1;
    SourceFit source_fit = SourceFit::Stretch;
    DisplayFit fit = DisplayFit::Stretch;
    int screen_aspect_x = 0, screen_aspect_y = 0;  // 0: the source's display aspect
    double fps = 60.0;
};

// What a derived preset's [passes.<alias>], or a tier's [tiers.<name>.passes.<alias>], changes in
// one pass of the scene it builds on.
struct PassOverride {
    std::vector<PresetStageEntry> stages;  // [...<alias>.stages.<stage>]: values set, stages turned on or off
    std::optional<double> scale;           // the pass's scale factor on both axes (its scale type kept)
    std::optional<int> supersample;        // Pass::supersample
    int line = 0;
    int scale_line = 0;
};

// [tiers.<name>]: a cheaper form of the whole scene the preset's author offers (a bloom blurred at a
// quarter of the display's size), weighed by crtforge bench and chosen by budget mode like the
// point and filtered tiers (quality_tiers.hpp).
struct TierEntry {
    std::string name, doc;
    int line = 0;
    std::map<std::string, PassOverride> passes;  // by pass alias ("main" in a single-pass preset)
};

struct PresetFile {
    std::string name;
    std::string doc;
    std::string base;                      // empty: no inheritance
    std::optional<Filter> filter;          // source texture filter; inherited when unset
    std::vector<PresetStageEntry> stages;  // in file order (single-pass presets)
    std::vector<PassEntry> passes;         // [[pass]]: this file defines the pass list
    std::map<std::string, PassOverride> pass_overrides;  // [passes.<alias>]: changes to a base's passes
    std::vector<TierEntry> tiers;                          // [tiers.<name>], in file order
    // [source], [display], [time]: each key inherited on its own.
    std::optional<int> source_width, source_height, pixel_aspect_x, pixel_aspect_y, screen_aspect_x,
        screen_aspect_y;
    std::optional<SourceFit> source_fit;
    std::optional<DisplayFit> fit;
    std::optional<double> fps;
    std::vector<LutSpec> luts;             // [lut.<name>]
    std::map<std::string, int> key_lines;  // top-level table -> line, for diagnostics
    SourceLocation where;
    int format = 2;                        // the file's layout version (1: Glitch's, migrated on load)
    std::vector<std::string> warnings;     // "file:line: warning: field 'x': ..." (migrated keys)
};

// A preset after inheritance: the enabled stages (in pass order) and every value they use.
struct ResolvedStage {
    const StageSpec* stage = nullptr;
    const FormSpec* form = nullptr;
    std::map<std::string, Value> values;   // every param the form reads, defaults filled in
};

struct Pass {
    std::string alias;                     // unique in the preset; "main" for a single-pass preset
    std::vector<ResolvedStage> stages;     // sorted by StageSpec::order
    PassScale scale_x, scale_y;
    PixelFormat format = PixelFormat::Rgba8;
    std::vector<PassInput> inputs;         // "source" first, then each texture its stages read
    int frame_count_mod = 0;               // frameCount reaches the shader modulo this (0 = as is)
    // Samples per pixel side the shader averages (1..4): the pass's whole math at n x n points of
    // each pixel, a box filter of its point-sampled picture (edges of nearest-filtered texels
    // under a palette, which no form of a single stage can filter).
    int supersample = 1;
    SourceLocation where;

    const ResolvedStage* find_stage(const std::string& name) const;
    const PassInput* find_input(const std::string& binding) const;
    // The textures the pass's enabled forms declare, in stage order, each once.
    std::vector<std::string> texture_names() const;
};

struct Preset;

// A declared tier, resolved: the whole preset with the tier's changes.
struct DeclaredTier {
    std::string name, doc;
    SourceLocation where;
    std::shared_ptr<const Preset> preset;
    std::vector<std::string> changes;  // e.g. "pass bloom_up: scale 1 -> 0.25"
};

struct Preset {
    std::string name;
    std::string doc;
    Filter filter = Filter::Linear;        // how the first pass samples the original
    std::vector<Pass> passes;              // in execution order; the last one draws the display
    SceneSettings scene;
    std::vector<LutSpec> luts;
    std::vector<std::string> lineage;      // this preset, then its bases
    SourceLocation where;
    bool test_only = false;                // a validation configuration (add_test_presets), not shipped
    std::string tier_of;                   // a declared tier as a test preset (add_tier_presets): its preset
    std::vector<DeclaredTier> tiers;       // [tiers.<name>] of the preset and its bases (a tier's own preset has none)

    bool single_pass() const { return passes.size() == 1; }
    // The first enabled stage of that name in any pass.
    const ResolvedStage* find_stage(const std::string& name) const;
    const Pass* find_pass(const std::string& alias) const;
    const LutSpec* find_lut(const std::string& name) const;
    // How many frames of the original any pass reads back (0: none), and whether any pass reads a
    // previous frame's output: what a host must keep between frames.
    int history_depth() const;
    bool has_feedback() const;
    // Feedback or history: frame n needs every frame before it run first.
    bool keeps_state() const { return has_feedback() || history_depth() > 0; }
};

}  // namespace crtforge
