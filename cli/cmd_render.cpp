// crtforge render --preset P [--target T] --input FILE|NAME|PATTERN --output FILE|PATTERN
//                [--size WxH] [--fit stretch|aspect|integer] [--frame N | --frames A:B]
#include <unistd.h>

#include <filesystem>

#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "cli/heartbeat.hpp"
#include "reference/reference_work.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/parse_number.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/scene.hpp"
#include "crtforge/validate/target_render.hpp"

namespace crtforge::cli {

Result<std::optional<DisplayFit>> parse_fit(const std::string& text) {
    if (text.empty()) return std::optional<DisplayFit>{};
    for (DisplayFit f : {DisplayFit::Stretch, DisplayFit::Aspect, DisplayFit::Integer})
        if (text == display_fit_name(f)) return std::optional<DisplayFit>{f};
    return make_error("'" + text + "' must be stretch, aspect or integer", {}, 0, "--fit");
}

Result<std::pair<int, int>> parse_size(const std::string& text) {
    const auto size = parse_int_pair(text, 'x', 'X');
    if (!size || size->first < 1 || size->second < 1 || size->first > kMaxImageDimension || size->second > kMaxImageDimension)
        return make_error(fmt::format("'{}' must be WIDTHxHEIGHT, each 1..{} (e.g. 640x480)", text, kMaxImageDimension), {}, 0,
                          "--size");
    if (const std::string over = render_budget_error(static_cast<int>(size->first), static_cast<int>(size->second)); !over.empty())
        return make_error("'" + text + "' " + over, {}, 0, "--size");
    return std::make_pair(static_cast<int>(size->first), static_cast<int>(size->second));
}

namespace {

// Runs of at least this many frames show their progress.
constexpr size_t kProgressFrames = 30;

// "%d" or "%0Nd" (one of them) in a file name: a sequence, one file per frame.
struct Pattern {
    std::string before, after;
    int width = 0;  // zero-padded digits (0: as many as needed)
    std::string at(int frame) const {
        std::string digits = std::to_string(frame);
        if (static_cast<int>(digits.size()) < width) digits.insert(0, static_cast<size_t>(width) - digits.size(), '0');
        return before + digits + after;
    }
};

std::optional<Pattern> parse_pattern(const std::string& text) {
    const size_t at = text.find('%');
    if (at == std::string::npos) return std::nullopt;
    size_t i = at + 1;
    int width = 0;
    if (i < text.size() && text[i] == '0') {
        ++i;
        while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && width < 100) width = width * 10 + (text[i++] - '0');
    }
    if (i >= text.size() || text[i] != 'd' || text.find('%', i) != std::string::npos) return std::nullopt;
    return Pattern{text.substr(0, at), text.substr(i + 1), width};
}

// An input picture within the source budget (kMaxSourcePixels): a render holds many copies of
// pictures its source's size, so a 4096x4096 input reached 2 GB whatever the display.
Result<Image> read_input(const std::string& path) {
    auto image = read_image(path);
    if (!image.ok()) return image.error();
    if (const std::string over = source_budget_error(image.value().width, image.value().height); !over.empty())
        return make_error(fmt::format("the input picture {}x{} {} (a render holds many copies of its source): scale it down first",
                                      image.value().width, image.value().height, over),
                          path, 0, "--input");
    return image;
}

// The input at each frame. A generated input's size: the scene's source size when it states one,
// else an NES frame for pixel art and 640x480 for the others.
Result<std::function<Result<Image>(int)>> input_source(const std::string& spec, const Preset* preset) {
    std::error_code ec;
    if (auto pattern = parse_pattern(spec); pattern && !std::filesystem::exists(spec, ec)) {
        const Pattern p = *pattern;
        return std::function<Result<Image>(int)>([p](int frame) -> Result<Image> {
            const std::string path = p.at(frame);
            std::error_code e;
            if (!std::filesystem::exists(path, e))
                return make_error("the input sequence has no frame " + std::to_string(frame), path, 0, "--input");
            return read_input(path);
        });
    }
    if (std::filesystem::exists(spec, ec)) {
        auto image = read_input(spec);
        if (!image.ok()) return image.error();
        Image still = std::move(image.value());
        return std::function<Result<Image>(int)>([still](int) -> Result<Image> { return still; });
    }
    const auto& names = test_input_names();
    if (std::find(names.begin(), names.end(), spec) != names.end()) {
        int w = 640, h = 480;
        if (spec == "pixel_art" || spec == "moving_sprite") std::tie(w, h) = std::make_pair(kPixelArtWidth, kPixelArtHeight);
        if (preset && preset->scene.source_width) std::tie(w, h) = std::make_pair(preset->scene.source_width, preset->scene.source_height);
        return std::function<Result<Image>(int)>([spec, w, h](int frame) { return make_test_input(spec, w, h, frame); });
    }
    return make_error("'" + spec + "' is neither an image file, a sequence (name_%03d.png) nor a generated input (" +
                          join_list(names) + ")",
                      {}, 0, "--input");
}

struct RenderArgs {
    std::string preset, tier, target = "spirv", input, output, size, device, frames, fit, display = "rgba16f";
    int frame = 0, supersample = 1, frame_count_base = 0;
    bool reference = false;
    VariantFlags flags;
};

Status write_output(const std::string& path, const Image& image) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".exr") return write_exr(path, image);
    if (ext == ".png") return write_png(path, image, 8);
    return make_error("output must end in .png or .exr", path, 0, "--output");
}

