#include "reference/reference_sampler.hpp"
#include "reference/reference_stages.hpp"

namespace crtforge::reference {

namespace {

// The texel index an out-of-range coordinate addresses (Vulkan's wrapping rules).
int address(int i, int size, WrapMode wrap) {
    switch (wrap) {
        case WrapMode::ClampToEdge: return std::clamp(i, 0, size - 1);
        case WrapMode::Repeat: return ((i % size) + size) % size;
        case WrapMode::MirroredRepeat: {
            const int period = 2 * size;
            const int m = ((i % period) + period) % period;
            return m < size ? m : period - 1 - m;
        }
        case WrapMode::ClampToBorder: return i < 0 || i >= size ? -1 : i;  // -1: the border
    }
    return std::clamp(i, 0, size - 1);
}

}  // namespace

Rgba Sampler::texel(int x, int y) const {
    x = address(x, image_.width, wrap_);
    y = address(y, image_.height, wrap_);
    if (x < 0 || y < 0) return {0, 0, 0, 0};  // clamp_to_border: transparent black
    const float* p = image_.rgba.data() + (static_cast<size_t>(y) * image_.width + x) * 4;
    return {p[0], p[1], p[2], p[3]};
}

Rgba Sampler::sample(Vec2 uv) const {
    // Far outside 0..1 (or not finite) every wrap mode has long since settled: keep the texel
    // arithmetic inside int.
    auto tame = [](double t) { return std::isfinite(t) ? std::clamp(t, -1e8, 1e8) : 0.0; };
    const double u = tame(uv.x * image_.width + reference_fault().sampler_shift + shift_), v = tame(uv.y * image_.height + shift_);
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
