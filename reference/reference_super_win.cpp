// Super Win the Game's CRT simulation ("CRT simulation", the game's write-up), each stage as the
// spec's doc states its formula (templates/stages/*.toml), in double precision: colour grade,
// trails, edge ringing, NTSC mask, the curved screen through a perspective camera with its border
// reflection, the texel mask, the Poisson bloom blur and the squared bloom composite.
#include "reference/reference_stages.hpp"

namespace crtforge::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 mix3(Vec3 a, Vec3 b, double t) { return {mix(a.r, b.r, t), mix(a.g, b.g, t), mix(a.b, b.b, t)}; }
Vec3 max3(Vec3 a, Vec3 b) { return {std::max(a.r, b.r), std::max(a.g, b.g), std::max(a.b, b.b)}; }

// The 32^3 cube stored as 1024 x 32 (x = blue * 32 + red, y = green), trilinear.
bool color_grade(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form != "lut32") return false;
    const Sampler& lut = f.texture("grade");
    const double r = std::clamp(color.r, 0.0, 1.0) * 31.0, g = std::clamp(color.g, 0.0, 1.0) * 31.0,
                 b = std::clamp(color.b, 0.0, 1.0) * 31.0;
    const double slice = std::floor(b), next = std::min(slice + 1.0, 31.0);
    const double y = (g + 0.5) / 32.0;
    const Vec3 low = lut.rgb({(slice * 32.0 + r + 0.5) / 1024.0, y});
    const Vec3 high = lut.rgb({(next * 32.0 + r + 0.5) / 1024.0, y});
    color = mix3(color, mix3(low, high, b - slice), p.num("gradeStrength"));
    return true;
}

bool trails(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form != "persistence") return false;
    const Sampler& previous = f.texture("feedback");
    const double dx = 1.0 / f.output_size.x;
    const Vec3 left = previous.rgb({f.uv.x - dx, f.uv.y}), centre = previous.rgb(f.uv), right = previous.rgb({f.uv.x + dx, f.uv.y});
    const Vec3 tinted = (left + centre + right) * (1.0 / 3.0) * p.color("trailTint");
    color = mix3(color, max3(color, tinted), p.num("trailBlend"));
    return true;
}

bool ringing(const std::string& form, const Params& p, const Fragment& f, Vec2 uv, Vec3& color) {
    if (form != "bands") return false;
    const double centre = luma601(color);
    double ring = 0.0;
    const int taps = static_cast<int>(p.num("ringTaps"));
    for (int k = 1; k <= taps; ++k) {
        const double dx = k / f.source_size.x;
        const double side = 0.5 * (luma601(f.source->rgb({uv.x - dx, uv.y})) + luma601(f.source->rgb({uv.x + dx, uv.y})));
        ring += (k % 2 == 1 ? 1.0 : -1.0) / k * (side - centre);
    }
    color = color * std::max(1.0 + p.num("ringStrength") * ring, 0.0);
    return true;
}

bool ntsc_mask(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    const long long phase = static_cast<long long>(std::floor(f.pixel.x)) + static_cast<long long>(std::floor(f.pixel.y));
    auto cycle = [](long long i) { return one_hot(static_cast<int>(((i % 3) + 3) % 3)) * 3.0; };
    Vec3 mask;
    if (form == "alternate") mask = cycle(phase + f.frame_count % 2);
    else if (form == "blend") mask = (cycle(phase) + cycle(phase + 1)) * 0.5;
    else return false;
    const double k = p.num("ntscStrength");
    color = color * Vec3{mix(1.0, mask.r, k), mix(1.0, mask.g, k), mix(1.0, mask.b, k)};
    return true;
}

