#include "runtime/common/job_checks.hpp"

#include <fmt/format.h>

namespace crtforge::detail {

Diagnostic job_error(std::string message, const char* field) {
    return make_error(std::move(message), {}, 0, fmt::format("job.{}", field));
}

const char* output_format_name(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm: return "Rgba8Unorm";
        case OutputFormat::Rgba8Srgb: return "Rgba8Srgb";
        case OutputFormat::Rgba16Float: return "Rgba16Float";
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
    if (!input.consistent() || input.width < 0 || input.height < 0)
        return job_error(fmt::format("input image is {}x{} but holds {} floats (expected width * height * 4)",
                                     input.width, input.height, input.rgba.size()),
                         "input");
    if (input.width > limits.max_input || input.height > limits.max_input)
        return job_error(fmt::format("input image {}x{} exceeds {} of {}", input.width, input.height,
                                     limits.input_limit_name, limits.max_input),
                         "input");
    return Ok{};
}

}  // namespace crtforge::detail
