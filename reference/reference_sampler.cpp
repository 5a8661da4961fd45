#include "reference/reference_sampler.hpp"

namespace crtforge::reference {

Rgba Sampler::texel(int x, int y) const {
    x = std::clamp(x, 0, image_.width - 1);
    y = std::clamp(y, 0, image_.height - 1);
    const float* p = image_.rgba.data() + (static_cast<size_t>(y) * image_.width + x) * 4;
    return {p[0], p[1], p[2], p[3]};
}

Rgba Sampler::sample(Vec2 uv) const {
    const double u = uv.x * image_.width, v = uv.y * image_.height;
    if (filter_ == SamplerFilter::Nearest)
        return texel(static_cast<int>(std::floor(u)), static_cast<int>(std::floor(v)));
    // Bilinear between the four texel centres around (u, v).
    const double x = u - 0.5, y = v - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
    const Rgba a = texel(ix, iy), b = texel(ix + 1, iy), c = texel(ix, iy + 1), d = texel(ix + 1, iy + 1);
    Rgba out{};
    for (int i = 0; i < 4; ++i)
        out[i] = (a[i] * (1 - fx) + b[i] * fx) * (1 - fy) + (c[i] * (1 - fx) + d[i] * fx) * fy;
    return out;
}

}  // namespace crtforge::reference