// "A:B" (inclusive, A <= B) or a single frame.
Result<std::vector<int>> parse_frames(const std::string& text) {
    const auto range = parse_int_pair(text, ':');
    const int64_t a = range ? range->first : -1, b = range ? range->second : -1;
    if (!range || a < 0 || b < a || b > 1000000 || b - a >= 10000)
        return make_error("'" + text + "' must be A:B with 0 <= A <= B <= 1000000 and at most 10000 frames", {}, 0, "--frames");
    std::vector<int> frames;
    for (int64_t f = a; f <= b; ++f) frames.push_back(static_cast<int>(f));
    return frames;
}

// The display and every pass's framebuffer within the render budget (kMaxRenderPixels), checked
// before anything is drawn: a display taken from a large input, or a pass scaled past the display,
// would otherwise hold several pictures of that size (a 4096x4096 input at its own size: 2 GB).
Status check_render_budget(const Preset& preset, PixelSize source, PixelSize display, std::optional<DisplayFit> fit, bool from_input) {
    if (const std::string over = render_budget_error(display.width, display.height); !over.empty())
        return make_error(fmt::format("the display {}x{} {}{}", display.width, display.height, over,
                                      from_input ? " (it is the input's size: give a smaller --size)" : ""),
                          {}, 0, from_input ? "--input" : "--size");
    const PixelRect screen = screen_rect(preset, display, source, fit);
    const std::vector<PixelSize> sizes = pass_sizes(preset, source, {screen.width, screen.height});
    for (size_t i = 0; i < sizes.size() && i < preset.passes.size(); ++i)
        if (const std::string over = render_budget_error(sizes[i].width, sizes[i].height); !over.empty())
            return make_error(fmt::format("pass '{}' would render {}x{} for a {}x{} display: it {}", preset.passes[i].alias, sizes[i].width,
                                          sizes[i].height, display.width, display.height, over),
                              preset.passes[i].where.file, preset.passes[i].where.line, "pass." + preset.passes[i].alias + ".scale");
    return Ok{};
}

}  // namespace

