#include "runtime/common/pixel_conversion.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

namespace crtforge::vulkan {

float half_to_float(uint16_t half) {
    const uint32_t sign = (half & 0x8000u) << 16;
    const uint32_t exponent = (half >> 10) & 0x1fu;
    const uint32_t mantissa = half & 0x3ffu;
    if (exponent == 0) {
        // Zero or subnormal: mantissa * 2^-24, exactly representable as a float.
        const float magnitude = std::ldexp(static_cast<float>(mantissa), -24);
        return sign ? -magnitude : magnitude;
    }
    if (exponent == 0x1f) return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));  // inf / NaN
    // Normal: rebias the exponent from 15 to 127.
    return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

uint16_t float_to_half(float value) {
    const uint32_t bits = std::bit_cast<uint32_t>(value);
    const uint16_t sign = static_cast<uint16_t>((bits >> 16) & 0x8000u);
    const uint32_t magnitude = bits & 0x7fffffffu;

    if (magnitude > 0x7f800000u) return sign | 0x7e00u;  // NaN stays a (quiet) NaN
    if (magnitude >= 0x477ff000u) return sign | 0x7c00u; // >= 65520 rounds to infinity
    if (magnitude >= 0x38800000u) {
        // Normal half: keep 10 mantissa bits, round the dropped 13 to nearest even. A carry out of
        // the mantissa correctly bumps the exponent.
        uint32_t half = ((magnitude >> 23) - 112u) << 10 | ((magnitude >> 13) & 0x3ffu);
        const uint32_t dropped = magnitude & 0x1fffu;
        if (dropped > 0x1000u || (dropped == 0x1000u && (half & 1u))) ++half;
        return static_cast<uint16_t>(sign | half);
    }
    // Subnormal half (or zero): value / 2^-24, rounded to nearest even.
    const uint32_t exponent = magnitude >> 23;
    if (exponent < 102) return sign;  // below 2^-25: rounds to zero
    const uint32_t full = (magnitude & 0x7fffffu) | 0x800000u;
    const uint32_t shift = 126u - exponent;  // 14..24
    uint32_t half = full >> shift;
    const uint32_t dropped = full & ((1u << shift) - 1u), midpoint = 1u << (shift - 1u);
    if (dropped > midpoint || (dropped == midpoint && (half & 1u))) ++half;
    return static_cast<uint16_t>(sign | half);
}

float srgb_to_linear(float encoded) {
    const double c = encoded;
    const double linear = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    return static_cast<float>(linear);
}

size_t texel_bytes(TextureTexels texels) {
    switch (texels) {
        case TextureTexels::Rgba32Float: return 16;
        case TextureTexels::Rgba16Float: return 8;
        case TextureTexels::Rgba8Unorm: return 4;
    }
    return 16;
}

size_t texel_bytes(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm:
        case OutputFormat::Rgba8Srgb:
        case OutputFormat::Rgb10A2Unorm:
        case OutputFormat::Rg16Float: return 4;
        case OutputFormat::Rgba16Float: return 8;
        case OutputFormat::Rgba32Float: return 16;
        case OutputFormat::R16Float: return 2;
    }
    return 16;
}

namespace {

// `channels` half floats a texel; the channels a format lacks read as 0 (colour) and 1 (alpha).
void read_halves(const unsigned char* in, size_t texels, size_t channels, float* out) {
    for (size_t t = 0; t < texels; ++t) {
        for (size_t c = 0; c < 4; ++c) {
            uint16_t half = 0;
            if (c < channels) std::memcpy(&half, in + (t * channels + c) * sizeof half, sizeof half);
            out[t * 4 + c] = c < channels ? half_to_float(half) : c == 3 ? 1.0f : 0.0f;
        }
    }
}

}  // namespace

void write_texels(const Image& image, TextureTexels texels, void* dst) {
    if (texels == TextureTexels::Rgba32Float) {
        std::memcpy(dst, image.rgba.data(), image.rgba.size() * sizeof(float));
        return;
    }
    auto* out = static_cast<unsigned char*>(dst);
    if (texels == TextureTexels::Rgba8Unorm) {
        for (size_t i = 0; i < image.rgba.size(); ++i) {
            const float v = image.rgba[i];  // NaN goes to 0
            out[i] = static_cast<unsigned char>(v > 0.0f ? std::lround(std::min(v, 1.0f) * 255.0f) : 0);
        }
        return;
    }
    for (size_t i = 0; i < image.rgba.size(); ++i) {
        const uint16_t half = float_to_half(image.rgba[i]);
        std::memcpy(out + i * sizeof half, &half, sizeof half);  // dst may not be 2-byte aligned in theory
    }
}

Image read_texels(const void* src, int width, int height, OutputFormat format) {
    Image image = Image::make(width, height);
    const auto* in = static_cast<const unsigned char*>(src);
    const size_t count = image.rgba.size();
    switch (format) {
        case OutputFormat::Rgba8Unorm:
            for (size_t i = 0; i < count; ++i) image.rgba[i] = static_cast<float>(in[i]) / 255.0f;
            break;
        case OutputFormat::Rgba8Srgb: {
            // The hardware encoded R, G and B on store; alpha is always stored linear.
            static const std::array<float, 256> decoded = [] {
                std::array<float, 256> table{};
                for (size_t b = 0; b < 256; ++b) table[b] = srgb_to_linear(static_cast<float>(b) / 255.0f);
                return table;
            }();
            for (size_t i = 0; i < count; ++i) {
                image.rgba[i] = (i % 4 == 3) ? static_cast<float>(in[i]) / 255.0f : decoded[in[i]];
            }
            break;
        }
        case OutputFormat::Rgba16Float: read_halves(in, count / 4, 4, image.rgba.data()); break;
        case OutputFormat::R16Float: read_halves(in, count / 4, 1, image.rgba.data()); break;
        case OutputFormat::Rg16Float: read_halves(in, count / 4, 2, image.rgba.data()); break;
        case OutputFormat::Rgba32Float: std::memcpy(image.rgba.data(), in, count * sizeof(float)); break;
        case OutputFormat::Rgb10A2Unorm:
            // Little-endian 32-bit words: red in bits 0-9, green 10-19, blue 20-29, alpha 30-31
            // (Vulkan's A2B10G10R10_UNORM_PACK32, GL's UNSIGNED_INT_2_10_10_10_REV, WebGPU's rgb10a2unorm).
            for (size_t t = 0; t < count / 4; ++t) {
                uint32_t word = 0;
                std::memcpy(&word, in + t * sizeof word, sizeof word);
                for (int c = 0; c < 3; ++c) image.rgba[t * 4 + c] = static_cast<float>((word >> (10 * c)) & 0x3ffu) / 1023.0f;
                image.rgba[t * 4 + 3] = static_cast<float>(word >> 30) / 3.0f;
            }
            break;
    }
    return image;
}

}  // namespace crtforge::vulkan
