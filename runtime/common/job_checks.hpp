// Job checks that do not depend on the graphics API: the Vulkan and the GL engine both refuse a
// bad size or a malformed input image the same way, before any driver call.
#pragma once

#include <string>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge::detail {

// An input error about one field of the job ("job.<field>").
Diagnostic job_error(std::string message, const char* field);

const char* output_format_name(OutputFormat format);

struct JobLimits {
    int max_width = 0, max_height = 0;  // output extent the device can render
    int max_input = 0;                  // largest input texture side
    std::string device;                 // named in messages
    const char* input_limit_name = "";  // the API's name for max_input, e.g. "GL_MAX_TEXTURE_SIZE"
};

// Output size within 1..limit on both axes; the input image consistent and within max_input.
Status check_job_extent(int width, int height, const Image& input, const JobLimits& limits);

}  // namespace crtforge::detail