Runner add_render_command(CLI::App& app, const GlobalOptions& g) {
    auto a = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand("render", "Render a preset's scene through one target's consumer onto an image or a sequence");
    cmd->add_option("--preset", a->preset, "Preset name, or a RetroArch .slangp file (imported first)")->required();
    cmd->add_option("--tier", a->tier, "Render this quality tier of the preset (see generate --tier)");
    cmd->add_option("--target", a->target, "Target whose consumer renders it")->capture_default_str();
    cmd->add_option("--input", a->input,
                    "An image file (any format OpenImageIO reads), a sequence of them (in_%03d.png: frame N reads in_00N.png) "
                    "or a generated input name (moving_sprite moves)")
        ->required();
    cmd->add_option("--output", a->output, "Output image (.png, or .exr to keep HDR); with --frames a pattern such as out_%03d.png")
        ->required();
    cmd->add_option("--size", a->size, "Display size WIDTHxHEIGHT (default: the input's size)");
    cmd->add_option("--fit", a->fit, "How the screen fits the display: stretch, aspect or integer (default: the preset's)");
    auto* frame = cmd->add_option("--frame", a->frame, "Frame number; time = frame / the scene's fps")->check(CLI::Range(0, 1000000));
    cmd->add_option("--frames", a->frames, "Frames A:B (inclusive): one output file each")->excludes(frame);
    cmd->add_option("--frame-count-base", a->frame_count_base, "frameCount at frame 0 (RetroArch's Vulkan driver starts at 1); not with --reference")
        ->check(CLI::Range(0, 1000000));
    cmd->add_option("--display", a->display,
                    "The display's format: rgba16f (values kept as drawn; a NaN is an error when written) or rgba8 (an 8-bit "
                    "display such as RetroArch's: values clamp to 0..1, a NaN shows as 0); not with --reference")
        ->check(CLI::IsMember({"rgba16f", "rgba8"}))
        ->capture_default_str();
    cmd->add_option("--device", a->device, "Vulkan device name or index (default: lavapipe)");
    cmd->add_flag("--reference", a->reference, "Render with the CPU double-precision reference instead");
    cmd->add_option("--supersample", a->supersample,
                    "With --reference: N x N samples per display pixel, box-filtered (the aliasing-free reference)")
        ->check(CLI::Range(1, 16));
    a->flags.add_to(*cmd);
    return [&g, a]() {
        int code = kExitOk;
        auto target_found = lookup_target(a->target);
        if (!target_found.ok()) return report(target_found.error());
        const TargetInfo* target = target_found.value();
        auto options = a->flags.parse();
        if (!options.ok()) return report(options.error());
        std::vector<int> frames{a->frame};
        if (!a->frames.empty()) {
            auto parsed = parse_frames(a->frames);
            if (!parsed.ok()) return report(parsed.error());
            frames = parsed.value();
        }
        const auto pattern = parse_pattern(a->output);
        if (!a->frames.empty() && !pattern)
            return report(make_error("with --frames the output names each frame: put %d (or %04d) in it", a->output, 0, "--output"));
        auto fit = parse_fit(a->fit);
        if (!fit.ok()) return report(fit.error());
        std::optional<std::pair<int, int>> size;
        if (!a->size.empty()) {
            auto parsed = parse_size(a->size);
            if (!parsed.ok()) return report(parsed.error());
            size = parsed.value();
        }
        std::vector<std::string> named{a->preset};
        auto lib = load_library(g, code, &named);
        if (!lib) return code;
        auto preset_found = lookup_preset(*lib, named.front());
        if (!preset_found.ok()) return report(preset_found.error());
        const Preset* preset = preset_found.value();
        std::optional<PresetTier> tier;
        if (!a->tier.empty()) {
            auto found = find_tier(*preset, a->tier);
            if (!found.ok()) return report(found.error());
            tier = std::move(found.value());
            preset = &tier->preset;
        }
        auto source = input_source(a->input, preset);
        if (!source.ok()) return report(source.error());
        int w = size ? size->first : 0, h = size ? size->second : 0;
        PixelSize source_size;  // the first frame's, read once here (the work count reuses it)
        {
            // The first frame only says the display size (and that it loads); not kept, so a large
            // picture is not held once more through the render.
            auto first = source.value()(frames.front());
            if (!first.ok()) return report(first.error());
            source_size = {first.value().width, first.value().height};
            if (!size) std::tie(w, h) = std::make_pair(source_size.width, source_size.height);
            if (auto s = check_render_budget(*preset, source_size, {w, h}, fit.value(), !size); !s.ok())
                return report(s.error());
        }
        auto luts = read_file_luts(*preset);
        if (!luts.ok()) return report(luts.error());
        const std::map<std::string, SharedImage>& file_luts = luts.value();
        Cache cache = make_cache(g);

        if (a->supersample != 1 && !a->reference) return report(make_error("needs --reference", {}, 0, "--supersample"));
        if (a->frame_count_base != 0 && a->reference)
            return report(make_error("the reference counts frames from 0", {}, 0, "--frame-count-base"));
        if (a->display != "rgba16f" && a->reference)
            return report(make_error("the reference draws in double precision, not onto a display format", {}, 0, "--display"));
        // The scene as the reference would render it; its work is counted for every target, since
        // the GPU runs the stages' loops as the reference does (a driver's watchdog would cut one
        // of billions of steps short without a word).
        ReferenceSceneJob job;
        job.library = lib.get();
        job.preset = preset;
        job.source = source.value();
        job.width = w;
        job.height = h;
        job.fit = fit.value();
        job.frames = frames;
        job.file_luts = file_luts;
        job.supersample = a->supersample;
        if (auto s = reference::check_reference_work(job, source_size); !s.ok()) return report(s.error());
        Result<std::vector<Image>> images = make_error("not rendered");
        if (a->reference) {
            // The reference reports no progress of its own; a render of many samples, or of a
            // preset whose params ask for much work per pixel, takes minutes.
            Heartbeat heartbeat(fmt::format("render --reference {}x{}", w, h));
            images = render_reference_scene(job);
        } else {
            auto compiled = compile_scene(*lib, *preset, options.value(), cache);
            if (!compiled.ok()) return report(compiled.error());
            auto outputs = emit_scene(compiled.value(), target->id, cache);
            if (!outputs.ok()) return report(outputs.error());
            TargetRenderer renderer(EngineOptions{a->device, false});
            SceneRenderRequest r;
            r.preset = preset;
            r.passes = &compiled.value();
            r.target = target->id;
            r.outputs = &outputs.value();
            r.source = source.value();
            r.width = w;
            r.height = h;
            r.fit = fit.value();
            r.frames = frames;
            r.file_luts = file_luts;
            r.frame_count_base = a->frame_count_base;
            r.format = a->display == "rgba8" ? OutputFormat::Rgba8Unorm : OutputFormat::Rgba16Float;
            // A long run (--frame 500 of a preset that keeps state draws every frame before it):
            // a bar on a terminal, a line per 10 % in a log.
            const bool tty = ::isatty(STDOUT_FILENO);
            r.on_frame = [tty](size_t done, size_t total) {
                if (total >= kProgressFrames) report_progress(tty, done, total, "render", fmt::format("frame {}/{}", done, total), 10);
            };
            Heartbeat heartbeat(fmt::format("render {}x{} on {}", w, h, target->name));
            images = renderer.render_scene(r);
        }
        if (!images.ok()) return report(images.error());
        // Every file goes to its temporary name first: a failure part-way leaves none behind.
        for (size_t i = 0; i < frames.size(); ++i) {
            const std::string path = pattern ? pattern->at(frames[i]) : a->output;
            if (auto s = write_output(path, images.value()[i]); !s.ok()) {
                for (size_t k = 0; k < i; ++k) {
                    std::error_code ec;
                    std::filesystem::remove(pattern ? pattern->at(frames[k]) : a->output, ec);
                }
                return report(s.error());
            }
        }
        const std::string where = pattern ? pattern->at(frames.front()) + (frames.size() > 1 ? " .. " + pattern->at(frames.back()) : "")
                                          : a->output;
        fmt::print("{}: {} via {} at {}x{}, frame{} {}\n", where, preset->name, a->reference ? "reference" : target->name, w, h,
                   frames.size() > 1 ? "s" : "", frames.size() > 1 ? fmt::format("{}:{}", frames.front(), frames.back())
                                                                  : std::to_string(frames.front()));
        return kExitOk;
    };
}

}  // namespace crtforge::cli
