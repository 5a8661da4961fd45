// Job checks that do not depend on the graphics API: the Vulkan, GL and Dawn engines refuse a bad
// size, a malformed image, a viewport outside the target, a non-finite clear colour or two
// resources at one binding the same way, before any driver call.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge::detail {

// An input error about one field of the job ("job.<field>").
Diagnostic job_error(std::string message, const std::string& field);

const char* output_format_name(OutputFormat format);
const char* wrap_mode_name(WrapMode wrap);

struct JobLimits {
    int max_width = 0, max_height = 0;  // output extent the device can render
    int max_input = 0;                  // largest input texture side
    std::string device;                 // named in messages
    const char* input_limit_name = "";  // the API's name for max_input, e.g. "GL_MAX_TEXTURE_SIZE"
    // The DevicePicture::owner() of pictures this engine kept on its device and can sample; null
    // where it keeps none (every such picture is then refused).
    const void* device_pictures = nullptr;
};

// Output size within 1..limit on both axes; the input image consistent and within max_input.
Status check_job_extent(int width, int height, const Image& input, const JobLimits& limits);

// An image to sample: consistent (or kept on this engine's device) and within max_input (and
// kMaxImageDimension). `what` names it
// in the message ("input image", "texture 'lut'"), `field` in the Diagnostic.
Status check_texture_image(const Image& image, const JobLimits& limits, const std::string& what,
                           const std::string& field);

// The image of each of `textures` (within max_input and kMaxImageDimension), with fields
// "textures[i].image".
Status check_texture_images(const std::vector<TextureInput>& textures, const JobLimits& limits);

// The full 0x0 default, or a rectangle with positive sides inside the width x height target.
Status check_viewport(const Viewport& viewport, int width, int height);

Status check_clear_color(const std::array<float, 4>& color);

// One resource a job puts at a binding; the field names it in errors.
struct BindingUse {
    uint32_t number = 0;
    std::string field;  // e.g. "texture_binding", "textures[1].binding"
};

// No two uses share a number; the later one of a clashing pair is reported, naming the earlier.
Status check_distinct_bindings(const std::vector<BindingUse>& uses);

// "textures[i].<member>", the field of one extra texture's member.
std::string texture_field(std::size_t index, const char* member);

// A job's frame numbers as a runner's argument: "1,3,9".
std::string frame_list(const std::vector<int>& frames);

}  // namespace crtforge::detail
