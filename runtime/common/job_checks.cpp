#include "runtime/common/job_checks.hpp"

#include <cmath>

#include <fmt/format.h>

namespace crtforge::detail {

Diagnostic job_error(std::string message, const std::string& field) {
    return make_error(std::move(message), {}, 0, fmt::format("job.{}", field));
}

const char* output_format_name(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm: return "Rgba8Unorm";
        case OutputFormat::Rgba8Srgb: return "Rgba8Srgb";
        case OutputFormat::Rgba16Float: return "Rgba16Float";
        case OutputFormat::Rgba32Float: return "Rgba32Float";
        case OutputFormat::Rgb10A2Unorm: return "Rgb10A2Unorm";
        case OutputFormat::R16Float: return "R16Float";
        case OutputFormat::Rg16Float: return "Rg16Float";
    }
    return "?";
}

const char* wrap_mode_name(WrapMode wrap) {
    switch (wrap) {
        case WrapMode::ClampToEdge: return "ClampToEdge";
        case WrapMode::Repeat: return "Repeat";
        case WrapMode::MirroredRepeat: return "MirroredRepeat";
        case WrapMode::ClampToBorder: return "ClampToBorder";
    }
    return "?";
}

Status check_job_extent(int width, int height, const Image& input, const JobLimits& limits) {
    for (bool horizontal : {true, false}) {
        const int size = horizontal ? width : height;
        const char* field = horizontal ? "width" : "height";
        const int limit = horizontal ? limits.max_width : limits.max_height;
        if (size <= 0 || size > limit)
            return job_error(fmt::format("output {} must be between 1 and {} (limit of '{}'); got {}", field, limit,
                                         limits.device, size),
                             field);
    }
    return check_texture_image(input, limits, "input image", "input");
}

Status check_texture_image(const Image& image, const JobLimits& limits, const std::string& what,
                           const std::string& field) {
    if (image.device) {
        if (!limits.device_pictures || image.device->owner() != limits.device_pictures)
            return job_error(fmt::format("{} is a picture another engine kept on its device: only that engine can sample it", what),
                             field);
        if (!image.rgba.empty() || image.empty())
            return job_error(fmt::format("{} is kept on the device but is {}x{} with {} floats", what, image.width, image.height,
                                         image.rgba.size()),
                             field);
    } else if (!image.consistent() || image.width < 0 || image.height < 0)
        return job_error(fmt::format("{} is {}x{} but holds {} floats (expected width * height * 4)", what,
                                     image.width, image.height, image.rgba.size()),
                         field);
    if (image.width > limits.max_input || image.height > limits.max_input)
        return job_error(fmt::format("{} {}x{} exceeds {} of {}", what, image.width, image.height,
                                     limits.input_limit_name, limits.max_input),
                         field);
    return Ok{};
}

Status check_texture_images(const std::vector<TextureInput>& textures, const JobLimits& device_limits) {
    // kMaxImageDimension bounds every image crtforge handles, whatever a device would take.
    JobLimits limits = device_limits;
    if (limits.max_input > kMaxImageDimension) {
        limits.max_input = kMaxImageDimension;
        limits.input_limit_name = "kMaxImageDimension";
    }
    for (std::size_t i = 0; i < textures.size(); ++i) {
        const std::string what = fmt::format("texture {} ('{}') image", i, textures[i].name);
        if (auto s = check_texture_image(*textures[i].image, limits, what, texture_field(i, "image")); !s.ok()) return s;
    }
    return Ok{};
}

Status check_viewport(const Viewport& viewport, int width, int height) {
    const Viewport& v = viewport;
    if (v.full()) {
        if (v.x != 0 || v.y != 0)
            return job_error(fmt::format("viewport has an offset ({}, {}) but no size (0x0 means the whole target)",
                                         v.x, v.y),
                             "viewport");
        return Ok{};
    }
    // 64-bit sums: x + width must not overflow on a hostile job.
    const int64_t right = int64_t{v.x} + v.width, bottom = int64_t{v.y} + v.height;
    if (v.width <= 0 || v.height <= 0 || v.x < 0 || v.y < 0 || right > width || bottom > height)
        return job_error(fmt::format("viewport {}x{} at ({}, {}) must have positive sides and lie inside the {}x{} "
                                     "target",
                                     v.width, v.height, v.x, v.y, width, height),
                         "viewport");
    return Ok{};
}

Status check_clear_color(const std::array<float, 4>& color) {
    for (float c : color) {
        if (!std::isfinite(c))
            return job_error(fmt::format("clear colour ({}, {}, {}, {}) is not finite", color[0], color[1], color[2],
                                         color[3]),
                             "clear_color");
    }
    return Ok{};
}

Status check_distinct_bindings(const std::vector<BindingUse>& uses) {
    for (std::size_t i = 0; i < uses.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            if (uses[i].number == uses[j].number)
                return job_error(fmt::format("binding {} of job.{} is also the binding of job.{}", uses[i].number,
                                             uses[i].field, uses[j].field),
                                 uses[i].field);
        }
    }
    return Ok{};
}

std::string texture_field(std::size_t index, const char* member) {
    return fmt::format("textures[{}].{}", index, member);
}

std::string frame_list(const std::vector<int>& frames) {
    std::string out;
    for (int f : frames) {
        if (!out.empty()) out.push_back(',');
        out.append(std::to_string(f));
    }
    return out;
}

}  // namespace crtforge::detail
