// crtforge render --preset P --target T --input FILE|NAME --output FILE [--size WxH] [--frame N]
#include <filesystem>

#include <fmt/format.h>

#include "cli/cli_common.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/runtime/test_inputs.hpp"

namespace crtforge::cli {

Result<std::pair<int, int>> parse_size(const std::string& text) {
    int w = 0, h = 0, consumed = 0;
    char x = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%n", &w, &x, &h, &consumed) != 3 || (x != 'x' && x != 'X') ||
        consumed != static_cast<int>(text.size()) || w < 1 || h < 1 || w > kMaxImageDimension || h > kMaxImageDimension)
        return make_error(fmt::format("'{}' must be WIDTHxHEIGHT, each 1..{} (e.g. 640x480)", text, kMaxImageDimension), {}, 0,
                          "--size");
    return std::make_pair(w, h);
}

Result<Image> load_input(const std::string& spec) {
    std::error_code ec;
    if (std::filesystem::exists(spec, ec)) return read_image(spec);
    const auto& names = test_input_names();
    if (std::find(names.begin(), names.end(), spec) != names.end()) {
        const bool nes = spec == "pixel_art";
        return make_test_input(spec, nes ? 256 : 640, nes ? 224 : 480);
    }
    return make_error("'" + spec + "' is neither an image file nor a generated input (" + join_list(names) + ")", {}, 0, "--input");
}

namespace {

struct RenderArgs {
    std::string preset, target = "spirv", input, output, size, device;
    int frame = 0;
    bool reference = false;
    VariantFlags flags;
};

Status write_output(const std::string& path, const Image& image) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".exr") return write_exr(path, image);
    if (ext == ".png") return write_png(path, image, 8);
    return make_error("output must end in .png or .exr", path, 0, "--output");
}

}  // namespace

Runner add_render_command(CLI::App& app, const GlobalOptions& g) {
    auto a = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand("render", "Render one preset through one target's consumer onto an image");
    cmd->add_option("--preset", a->preset, "Preset name")->required();
    cmd->add_option("--target", a->target, "Target whose consumer renders it")->capture_default_str();
    cmd->add_option("--input", a->input, "An image file (any format OpenImageIO reads) or a generated input name")->required();
    cmd->add_option("--output", a->output, "Output image (.png, or .exr to keep HDR)")->required();
    cmd->add_option("--size", a->size, "Output size WIDTHxHEIGHT (default: the input's size)");
    cmd->add_option("--frame", a->frame, "Frame number; time = frame / 60 s")->check(CLI::Range(0, 1000000));
    cmd->add_option("--device", a->device, "Vulkan device name or index (default: lavapipe)");
    cmd->add_flag("--reference", a->reference, "Render with the CPU double-precision reference instead");
    a->flags.add_to(*cmd);
    return [&g, a]() {
        int code = kExitOk;
        auto target_found = lookup_target(a->target);
        if (!target_found.ok()) return report(target_found.error());
        const TargetInfo* target = target_found.value();
        auto options = a->flags.parse();
        if (!options.ok()) return report(options.error());
        auto input = load_input(a->input);
        if (!input.ok()) return report(input.error());
        int w = input.value().width, h = input.value().height;
        if (!a->size.empty()) {
            auto size = parse_size(a->size);
            if (!size.ok()) return report(size.error());
            std::tie(w, h) = size.value();
        }
        auto lib = load_library(g, code);
        if (!lib) return code;
        auto preset_found = lookup_preset(*lib, a->preset);
        if (!preset_found.ok()) return report(preset_found.error());
        const Preset* preset = preset_found.value();
        Cache cache = make_cache(g);
        auto compiled = compile_variant(*lib, *preset, options.value(), cache);
        if (!compiled.ok()) return report(compiled.error());
        const SamplerFilter filter = preset->filter == Filter::Nearest ? SamplerFilter::Nearest : SamplerFilter::Linear;
        Result<Image> image = make_error("not rendered");
        if (a->reference) {
            ReferenceJob job{&compiled.value().variant, {}, input.value(), filter, w, h, FrameInfo::time_of_frame(a->frame)};
            image = render_reference(job);
        } else {
            auto out = emit_target(compiled.value(), target->id, cache);
            if (!out.ok()) return report(out.error());
            TargetRenderer renderer(EngineOptions{a->device, false});
            TargetRenderRequest r;
            r.compiled = &compiled.value();
            r.target = target->id;
            r.output = &out.value();
            r.input = input.value();
            r.filter = filter;
            r.width = w;
            r.height = h;
            r.time = FrameInfo::time_of_frame(a->frame);
            image = renderer.render(r);
        }
        if (!image.ok()) return report(image.error());
        if (auto s = write_output(a->output, image.value()); !s.ok()) return report(s.error());
        fmt::print("{}: {} via {} at {}x{}, frame {}\n", a->output, preset->name, a->reference ? "reference" : target->name, w, h, a->frame);
        return kExitOk;
    };
}

}  // namespace crtforge::cli
