// Scene geometry: screen rectangle, source mapping, pass sizes (see crtforge/scene.hpp).
#include "crtforge/scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "crtforge/runtime/image.hpp"

namespace crtforge {

namespace {

double picture_aspect(const SceneSettings& s, PixelSize source) {
    return static_cast<double>(source.width) * s.pixel_aspect_x / (static_cast<double>(source.height) * s.pixel_aspect_y);
}

double screen_aspect(const SceneSettings& s, PixelSize source) {
    if (s.screen_aspect_x) return static_cast<double>(s.screen_aspect_x) / s.screen_aspect_y;
    return picture_aspect(s, source);
}

PixelRect centred(PixelSize display, int width, int height) {
    width = std::clamp(width, 1, display.width);
    height = std::clamp(height, 1, display.height);
    return {(display.width - width) / 2, (display.height - height) / 2, width, height};
}

}  // namespace

PixelRect screen_rect(const Preset& preset, PixelSize display, PixelSize source, std::optional<DisplayFit> fit_override) {
    const SceneSettings& s = preset.scene;
    const DisplayFit fit = fit_override.value_or(s.fit);
    if (fit == DisplayFit::Stretch || source.width <= 0 || source.height <= 0) return {0, 0, display.width, display.height};
    const double aspect = screen_aspect(s, source);
    if (fit == DisplayFit::Integer) {
        const int rows = display.height / source.height;
        for (int k = rows; k >= 1; --k) {
            const int height = k * source.height, width = static_cast<int>(std::lround(height * aspect));
            if (width <= display.width) return centred(display, width, height);
        }
    }
    // The largest rectangle of that aspect: full width, or full height.
    if (display.width >= display.height * aspect)
        return centred(display, static_cast<int>(std::lround(display.height * aspect)), display.height);
    return centred(display, display.width, static_cast<int>(std::lround(display.width / aspect)));
}

std::array<double, 2> source_uv_scale(const Preset& preset) {
    const SceneSettings& s = preset.scene;
    if (s.source_fit == SourceFit::Stretch || !s.source_width) return {1.0, 1.0};
    const PixelSize source{s.source_width, s.source_height};
    const double picture = picture_aspect(s, source), screen = screen_aspect(s, source);
    // Width: the picture spans the screen's width, so a screen row shows picture / screen of its height.
    const double width_fit = picture / screen, height_fit = screen / picture;
    switch (s.source_fit) {
        case SourceFit::Width: return {1.0, width_fit};
        case SourceFit::Height: return {height_fit, 1.0};
        case SourceFit::Contain: return picture >= screen ? std::array<double, 2>{1.0, width_fit} : std::array<double, 2>{height_fit, 1.0};
        case SourceFit::Stretch: break;
    }
    return {1.0, 1.0};
}

size_t screen_pass_index(const Preset& preset) {
    for (size_t i = 0; i < preset.passes.size(); ++i)
        if (preset.passes[i].scale_x.type == PassScale::Type::Viewport && preset.passes[i].scale_y.type == PassScale::Type::Viewport)
            return i;
    return preset.passes.size() - 1;
}

std::vector<PixelSize> pass_sizes(const Preset& preset, PixelSize source, PixelSize screen) {
    std::vector<PixelSize> sizes;
    auto input_size = [&](const Pass& pass) -> PixelSize {
        const TextureSource& from = pass.inputs.front().from;
        if (from.kind == TextureSource::Kind::Pass || from.kind == TextureSource::Kind::Feedback)
            for (size_t i = 0; i < sizes.size(); ++i)
                if (preset.passes[i].alias == from.name) return sizes[i];
        return source;  // the original (or a LUT: a source-relative scale of it is unusual)
    };
    auto axis = [](const PassScale& s, int input, int viewport) {
        const double base = s.type == PassScale::Type::Source ? input : s.type == PassScale::Type::Viewport ? viewport : 1.0;
        return std::clamp(static_cast<int>(std::lround(base * s.factor)), 1, kMaxSceneDimension);
    };
    for (const Pass& pass : preset.passes) {
        const PixelSize in = input_size(pass);
        sizes.push_back({axis(pass.scale_x, in.width, screen.width), axis(pass.scale_y, in.height, screen.height)});
    }
    // The last pass draws the screen, whatever its scale says (as RetroArch's last pass does).
    if (!sizes.empty()) sizes.back() = {std::max(screen.width, 1), std::max(screen.height, 1)};
    return sizes;
}

Status check_pass_sizes(const Preset& preset, const std::vector<PixelSize>& sizes, PixelSize screen) {
    for (size_t i = 0; i < sizes.size() && i < preset.passes.size(); ++i) {
        const std::string over = image_budget_error(sizes[i].width, sizes[i].height);
        if (over.empty()) continue;
        const Pass& pass = preset.passes[i];
        return make_error("pass '" + pass.alias + "' would render " + std::to_string(sizes[i].width) + "x" + std::to_string(sizes[i].height) +
                              " for a " + std::to_string(screen.width) + "x" + std::to_string(screen.height) + " screen: it " + over,
                          pass.where.file, pass.where.line, "pass." + pass.alias + ".scale");
    }
    return Ok{};
}

}  // namespace crtforge
