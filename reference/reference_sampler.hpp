// Texture sampling as a Vulkan sampler does it: normalised coordinates, texel centres at +0.5,
// clamp-to-edge, repeat or mirrored-repeat addressing, nearest or bilinear filtering — evaluated in
// double precision.
#pragma once

#include <array>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "reference/reference_math.hpp"

namespace crtforge::reference {

using Rgba = std::array<double, 4>;

class Sampler {
public:
    Sampler(const Image& image, SamplerFilter filter, WrapMode wrap = WrapMode::ClampToEdge, double shift = 0.0)
        : image_(image), filter_(filter), wrap_(wrap), shift_(shift) {}
    Rgba sample(Vec2 uv) const;
    Vec3 rgb(Vec2 uv) const {
        const Rgba c = sample(uv);
        return {c[0], c[1], c[2]};
    }
    // texelFetch: the texel at integer coordinates (addressed like the sampler's wrap).
    Rgba texel(int x, int y) const;
    int width() const { return image_.width; }
    int height() const { return image_.height; }

private:
    const Image& image_;
    SamplerFilter filter_;
    WrapMode wrap_;
    double shift_;  // texels added to every read's position on both axes (ReferenceJob::texel_jitter)
};

}  // namespace crtforge::reference
