// Texture sampling as a Vulkan sampler does it: normalised coordinates, texel centres at +0.5,
// clamp-to-edge addressing, nearest or bilinear filtering — evaluated in double precision.
#pragma once

#include <array>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "reference/reference_math.hpp"

namespace crtforge::reference {

using Rgba = std::array<double, 4>;

class Sampler {
public:
    Sampler(const Image& image, SamplerFilter filter) : image_(image), filter_(filter) {}
    Rgba sample(Vec2 uv) const;
    Vec3 rgb(Vec2 uv) const {
        const Rgba c = sample(uv);
        return {c[0], c[1], c[2]};
    }

private:
    Rgba texel(int x, int y) const;  // clamped to the edge
    const Image& image_;
    SamplerFilter filter_;
};

}  // namespace crtforge::reference