// The glass: a sphere cap of radius 1 / curvature touching z = 0 at the centre, bulging toward a
// camera at (0, 0, -D); the nearer intersection of the ray through the flat screen point.
bool screen_perspective(const std::string& form, const Params& p, const Fragment& f, Vec2& uv) {
    if (form != "perspective") return false;
    const double aspect = f.output_size.x / f.output_size.y;
    const double zoom = p.num("screenZoom"), distance = p.num("cameraDistance"), curvature = p.num("screenCurvature");
    const Vec2 flat{(uv.x * 2.0 - 1.0) * aspect / zoom, (uv.y * 2.0 - 1.0) / zoom};
    Vec2 hit = flat;
    if (curvature > 0.0) {
        const double radius = 1.0 / curvature;
        // Ray o + t d with o = (0, 0, -D), d = (flat, D); sphere centre (0, 0, R).
        const double a = flat.x * flat.x + flat.y * flat.y + distance * distance;
        const double b = distance * (-distance - radius);
        const double c = (distance + radius) * (distance + radius) - radius * radius;
        const double disc = b * b - a * c;
        if (disc < 0.0) {
            uv = {-10.0, -10.0};
            return true;
        }
        const double t = c / (-b + std::sqrt(disc));
        hit = flat * t;
    }
    uv = {hit.x / aspect * 0.5 + 0.5, hit.y * 0.5 + 0.5};
    return true;
}

bool screen_border(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form != "perspective") return false;
    const Vec2 uv = f.uv;
    const Vec2 over{std::max(-uv.x, uv.x - 1.0), std::max(-uv.y, uv.y - 1.0)};
    const double distance = std::max(over.x, over.y);
    if (distance <= 0.0) return true;
    const double strength = p.num("reflectionStrength"), width = p.num("reflectionWidth");
    if (strength <= 0.0 || distance >= width) {
        color = p.color("borderColor");
        return true;
    }
    // Mirror each axis that is outside across its nearer edge.
    auto mirror = [](double t, double o) { return o > 0.0 ? (t < 0.5 ? -t : 2.0 - t) : t; };
    const Vec2 mirrored{mirror(uv.x, over.x), mirror(uv.y, over.y)};
    const Vec3 picture = f.source->rgb(f.source_uv(mirrored));
    const double along = over.y > over.x ? std::min(uv.x, 1.0 - uv.x) : std::min(uv.y, 1.0 - uv.y);
    const double taper = smoothstep(0.0, p.num("reflectionTaper"), along);
    const double fade = 1.0 - distance / width;
    color = p.color("borderColor") + picture * (strength * fade * taper);
    return true;
}

// The mask's coordinate in source texels at a (warped) screen coordinate.
Vec2 texel_mask_coord(const Params& p, const Fragment& f, Vec2 uv) {
    Vec2 c = uv * 2.0 - Vec2{1, 1};
    c = c * (1.0 + p.num("maskPincushion") * dot(c, c));
    const Vec2 texel = f.source_uv(c * 0.5 + Vec2{0.5, 0.5});
    return {texel.x * f.source_size.x, texel.y * f.source_size.y};
}

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(kPi * x) / (kPi * x); }

