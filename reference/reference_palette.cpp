// Colour palette reduction (Retro CRT Effects, shaders/post/palette.frag), from the article's
// listing: its Bayer matrix as written, its gl_FragCoord (rows counted from the bottom).
#include "reference/reference_stages.hpp"

namespace crtforge::reference {

namespace {

// The article's `const mat4 bayer = mat4(...)`, in the order written: column-major, so
// bayer[x][y] is entry 4 * x + y.
constexpr double kBayer[16] = {0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0};

double bayer(const Fragment& f) {
    // ivec2(mod(gl_FragCoord.xy, 4.0)) in OpenGL, whose gl_FragCoord has its origin at the bottom-left.
    const int x = static_cast<int>(glsl_mod(std::floor(f.pixel.x), 4.0));
    const int y = static_cast<int>(glsl_mod(std::floor(f.output_size.y - f.pixel.y), 4.0));
    return kBayer[4 * x + y] / 16.0;
}

Vec3 dither(const Params& p, const Fragment& f, Vec3 color, double levels) {
    if (!p.flag("paletteDither")) return color;
    const double d = (bayer(f) - 0.5) / levels;
    return {color.r + d, color.g + d, color.b + d};
}

bool palette(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    const double levels = p.num("paletteSize") / 4.0;  // "Rough approximation"
    color = dither(p, f, color, levels);
    if (form == "levels") {
        auto q = [&](double c) { return std::floor(c * levels + 0.5) / levels; };
        color = {q(color.r), q(color.g), q(color.b)};
        return true;
    }
    if (form == "nearest") {
        // The first palette texel at the smallest squared RGB distance.
        const Sampler& palette = f.texture("palette");
        double best_distance = 0;
        Vec3 best{};
        for (int i = 0; i < palette.width(); ++i) {
            const Rgba t = palette.texel(i, 0);
            const double dr = t[0] - color.r, dg = t[1] - color.g, db = t[2] - color.b;
            const double distance = dr * dr + dg * dg + db * db;
            if (i == 0 || distance < best_distance) {
                best_distance = distance;
                best = {t[0], t[1], t[2]};
            }
        }
        color = best;
        return true;
    }
    return false;
}

}  // namespace

std::vector<StageModel> palette_stage_models() { return {{"palette", nullptr, nullptr, nullptr, palette, nullptr}}; }

}  // namespace crtforge::reference
