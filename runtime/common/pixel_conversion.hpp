// Texel packing for upload and unpacking for readback. Pure CPU code, independent of Vulkan, so
// the conversions can be tested on their own.
#pragma once

#include <cstddef>
#include <cstdint>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge::vulkan {

// IEEE 754 binary16 <-> binary32. half_to_float is exact for every input (subnormals, infinities,
// NaN); float_to_half rounds to nearest even and overflows to infinity, as GPUs do.
float half_to_float(uint16_t half);
uint16_t float_to_half(float value);

// The sRGB electro-optical transfer function (IEC 61966-2-1): encoded [0, 1] -> linear [0, 1].
float srgb_to_linear(float encoded);

// Texel formats the input texture can take.
enum class TextureTexels { Rgba32Float, Rgba16Float, Rgba8Unorm };  // Rgba8Unorm: round(value * 255), clamped
size_t texel_bytes(TextureTexels texels);
size_t texel_bytes(OutputFormat format);

// Writes image.rgba (row 0 first, so texture coordinate v = 0 is the top row) into `dst`, which
// holds width * height * texel_bytes(texels) bytes, tightly packed.
void write_texels(const Image& image, TextureTexels texels, void* dst);

// Reads a tightly packed width x height readback in `format` into linear floats. UNORM bytes become
// byte / 255; sRGB bytes are decoded to linear (the value the shader wrote, quantised); half floats
// are widened exactly; 10-bit channels are n / 1023 (alpha n / 3); a channel the format lacks
// reads as 0 (colour) or 1 (alpha).
Image read_texels(const void* src, int width, int height, OutputFormat format);

}  // namespace crtforge::vulkan