bool texel_mask(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    const Vec2 t = texel_mask_coord(p, f, f.uv);
    const double fx = fract(t.x), fy = fract(t.y);
    double mask = 0.0;
    if (form == "pincushion") {
        const double sx = std::sin(fx * kPi), sy = std::sin(fy * kPi);
        const double rows = 1.0 - p.num("maskScanline") * (1.0 - sy * sy);
        const double columns = 1.0 - p.num("maskColumn") * (1.0 - sx * sx);
        mask = rows * columns;
    } else if (form == "pincushion_filtered") {
        // The coordinate's change over one pixel across (a, c) and down (b, d), through the warp;
        // the mask (1 - S - S cos 2 pi t.y)(1 - C - C cos 2 pi t.x) averaged over the pixel's square
        // with t linear across it.
        const Vec2 across{0.5 / f.output_size.x, 0.0}, down{0.0, 0.5 / f.output_size.y};
        auto at = [&](Vec2 screen) { return texel_mask_coord(p, f, f.warp(screen)); };
        const Vec2 dx = at(f.screen_uv + across) - at(f.screen_uv - across);
        const Vec2 dy = at(f.screen_uv + down) - at(f.screen_uv - down);
        const double a = dx.x, b = dy.x, c = dx.y, d = dy.y;
        const double columns = std::cos(2 * kPi * fx) * sinc(a) * sinc(b);
        const double rows = std::cos(2 * kPi * fy) * sinc(c) * sinc(d);
        const double both = 0.5 * (std::cos(2 * kPi * (fx + fy)) * sinc(a + c) * sinc(b + d) +
                                   std::cos(2 * kPi * (fx - fy)) * sinc(a - c) * sinc(b - d));
        const double s = 0.5 * p.num("maskScanline"), k = 0.5 * p.num("maskColumn");
        mask = (1 - s) * (1 - k) - s * (1 - k) * rows - k * (1 - s) * columns + s * k * both;
    } else {
        return false;
    }
    color = color * (p.num("maskGain") * mask);
    return true;
}

// The centre and 12 taps of the Poisson-disk set the spec names.
Vec3 poisson_disk(const Params& p, const Fragment& f, Vec2 uv, Vec3 centre) {
    static const Vec2 disk[12] = {{0.3137, -0.3266}, {-0.8880, 0.3373}, {0.6626, 0.3968},  {-0.2229, -0.2067},
                                  {0.4765, -0.8205}, {-0.2606, 0.7713}, {-0.2568, -0.7517}, {0.2967, 0.1267},
                                  {-0.9739, -0.4774}, {-0.2619, 0.2653}, {0.8322, -0.0817},  {0.2822, 0.7673}};
    const double radius = p.num("blurRadius");
    Vec3 sum = centre;
    for (const Vec2& tap : disk)
        sum = sum + f.source->rgb({uv.x + tap.x * radius / f.output_size.x, uv.y + tap.y * radius / f.output_size.y});
    return sum * (1.0 / 13.0);
}

bool poisson_blur(const std::string& form, const Params& p, const Fragment& f, Vec2 uv, Vec3& color) {
    if (form == "poisson") {
        color = poisson_disk(p, f, uv, color);
        return true;
    }
    if (form != "poisson_filtered") return false;
    // A pass that shrinks its source: the blur at 4 x 4 points of the output pixel's square.
    if (f.source_size.x <= f.output_size.x && f.source_size.y <= f.output_size.y) {
        color = poisson_disk(p, f, uv, color);
        return true;
    }
    Vec3 sum{};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec2 at{uv.x + (i - 1.5) / 4.0 / f.output_size.x, uv.y + (j - 1.5) / 4.0 / f.output_size.y};
            sum = sum + poisson_disk(p, f, at, f.source->rgb(at));
        }
    color = sum * (1.0 / 16.0);
    return true;
}

bool bloom_add(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form != "squared") return false;
    const Vec3 glow = f.texture("bloom").rgb(f.uv);
    color = color + glow * glow * p.num("bloomGain");
    return true;
}

}  // namespace

std::vector<StageModel> super_win_stage_models() {
    return {
        {"color_grade", nullptr, nullptr, nullptr, color_grade, nullptr},
        {"trails", nullptr, nullptr, nullptr, trails, nullptr},
        {"ringing", nullptr, nullptr, ringing, nullptr, nullptr},
        {"ntsc_mask", nullptr, nullptr, nullptr, ntsc_mask, nullptr},
        {"crt_screen", screen_perspective, nullptr, nullptr, nullptr, screen_border},
        {"texel_mask", nullptr, nullptr, nullptr, texel_mask, nullptr},
        {"poisson_blur", nullptr, nullptr, poisson_blur, nullptr, nullptr},
        {"bloom_add", nullptr, nullptr, nullptr, bloom_add, nullptr},
    };
}

}  // namespace crtforge::reference
